#pragma once
// A colon-separated list of folders from an environment variable (empty entries skipped), as
// WYSIWYF_COMPONENT_PATH and WYSIWYF_CONFIG_PATH are read.
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

namespace wysiwyf::detail {

inline std::vector<std::string> search_path_from_env(const char* variable) {
  std::vector<std::string> dirs;
  if (const char* env = std::getenv(variable)) {
    std::stringstream s(env);
    for (std::string d; std::getline(s, d, ':');)
      if (!d.empty()) dirs.push_back(d);
  }
  return dirs;
}

}  // namespace wysiwyf::detail
