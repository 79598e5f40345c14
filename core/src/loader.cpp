#include "wysiwyf/loader.hpp"

#include <dlfcn.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <sstream>

#include "wysiwyf/build_info.hpp"
#include "wysiwyf/search_paths.hpp"
#include "wysiwyf/validator.hpp"

namespace fs = std::filesystem;

namespace wysiwyf {

const char* kernel_build_id() { return WYSIWYF_BUILD_ID; }

Loader::Loader(std::vector<std::string> search_dirs) : dirs_(std::move(search_dirs)) {}

std::vector<std::string> Loader::default_search_dirs() { return component_search_dirs(); }

std::string Loader::find_file(const std::string& type) const {
  for (const auto& dir : dirs_) {
    const fs::path p = fs::path(dir) / library_file_name(type);
    std::error_code ec;
    if (fs::exists(p, ec)) return p.string();
  }
  return "";
}

std::vector<std::string> Loader::known_types() const {
  std::vector<std::string> types;
  for (const auto& dir : dirs_) {
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(dir, ec)) {
      const std::string f = e.path().filename().string();
      if (f.rfind("wysiwyf_", 0) == 0 && f.size() > 11 && f.compare(f.size() - 3, 3, ".so") == 0) {
        std::string t = f.substr(8, f.size() - 11);
        if (std::find(types.begin(), types.end(), t) == types.end()) types.push_back(t);
      }
    }
  }
  std::sort(types.begin(), types.end());
  return types;
}

std::vector<std::string> Loader::broken_libraries() {
  std::vector<std::string> broken;
  for (const auto& t : known_types()) {
    try {
      load(t);
    } catch (const LoadError& e) {
      broken.push_back(e.what());
    }
  }
  return broken;
}

const ComponentLibrary& Loader::load(const std::string& type) {
  if (auto it = by_type_.find(type); it != by_type_.end()) return it->second;
  const std::string path = find_file(type);
  if (path.empty()) {
    const std::vector<std::string> types = known_types();
    std::string known;
    for (const auto& t : types) known += (known.empty() ? "" : ", ") + t;
    std::string dirs;
    for (const auto& d : dirs_) dirs += (dirs.empty() ? "" : ":") + d;
    const std::string near = closest_name(type, types);
    throw LoadError("unknown component type '" + type + "'" + (near.empty() ? "" : " (did you mean '" + near + "'?)") +
                    ": no " + library_file_name(type) + " in " + dirs +
                    "; known types: " + (known.empty() ? "(none found)" : known));
  }
  const ComponentLibrary& lib = load_file(path);
  if (lib.type_name != type)
    throw LoadError(path + " exports component type '" + lib.type_name + "', not '" + type +
                    "'; the file must be named " + library_file_name(lib.type_name));
  return lib;
}

const ComponentLibrary& Loader::load_file(const std::string& path) {
  if (auto it = type_by_path_.find(path); it != type_by_path_.end()) return by_type_.at(it->second);
  std::error_code ec;
  if (!fs::exists(path, ec)) throw LoadError("component library " + path + " does not exist");
  // RTLD_NOW: a library with an unresolved symbol fails here, not in the middle of a run.
  // RTLD_LOCAL: components cannot clash through their own symbols.
  void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle)
    throw LoadError("cannot load component library " + path + ": " + dlerror() +
                    "; rebuild it against this tree (cmake --build build) or remove it from the search path");
  using EntryFn = const ComponentEntry* (*)();
  auto fn = reinterpret_cast<EntryFn>(dlsym(handle, WYSIWYF_COMPONENT_ENTRY_SYMBOL));
  if (!fn) {
    dlclose(handle);
    throw LoadError(path + " is not a wysiwyf component library: it has no '" WYSIWYF_COMPONENT_ENTRY_SYMBOL
                           "' symbol; export the component class with WYSIWYF_COMPONENT(Class, \"type\")");
  }
  const ComponentEntry* entry = fn();
  if (!entry) throw LoadError(path + ": " WYSIWYF_COMPONENT_ENTRY_SYMBOL " returned null");
  if (entry->abi_version != kAbiVersion)
    throw LoadError(path + " was built for component ABI version " + std::to_string(entry->abi_version) +
                    " but this kernel has ABI version " + std::to_string(kAbiVersion) +
                    "; rebuild the component against this kernel's headers (cmake --build build)");
  if (!entry->build_id || std::string(entry->build_id) != kernel_build_id())
    throw LoadError(path + " was built against kernel build " + (entry->build_id ? entry->build_id : "(none)") +
                    " but this kernel is build " + kernel_build_id() +
                    "; the kernel headers changed since it was built: rebuild it (cmake --build build)");
  if (!entry->type_name || !entry->create || !entry->destroy)
    throw LoadError(path + ": its component entry lacks a type name or factory; rebuild it with WYSIWYF_COMPONENT");
  // Never dlclose: a loaded component's code may still be referenced (registered types, threads).
  ComponentLibrary lib{entry->type_name, path, entry};
  type_by_path_[path] = lib.type_name;
  auto [it, inserted] = by_type_.emplace(lib.type_name, lib);
  if (!inserted && it->second.path != path)
    throw LoadError(path + " exports component type '" + lib.type_name + "', already loaded from " + it->second.path);
  return it->second;
}

ComponentPtr Loader::create(const std::string& type) {
  const ComponentLibrary& lib = load(type);
  return ComponentPtr(lib.entry->create(), ComponentDeleter{lib.entry->destroy});
}

}  // namespace wysiwyf
