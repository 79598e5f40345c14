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

// Member `id` of `data`, read with DynamicData's getter for its C++ type.
template <class V, class R>
V read(const types::DynamicData& data, types::MemberId id, R (types::DynamicData::*get)(V&, types::MemberId) const) {
  V v{};
  (data.*get)(v, id);
  return v;
}

// One basic value (member `id` of `data`) as YAML text.
std::string basic_value(types::DynamicData& data, types::MemberId id, types::TypeKind kind) {
  using D = types::DynamicData;
  switch (kind) {
    case types::TK_BOOLEAN: return read(data, id, &D::get_bool_value) ? "true" : "false";
    case types::TK_BYTE: return std::to_string(read(data, id, &D::get_byte_value));
    case types::TK_INT16: return std::to_string(read(data, id, &D::get_int16_value));
    case types::TK_UINT16: return std::to_string(read(data, id, &D::get_uint16_value));
    case types::TK_INT32: return std::to_string(read(data, id, &D::get_int32_value));
    case types::TK_UINT32: return std::to_string(read(data, id, &D::get_uint32_value));
    case types::TK_INT64: return std::to_string(read(data, id, &D::get_int64_value));
    case types::TK_UINT64: return std::to_string(read(data, id, &D::get_uint64_value));
    case types::TK_FLOAT32: return round_trip_text(read(data, id, &D::get_float32_value));
    case types::TK_FLOAT64: return round_trip_text(read(data, id, &D::get_float64_value));
    case types::TK_FLOAT128: return round_trip_text(static_cast<double>(read(data, id, &D::get_float128_value)));
    case types::TK_CHAR8: return yaml_quoted(std::string(1, read(data, id, &D::get_char8_value)));
    case types::TK_STRING8: return yaml_quoted(read(data, id, &D::get_string_value));
    case types::TK_ENUM: return read<std::string>(data, id, &D::get_enum_value);  // the name, not the number
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
