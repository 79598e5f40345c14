#pragma once
// Finds component libraries (wysiwyf_<type>.so) and loads them with dlopen, refusing any whose
// ABI version or build id differs from this kernel's, with a message that says how to fix it.
// Search order: wysiwyf/search_paths.hpp (the environment, beside the program, beside the core).
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "wysiwyf/component.hpp"

namespace wysiwyf {

class LoadError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct ComponentLibrary {
  std::string type_name;
  std::string path;
  const ComponentEntry* entry = nullptr;
};

struct ComponentDeleter {
  void (*destroy)(Component*) = nullptr;
  void operator()(Component* c) const {
    if (c && destroy) destroy(c);
  }
};
using ComponentPtr = std::unique_ptr<Component, ComponentDeleter>;

class Loader {
 public:
  explicit Loader(std::vector<std::string> search_dirs = default_search_dirs());
  Loader(const Loader&) = delete;
  Loader& operator=(const Loader&) = delete;

  static std::vector<std::string> default_search_dirs();
  static std::string library_file_name(const std::string& type) { return "wysiwyf_" + type + ".so"; }

  // The library of component type `type`; throws LoadError (unknown type: lists the known ones).
  const ComponentLibrary& load(const std::string& type);
  // Loads one library file and checks it; throws LoadError saying what is wrong and how to fix it.
  const ComponentLibrary& load_file(const std::string& path);
  ComponentPtr create(const std::string& type);

  // Every component type found on the search path (sorted), and the problems of broken ones.
  std::vector<std::string> known_types() const;
  std::vector<std::string> broken_libraries();  // "path: why"

  const std::vector<std::string>& search_dirs() const { return dirs_; }

 private:
  std::string find_file(const std::string& type) const;

  std::vector<std::string> dirs_;
  std::map<std::string, ComponentLibrary> by_type_;
  std::map<std::string, std::string> type_by_path_;
};

// This kernel's build id (WYSIWYF_BUILD_ID as compiled into core).
const char* kernel_build_id();

}  // namespace wysiwyf
