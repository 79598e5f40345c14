#include "wysiwyf/config_files.hpp"

#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "wysiwyf/search_paths.hpp"

namespace wysiwyf {

std::string find_config_file(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::path(path).is_absolute() || fs::exists(path, ec)) {
    if (fs::exists(path, ec)) return path;
    throw std::invalid_argument("configuration file '" + path + "' does not exist");
  }
  const std::vector<std::string> dirs = config_search_dirs();
  std::string looked = "the working directory";
  for (const auto& d : dirs) {
    const fs::path candidate = fs::path(d) / path;
    if (fs::exists(candidate, ec)) return candidate.string();
    looked += ", " + d;
  }
  throw std::invalid_argument("configuration file '" + path + "' not found (looked in " + looked + ")");
}

}  // namespace wysiwyf
