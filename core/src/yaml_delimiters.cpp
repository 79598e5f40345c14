// Finds the bracket or quote a YAML text left open (unclosed_delimiter).
#include "yaml_delimiters.hpp"

#include <vector>

namespace wysiwyf::detail {

std::optional<UnclosedDelimiter> unclosed_delimiter(const std::string& text) {
  std::vector<UnclosedDelimiter> open;  // brackets, innermost last
  int line = 1, column = 0;
  char quote = 0;
  UnclosedDelimiter quote_at{};
  char previous = '\n';  // the last character outside a quoted scalar that is not a space
  bool line_start = true;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '\n') {
      ++line;
      column = 0;
      line_start = true;
      if (!quote) previous = '\n';
      continue;
    }
    ++column;
    if (quote) {
      if (quote == '"' && c == '\\') {
        ++i;  // (an escaped character: \" does not close)
        ++column;
      } else if (c == quote) {
        if (quote == '\'' && i + 1 < text.size() && text[i + 1] == '\'') {
          ++i;  // ('' is a quote inside a single-quoted scalar)
          ++column;
        } else {
          quote = 0;
          previous = c;
        }
      }
      continue;
    }
    if (c == ' ' || c == '\t' || c == '\r') continue;
    const bool token_start = line_start || previous == ':' || previous == '-' || previous == '[' || previous == '{' ||
                             previous == ',' || previous == '?' || previous == '\n';
    const bool after_space = i == 0 || text[i - 1] == ' ' || text[i - 1] == '\t' || text[i - 1] == '\n';
    line_start = false;
    if (c == '#' && after_space) {  // a comment: to the end of the line
      while (i + 1 < text.size() && text[i + 1] != '\n') ++i;
      continue;
    }
    const bool in_flow = !open.empty();
    if ((c == '"' || c == '\'') && token_start) {
      quote = c;
      quote_at = {c, line, column};
      continue;
    }
    if ((c == '[' || c == '{') && (token_start || in_flow)) {
      open.push_back({c, line, column});
    } else if ((c == ']' || c == '}') && in_flow) {
      const char expected = open.back().open == '[' ? ']' : '}';
      if (c != expected) {
        UnclosedDelimiter wrong = open.back();
        wrong.found = c;
        wrong.found_line = line;
        wrong.found_column = column;
        return wrong;
      }
      open.pop_back();
    }
    previous = c;
  }
  if (quote) return quote_at;
  if (!open.empty()) return open.back();
  return std::nullopt;
}

}  // namespace wysiwyf::detail
