#include "dynamic_yaml.hpp"

#include <fastrtps/types/DynamicData.h>
#include <fastrtps/types/DynamicType.h>
#include <fastrtps/types/DynamicTypeMember.h>
#include <fastrtps/types/MemberDescriptor.h>
#include <fastrtps/types/TypeDescriptor.h>

#include <map>
#include <sstream>

#include "wysiwyf/number_text.hpp"

namespace wysiwyf::cli {

namespace types = eprosima::fastrtps::types;

namespace {

// A byte sequence longer than this (an image) is shown by its length, not its bytes.
constexpr std::uint32_t kMaxBytesShown = 32;

std::string yaml_quoted(const std::string& s) {
  std::string out = "\"";
  for (char c : s) out += (c == '"' || c == '\\') ? std::string("\\") + c : std::string(1, c);
  return out + "\"";
}

types::DynamicType_ptr resolve_alias(types::DynamicType_ptr type) {
  while (type && type->get_kind() == types::TK_ALIAS) type = type->get_descriptor()->get_base_type();
  return type;
}

bool is_basic(types::TypeKind k) {
  switch (k) {
    case types::TK_STRUCTURE:
    case types::TK_SEQUENCE:
    case types::TK_ARRAY:
    case types::TK_UNION:
    case types::TK_MAP:
    case types::TK_BITSET: return false;
    default: return true;
  }
}

// One basic value (member `id` of `data`) as YAML text.
std::string basic_value(types::DynamicData& data, types::MemberId id, types::TypeKind kind) {
  switch (kind) {
    case types::TK_BOOLEAN: {
      bool v = false;
      data.get_bool_value(v, id);
      return v ? "true" : "false";
    }
    case types::TK_BYTE: {
      types::octet v = 0;
      data.get_byte_value(v, id);
      return std::to_string(v);
    }
    case types::TK_INT16: {
      std::int16_t v = 0;
      data.get_int16_value(v, id);
      return std::to_string(v);
    }
    case types::TK_UINT16: {
      std::uint16_t v = 0;
      data.get_uint16_value(v, id);
      return std::to_string(v);
    }
    case types::TK_INT32: {
      std::int32_t v = 0;
      data.get_int32_value(v, id);
      return std::to_string(v);
    }
    case types::TK_UINT32: {
      std::uint32_t v = 0;
      data.get_uint32_value(v, id);
      return std::to_string(v);
    }
    case types::TK_INT64: {
      std::int64_t v = 0;
      data.get_int64_value(v, id);
      return std::to_string(v);
    }
    case types::TK_UINT64: {
      std::uint64_t v = 0;
      data.get_uint64_value(v, id);
      return std::to_string(v);
    }
    case types::TK_FLOAT32: {
      float v = 0;
      data.get_float32_value(v, id);
      return round_trip_text(v);
    }
    case types::TK_FLOAT64: {
      double v = 0;
      data.get_float64_value(v, id);
      return round_trip_text(v);
    }
    case types::TK_FLOAT128: {
      long double v = 0;
      data.get_float128_value(v, id);
      return round_trip_text(static_cast<double>(v));
    }
    case types::TK_CHAR8: {
      char v = 0;
      data.get_char8_value(v, id);
      return yaml_quoted(std::string(1, v));
    }
    case types::TK_STRING8: {
      std::string v;
      data.get_string_value(v, id);
      return yaml_quoted(v);
    }
    case types::TK_ENUM: {
      std::string v;
      data.get_enum_value(v, id);
      return v;
    }
    default: return "(a value of a kind this printer does not show)";
  }
}

class Printer {
 public:
  std::string text() const { return out_.str(); }

  // The members of a structure, one "name: value" line each, nested ones indented.
  void structure(types::DynamicData& data, const types::DynamicType_ptr& type, int depth) {
    std::map<types::MemberId, types::DynamicTypeMember*> members;
    type->get_all_members(members);
    for (const auto& [id, member] : members) {
      const types::DynamicType_ptr member_type = resolve_alias(member->get_descriptor()->get_type());
      field(data, id, member->get_name(), member_type, depth);
    }
  }

 private:
  std::ostringstream out_;

  void indent(int depth) { out_ << std::string(2 * depth, ' '); }

  void field(types::DynamicData& data, types::MemberId id, const std::string& name, const types::DynamicType_ptr& type,
             int depth) {
    indent(depth);
    out_ << name << ":";
    const types::TypeKind kind = type->get_kind();
    if (is_basic(kind)) {
      out_ << " " << basic_value(data, id, kind) << "\n";
      return;
    }
    types::DynamicData* child = data.loan_value(id);
    if (!child) {
      out_ << " (unreadable)\n";
      return;
    }
    if (kind == types::TK_STRUCTURE) {
      out_ << "\n";
      structure(*child, type, depth + 1);
    } else if (kind == types::TK_SEQUENCE || kind == types::TK_ARRAY) {
      collection(*child, type, depth);
    } else {
      out_ << " (a union, map or bitset: not shown)\n";
    }
    data.return_loaned_value(child);
  }

  void collection(types::DynamicData& data, const types::DynamicType_ptr& type, int depth) {
    const types::DynamicType_ptr element = resolve_alias(type->get_descriptor()->get_element_type());
    const types::TypeKind kind = element->get_kind();
    const std::uint32_t n = data.get_item_count();
    if ((kind == types::TK_BYTE || kind == types::TK_CHAR8) && n > kMaxBytesShown) {
      out_ << " <" << n << " bytes>\n";
      return;
    }
    if (is_basic(kind)) {
      out_ << " [";
      for (std::uint32_t i = 0; i < n; ++i)
        out_ << (i ? ", " : "") << basic_value(data, data.get_member_id_at_index(i), kind);
      out_ << "]\n";
      return;
    }
    if (n == 0) {
      out_ << " []\n";
      return;
    }
    out_ << "\n";
    for (std::uint32_t i = 0; i < n; ++i) {
      types::DynamicData* item = data.loan_value(data.get_member_id_at_index(i));
      indent(depth);
      if (!item) {
        out_ << "- (unreadable)\n";
        continue;
      }
      if (kind == types::TK_STRUCTURE) {
        out_ << "-\n";
        structure(*item, element, depth + 1);
      } else {
        out_ << "- (nested collection)\n";
      }
      data.return_loaned_value(item);
    }
  }
};

}  // namespace

std::string dynamic_to_yaml(types::DynamicData& sample, const types::DynamicType_ptr& type) {
  Printer p;
  p.structure(sample, resolve_alias(type), 0);
  return p.text();
}

}  // namespace wysiwyf::cli
