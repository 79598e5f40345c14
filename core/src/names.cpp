// Printable names of the kernel's enums.
#include "wysiwyf/params.hpp"
#include "wysiwyf/qos.hpp"

namespace wysiwyf {

std::string to_string(ParamType t) {
  switch (t) {
    case ParamType::kBool: return "bool";
    case ParamType::kInt: return "int";
    case ParamType::kDouble: return "double";
    case ParamType::kString: return "string";
    case ParamType::kDoubleList: return "list of double";
    case ParamType::kStringList: return "list of string";
  }
  return "?";
}

std::string to_string(Reliability r) { return r == Reliability::kReliable ? "reliable" : "best_effort"; }
std::string to_string(Durability d) { return d == Durability::kVolatile ? "volatile" : "transient_local"; }

}  // namespace wysiwyf
