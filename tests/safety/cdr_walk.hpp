#pragma once
// A walk over a message type's members in the order plain CDR (XCDR1, as Fast DDS 2.9 writes it)
// lays them out, driven by the type's dynamic description (its type object): the fuzzer writes a
// random sample with it (random_sample.hpp) and reads every number of an output sample back
// (finite_check.hpp), for any type of interfaces/, with no code per type.
#include <fastrtps/types/DynamicType.h>
#include <fastrtps/types/DynamicTypeMember.h>
#include <fastrtps/types/DynamicTypePtr.h>
#include <fastrtps/types/MemberDescriptor.h>
#include <fastrtps/types/TypeDescriptor.h>

#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>

namespace wysiwyf::safety {

namespace types = eprosima::fastrtps::types;

inline types::DynamicType_ptr resolve_alias(types::DynamicType_ptr type) {
  while (type && type->get_kind() == types::TK_ALIAS) type = type->get_descriptor()->get_base_type();
  return type;
}

// What a walk asks of its visitor. `path` names the member ("header.stamp_ns", "position.3").
// basic(): one primitive, string or enum; length(): a sequence's element count (bound: its IDL
// bound, 0 if unbounded), which the visitor writes or reads.
template <class Visitor>
class CdrWalk {
 public:
  explicit CdrWalk(Visitor& visitor) : v_(visitor) {}

  void structure(const types::DynamicType_ptr& type, const std::string& path) {
    if (auto base = resolve_alias(type->get_descriptor()->get_base_type())) structure(base, path);
    std::map<types::MemberId, types::DynamicTypeMember*> members;
    type->get_all_members(members);
    for (const auto& [id, member] : members)
      value(resolve_alias(member->get_descriptor()->get_type()), path + member->get_name());
  }

 private:
  void value(const types::DynamicType_ptr& type, const std::string& path) {
    switch (type->get_kind()) {
      case types::TK_STRUCTURE: structure(type, path + "."); return;
      case types::TK_SEQUENCE: {
        const std::uint32_t bound = type->get_descriptor()->get_bounds(0);
        const std::uint32_t n = v_.length(bound, resolve_alias(type->get_descriptor()->get_element_type()), path);
        elements(type, n, path);
        return;
      }
      case types::TK_ARRAY: elements(type, type->get_total_bounds(), path); return;
      case types::TK_UNION:
      case types::TK_MAP:
      case types::TK_BITSET: throw std::runtime_error("'" + path + "': unions, maps and bitsets are not walked");
      default: v_.basic(type, path);
    }
  }
  void elements(const types::DynamicType_ptr& type, std::uint32_t n, const std::string& path) {
    const types::DynamicType_ptr element = resolve_alias(type->get_descriptor()->get_element_type());
    if (element->get_kind() == types::TK_BYTE || element->get_kind() == types::TK_CHAR8) {
      v_.bytes(n, path);  // one call for a byte sequence (an image's pixels)
      return;
    }
    for (std::uint32_t i = 0; i < n; ++i) value(element, path + "." + std::to_string(i));
  }

  Visitor& v_;
};

// Plain CDR's alignment: a primitive of size s (at most 8) starts at a multiple of s counted from
// the end of the 4-byte encapsulation header.
inline std::size_t cdr_aligned(std::size_t pos, std::size_t size) {
  const std::size_t a = size < 8 ? size : 8;
  return 4 + (pos - 4 + a - 1) / a * a;
}

}  // namespace wysiwyf::safety
