#pragma once
// Where a YAML text's unclosed bracket or quote began: yaml-cpp reports where it noticed the
// missing end (often lines later), or, for a quote left open, nothing at all.
#include <optional>
#include <string>

namespace wysiwyf::detail {

struct UnclosedDelimiter {
  char open;         // '{', '[', '"' or '\''
  int line, column;  // 1-based, where it opened
  char found = 0;    // a closing bracket of the other kind met while it was open; 0: none
  int found_line = 0, found_column = 0;
};

// The first delimiter left open at the end of `text` (or closed by the wrong bracket), reading
// YAML's rules closely enough for configuration files: quotes and brackets count only where a
// token may start (a quote inside a plain scalar such as `don't` is text), comments are skipped,
// quoted scalars may span lines ('' and \" escapes).
std::optional<UnclosedDelimiter> unclosed_delimiter(const std::string& text);

}  // namespace wysiwyf::detail
