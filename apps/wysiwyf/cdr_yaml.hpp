#pragma once
// A sample as DDS carried it (CDR, with its encapsulation header) printed as YAML, walking the
// bytes by the type's description: the dynamic type built from its type object (this build's
// types, message libraries': message_libraries.hpp). What `topic echo`, the dashboard and
// `monitor` read every type with. Byte sequences longer than 32 are shown by their length, so a
// 640x480 image costs no more than its header (decoding it into Fast DDS 2.9's DynamicData took
// 110 s: one value object per byte).
#include <cstddef>
#include <cstdint>
#include <string>

namespace eprosima::fastrtps::types {
class DynamicType_ptr;
}

namespace wysiwyf::cli {

// Throws std::runtime_error when the bytes end early or hold a kind this reader does not walk
// (unions, maps, bitsets), saying which member.
std::string cdr_to_yaml(const std::uint8_t* cdr, std::size_t size,
                        const eprosima::fastrtps::types::DynamicType_ptr& type);

}  // namespace wysiwyf::cli
