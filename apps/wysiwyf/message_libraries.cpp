#include "message_libraries.hpp"
#include "wysiwyf/msgs.hpp"

#include <dlfcn.h>
#include <fastrtps/types/DynamicTypePtr.h>
#include <fastrtps/types/TypeObjectFactory.h>

#include <algorithm>
#include <filesystem>

#include "wysiwyf/search_paths.hpp"

namespace fs = std::filesystem;
namespace types = eprosima::fastrtps::types;

namespace wysiwyf::cli {

namespace {

struct Loaded {
  std::vector<std::string> libraries;  // "name (path)"
  std::vector<std::string> broken;     // "path: why"
  std::vector<std::string> dirs;
};

// Loads every lib*.so of the message folders once (never unloaded: their type objects stay).
const Loaded& load_all() {
  static const Loaded loaded = [] {
    Loaded l;
    l.dirs = message_library_dirs();
    for (const auto& dir : l.dirs) {
      std::error_code ec;
      std::vector<fs::path> files;
      for (const auto& e : fs::directory_iterator(dir, ec))
        if (e.path().extension() == ".so") files.push_back(e.path());
      std::sort(files.begin(), files.end());
      for (const auto& f : files) {
        void* handle = dlopen(f.c_str(), RTLD_NOW | RTLD_LOCAL);
        if (!handle) {
          l.broken.push_back(f.string() + ": " + dlerror());
          continue;
        }
        using Entry = const char* (*)();
        auto entry = reinterpret_cast<Entry>(dlsym(handle, "wysiwyf_message_library"));
        if (!entry) {
          l.broken.push_back(f.string() + ": no wysiwyf_message_library entry (build it with wysiwyf_add_messages)");
          continue;
        }
        l.libraries.push_back(std::string(entry()) + " (" + f.string() + ")");
      }
    }
    return l;
  }();
  return loaded;
}

}  // namespace

bool find_dynamic_type(const std::string& type_name, types::DynamicType_ptr& type, std::string& searched) {
  msgs::register_type_objects();  // this build's own types, described as any library's
  const Loaded& l = load_all();
  types::TypeObjectFactory* factory = types::TypeObjectFactory::get_instance();
  const types::TypeIdentifier* id = factory->get_type_identifier(type_name, true);
  const types::TypeObject* object = factory->get_type_object(type_name, true);
  if (id && object) type = factory->build_dynamic_type(type_name, id, object);
  if (type) return true;
  searched = "message libraries ";
  for (std::size_t i = 0; i < l.libraries.size(); ++i) searched += (i ? ", " : "") + l.libraries[i];
  if (l.libraries.empty()) searched += "(none)";
  searched += " in ";
  for (std::size_t i = 0; i < l.dirs.size(); ++i) searched += (i ? ":" : "") + l.dirs[i];
  if (l.dirs.empty()) searched += "(no lib/wysiwyf/messages folder found; set WYSIWYF_COMPONENT_PATH)";
  for (const auto& b : l.broken) searched += "; failed: " + b;
  return false;
}

std::vector<std::string> message_libraries(std::vector<std::string>* broken) {
  const Loaded& l = load_all();
  if (broken) *broken = l.broken;
  return l.libraries;
}

}  // namespace wysiwyf::cli
