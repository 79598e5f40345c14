#include "wysiwyf/config_files.hpp"

#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "wysiwyf/search_paths.hpp"

namespace wysiwyf {

namespace fs = std::filesystem;

std::string find_in_config_dirs(const std::string& relative) {
  std::error_code ec;
  for (const auto& d : config_search_dirs())
    if (fs::exists(fs::path(d) / relative, ec)) return (fs::path(d) / relative).string();
  return "";
}

std::string find_config_file(const std::string& path) {
  std::error_code ec;
  if (fs::path(path).is_absolute() || fs::exists(path, ec)) {
    if (fs::exists(path, ec)) return path;
    throw std::invalid_argument("configuration file '" + path + "' does not exist");
  }
  if (std::string found = find_in_config_dirs(path); !found.empty()) return found;
  std::string looked = "the working directory";
  for (const auto& d : config_search_dirs()) looked += ", " + d;
  throw std::invalid_argument("configuration file '" + path + "' not found (looked in " + looked + ")");
}

}  // namespace wysiwyf
