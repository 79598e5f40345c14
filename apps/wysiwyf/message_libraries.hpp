#pragma once
// Message types the tools were not compiled with: the message libraries of users' projects
// (wysiwyf_add_messages), found in message_library_dirs() (lib/wysiwyf/messages of a build tree or
// an install), loaded once, each registering its types' descriptions (TypeObjects) with Fast DDS.
#include <string>
#include <vector>

namespace eprosima::fastrtps::types {
class DynamicType_ptr;
}

namespace wysiwyf::cli {

// The dynamic type named `type_name` (e.g. "lab::msg::Gesture", "wysiwyf::msg::JointState") from
// this build's types or the loaded message libraries; false when none has it, with `searched` saying which libraries and folders were read.
bool find_dynamic_type(const std::string& type_name, eprosima::fastrtps::types::DynamicType_ptr& type,
                       std::string& searched);

// "name (path)" of every message library found, and "path: why" of those that failed to load.
std::vector<std::string> message_libraries(std::vector<std::string>* broken = nullptr);

}  // namespace wysiwyf::cli
