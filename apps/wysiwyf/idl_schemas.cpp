#include "idl_schemas.hpp"

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <vector>

#include "wysiwyf/search_paths.hpp"

namespace fs = std::filesystem;

namespace wysiwyf::cli {

namespace {

struct IdlFile {
  std::string text;                     // as written
  std::vector<std::string> includes;    // file names, in order
  std::map<std::string, bool> structs;  // qualified name -> first member is a Header
};

std::string without_comments(const std::string& s) {
  static const std::regex comments(R"(//[^\n]*|/\*[\s\S]*?\*/)");
  return std::regex_replace(s, comments, " ");
}

// Modules, structs and enums with their qualified names; a struct's first member's type.
IdlFile parse(const std::string& text) {
  IdlFile f;
  f.text = text;
  static const std::regex include(R"re(#include\s*"([^"]+)")re");
  for (std::sregex_iterator it(text.begin(), text.end(), include), end; it != end; ++it) f.includes.push_back((*it)[1]);
  std::string code = without_comments(text);
  code = std::regex_replace(code, std::regex(R"(#[^\n]*)"), " ");
  code = std::regex_replace(code, std::regex(R"(([{};]))"), " $1 ");
  std::istringstream tokens(code);
  std::vector<std::string> scope;  // one entry per open brace: a module's name or ""
  std::string pending_module, pending_struct, token;
  bool first_member = false;
  std::string current_struct;
  while (tokens >> token) {
    if (token == "module" || token == "struct" || token == "enum" || token == "union") {
      std::string name;
      tokens >> name;
      std::string qualified;
      for (const auto& s : scope)
        if (!s.empty()) qualified += s + "::";
      if (token == "module") pending_module = name;
      if (token == "struct") pending_struct = qualified + name;
      if (token == "enum" || token == "union") f.structs[qualified + name] = false;
      continue;
    }
    if (token == "{") {
      scope.push_back(pending_module);
      if (!pending_struct.empty())
        current_struct = pending_struct, first_member = true, f.structs[current_struct] = false;
      pending_module.clear();
      pending_struct.clear();
      continue;
    }
    if (token == "}") {
      if (!scope.empty()) scope.pop_back();
      current_struct.clear();
      first_member = false;
      continue;
    }
    if (first_member && !current_struct.empty() && token.rfind('@', 0) != 0) {
      f.structs[current_struct] = token == "wysiwyf::std_msgs::Header" || token == "std_msgs::Header";
      first_member = false;
    }
  }
  return f;
}

struct Catalogue {
  std::vector<std::string> dirs;
  std::map<std::string, IdlFile> files;        // file name -> parsed
  std::map<std::string, std::string> defined;  // qualified type -> file name
};

const Catalogue& catalogue() {
  static const Catalogue c = [] {
    Catalogue c;
    c.dirs = idl_search_dirs();
    for (const auto& dir : c.dirs) {
      std::error_code ec;
      for (const auto& e : fs::directory_iterator(dir, ec)) {
        if (e.path().extension() != ".idl") continue;
        const std::string name = e.path().filename().string();
        if (c.files.count(name)) continue;  // the first folder wins, as for includes
        std::ifstream in(e.path());
        c.files[name] = parse(std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>()));
        for (const auto& [type, stamped] : c.files[name].structs) c.defined.emplace(type, name);
      }
    }
    return c;
  }();
  return c;
}

// `name` and what it includes, dependencies first, each once, without preprocessor lines.
void append(const Catalogue& c, const std::string& name, std::set<std::string>& done, std::string& out) {
  if (!done.insert(name).second) return;
  const auto it = c.files.find(name);
  if (it == c.files.end()) return;
  for (const auto& inc : it->second.includes) append(c, inc, done, out);
  std::istringstream lines(it->second.text);
  out += "// " + name + "\n";
  for (std::string line; std::getline(lines, line);)
    if (line.find_first_not_of(" \t") == std::string::npos || line[line.find_first_not_of(" \t")] != '#')
      out += line + "\n";
}

}  // namespace

std::optional<IdlSchema> idl_schema(const std::string& type_name, std::string& searched) {
  const Catalogue& c = catalogue();
  const auto it = c.defined.find(type_name);
  if (it == c.defined.end()) {
    searched = "the IDL files in ";
    for (std::size_t i = 0; i < c.dirs.size(); ++i) searched += (i ? ":" : "") + c.dirs[i];
    if (c.dirs.empty()) searched += "(no IDL folder found; set WYSIWYF_IDL_PATH)";
    return std::nullopt;
  }
  IdlSchema schema;
  std::set<std::string> done;
  append(c, it->second, done, schema.text);
  schema.stamped = c.files.at(it->second).structs.at(type_name);
  return schema;
}

std::optional<std::int64_t> header_stamp(const std::vector<std::uint8_t>& cdr) {
  if (cdr.size() < 12 || cdr[1] != 0x01) return std::nullopt;
  std::int64_t stamp = 0;
  std::memcpy(&stamp, cdr.data() + 4, sizeof(stamp));  // after the encapsulation header
  return stamp;
}

}  // namespace wysiwyf::cli
