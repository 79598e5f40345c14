#include "wysiwyf/search_paths.hpp"

#include <dlfcn.h>

#include <algorithm>
#include <filesystem>

#include "search_path.hpp"

namespace fs = std::filesystem;

namespace wysiwyf {

namespace {

// Appends `dir` (normalised) if it is an existing folder not listed yet.
void add_existing(std::vector<std::string>& dirs, const fs::path& dir) {
  std::error_code ec;
  if (dir.empty() || !fs::is_directory(dir, ec)) return;
  const std::string d = fs::weakly_canonical(dir, ec).string();
  if (!ec && std::find(dirs.begin(), dirs.end(), d) == dirs.end()) dirs.push_back(d);
}

}  // namespace

std::string core_library_dir() {
  Dl_info info{};
  if (dladdr(reinterpret_cast<void*>(&core_library_dir), &info) == 0 || !info.dli_fname) return "";
  std::error_code ec;
  const fs::path lib = fs::weakly_canonical(info.dli_fname, ec);
  return ec ? "" : lib.parent_path().string();
}

std::string program_dir() {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  return ec ? "" : exe.parent_path().string();
}

std::vector<std::string> component_search_dirs() {
  // Folders named in the environment are kept even if missing: the user asked for them.
  std::vector<std::string> dirs = detail::search_path_from_env("WYSIWYF_COMPONENT_PATH");
  if (const std::string exe = program_dir(); !exe.empty()) {
    add_existing(dirs, fs::path(exe) / "lib" / "wysiwyf");
    add_existing(dirs, fs::path(exe).parent_path() / "lib" / "wysiwyf");
  }
  if (const std::string core = core_library_dir(); !core.empty()) add_existing(dirs, fs::path(core) / "wysiwyf");
  return dirs;
}

std::vector<std::string> message_library_dirs() {
  std::vector<std::string> dirs;
  for (const auto& d : component_search_dirs()) add_existing(dirs, fs::path(d) / "messages");
  return dirs;
}

std::vector<std::string> config_search_dirs() {
  std::vector<std::string> dirs = detail::search_path_from_env("WYSIWYF_CONFIG_PATH");
  const std::string core = core_library_dir();
  if (!core.empty()) add_existing(dirs, fs::path(core) / WYSIWYF_LIB_TO_DATA_DIR / "wysiwyf" / "config");
  // A core built in this tree (not installed) also reads the source tree's config/.
  std::error_code ec;
  if (!core.empty() && fs::equivalent(core, WYSIWYF_BUILD_LIB_DIR, ec)) add_existing(dirs, WYSIWYF_SOURCE_CONFIG_DIR);
  return dirs;
}

std::vector<std::string> idl_search_dirs() {
  std::vector<std::string> dirs = detail::search_path_from_env("WYSIWYF_IDL_PATH");
  const std::string core = core_library_dir();
  if (!core.empty()) add_existing(dirs, fs::path(core) / WYSIWYF_LIB_TO_DATA_DIR / "wysiwyf" / "idl");
  std::error_code ec;
  if (!core.empty() && fs::equivalent(core, WYSIWYF_BUILD_LIB_DIR, ec))
    for (const char* d : {"kernel", "msgs"}) add_existing(dirs, fs::path(WYSIWYF_SOURCE_INTERFACES_DIR) / d);
  // Users' types: the IDL that wysiwyf_add_messages puts beside each message library.
  for (const auto& d : message_library_dirs()) add_existing(dirs, fs::path(d) / "idl");
  return dirs;
}

}  // namespace wysiwyf
