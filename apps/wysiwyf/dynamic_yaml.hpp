#pragma once
// A sample of any type whose TypeObject is registered (fastddsgen -typeobject, loaded from a
// message library) printed as YAML, walking its DynamicType: what `wysiwyf topic echo` prints
// for a type it was not compiled with.
#include <string>

namespace eprosima::fastrtps::types {
class DynamicData;
class DynamicType_ptr;
}  // namespace eprosima::fastrtps::types

namespace wysiwyf::cli {

// `type` is the sample's own type (a structure).
std::string dynamic_to_yaml(eprosima::fastrtps::types::DynamicData& sample,
                            const eprosima::fastrtps::types::DynamicType_ptr& type);

}  // namespace wysiwyf::cli
