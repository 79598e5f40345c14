#include "cdr_yaml.hpp"

#include <fastrtps/types/DynamicType.h>
#include <fastrtps/types/DynamicTypeMember.h>
#include <fastrtps/types/DynamicTypePtr.h>
#include <fastrtps/types/MemberDescriptor.h>
#include <fastrtps/types/TypeDescriptor.h>

#include <cstring>
#include <map>
#include <sstream>
#include <stdexcept>

#include "wysiwyf/number_text.hpp"

namespace wysiwyf::cli {

namespace types = eprosima::fastrtps::types;

namespace {

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

// The members of a structure (or the literals of an enum) in declaration order.
std::map<types::MemberId, types::DynamicTypeMember*> members_of(const types::DynamicType_ptr& type) {
  std::map<types::MemberId, types::DynamicTypeMember*> members;
  type->get_all_members(members);
  return members;
}

// Plain CDR (XCDR1, as Fast DDS 2.9 writes it): primitives aligned to their size (at most 8)
// from the start of the data after the 4-byte encapsulation header.
class Reader {
 public:
  Reader(const std::uint8_t* cdr, std::size_t size) : data_(cdr), size_(size) {
    if (size < 4) throw std::runtime_error("a sample of " + std::to_string(size) + " bytes has no CDR header");
    little_ = cdr[1] & 0x01;
    pos_ = 4;
  }

  template <class T>
  T read(const std::string& what) {
    align(std::min<std::size_t>(sizeof(T), 8));
    need(sizeof(T), what);
    T v;
    std::memcpy(&v, data_ + pos_, sizeof(T));
    if (!little_) {
      auto* b = reinterpret_cast<std::uint8_t*>(&v);
      for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(b[i], b[sizeof(T) - 1 - i]);
    }
    pos_ += sizeof(T);
    return v;
  }
  std::string string(const std::string& what) {
    const auto n = read<std::uint32_t>(what);
    need(n, what);
    std::string s(reinterpret_cast<const char*>(data_ + pos_), n > 0 ? n - 1 : 0);  // without the NUL
    pos_ += n;
    return s;
  }
  void skip(std::size_t n, const std::string& what) {
    need(n, what);
    pos_ += n;
  }

 private:
  void align(std::size_t a) { pos_ = 4 + (pos_ - 4 + a - 1) / a * a; }
  void need(std::size_t n, const std::string& what) {
    if (pos_ + n > size_)
      throw std::runtime_error("the sample ends inside '" + what + "' (" + std::to_string(size_) + " bytes)");
  }
  const std::uint8_t* data_;
  std::size_t size_, pos_ = 0;
  bool little_ = true;
};

class Printer {
 public:
  explicit Printer(Reader& in) : in_(in) {}
  std::string text() const { return out_.str(); }

  void structure(const types::DynamicType_ptr& type, int depth, const std::string& path) {
    if (auto base = resolve_alias(type->get_descriptor()->get_base_type())) structure(base, depth, path);
    for (const auto& [id, member] : members_of(type)) {
      const types::DynamicType_ptr member_type = resolve_alias(member->get_descriptor()->get_type());
      field(member->get_name(), member_type, depth, path + member->get_name());
    }
  }

 private:
  void indent(int depth) { out_ << std::string(2 * depth, ' '); }

  void field(const std::string& name, const types::DynamicType_ptr& type, int depth, const std::string& path) {
    indent(depth);
    out_ << name << ":";
    const types::TypeKind kind = type->get_kind();
    if (is_basic(kind)) {
      out_ << " " << basic(type, path) << "\n";
    } else if (kind == types::TK_STRUCTURE) {
      out_ << "\n";
      structure(type, depth + 1, path + ".");
    } else if (kind == types::TK_SEQUENCE) {
      collection(type, in_.read<std::uint32_t>(path), depth, path);
    } else if (kind == types::TK_ARRAY) {
      collection(type, type->get_total_bounds(), depth, path);
    } else {
      throw std::runtime_error("'" + path + "' is a union, map or bitset: not read here");
    }
  }

  std::string basic(const types::DynamicType_ptr& type, const std::string& path) {
    switch (type->get_kind()) {
      case types::TK_BOOLEAN: return in_.read<std::uint8_t>(path) ? "true" : "false";
      case types::TK_BYTE: return std::to_string(in_.read<std::uint8_t>(path));
      case types::TK_INT16: return std::to_string(in_.read<std::int16_t>(path));
      case types::TK_UINT16: return std::to_string(in_.read<std::uint16_t>(path));
      case types::TK_INT32: return std::to_string(in_.read<std::int32_t>(path));
      case types::TK_UINT32: return std::to_string(in_.read<std::uint32_t>(path));
      case types::TK_INT64: return std::to_string(in_.read<std::int64_t>(path));
      case types::TK_UINT64: return std::to_string(in_.read<std::uint64_t>(path));
      case types::TK_FLOAT32: return round_trip_text(in_.read<float>(path));
      case types::TK_FLOAT64: return round_trip_text(in_.read<double>(path));
      case types::TK_CHAR8: return yaml_quoted(std::string(1, static_cast<char>(in_.read<std::uint8_t>(path))));
      case types::TK_STRING8: return yaml_quoted(in_.string(path));
      case types::TK_ENUM: {
        // The literal's name: IDL enums without @value number their literals 0, 1, ... in order.
        const auto value = in_.read<std::uint32_t>(path);
        std::uint32_t i = 0;
        for (const auto& [id, literal] : members_of(type))
          if (i++ == value) return literal->get_name();
        return std::to_string(value);
      }
      default:
        throw std::runtime_error("'" + path + "' is of a kind (" + std::to_string(type->get_kind()) +
                                 ") not read here");
    }
  }

  void collection(const types::DynamicType_ptr& type, std::uint32_t n, int depth, const std::string& path) {
    const types::DynamicType_ptr element = resolve_alias(type->get_descriptor()->get_element_type());
    const types::TypeKind kind = element->get_kind();
    if ((kind == types::TK_BYTE || kind == types::TK_CHAR8) && n > kMaxBytesShown) {
      in_.skip(n, path);
      out_ << " <" << n << " bytes>\n";
      return;
    }
    if (is_basic(kind)) {
      out_ << " [";
      for (std::uint32_t i = 0; i < n; ++i) out_ << (i ? ", " : "") << basic(element, path);
      out_ << "]\n";
      return;
    }
    if (n == 0) {
      out_ << " []\n";
      return;
    }
    out_ << "\n";
    for (std::uint32_t i = 0; i < n; ++i) {
      indent(depth);
      const std::string item = path + "." + std::to_string(i);
      if (kind == types::TK_STRUCTURE) {
        out_ << "-\n";
        structure(element, depth + 1, item + ".");
      } else {
        throw std::runtime_error("'" + item + "' is a nested collection: not read here");
      }
    }
  }

  Reader& in_;
  std::ostringstream out_;
};

}  // namespace

std::string cdr_to_yaml(const std::uint8_t* cdr, std::size_t size, const types::DynamicType_ptr& type) {
  Reader in(cdr, size);
  Printer p(in);
  p.structure(resolve_alias(type), 0, "");
  return p.text();
}

}  // namespace wysiwyf::cli
