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

std::string Length::text() const {
  const auto values = [](std::size_t n) { return std::to_string(n) + (n == 1 ? " value" : " values"); };
  std::string t;
  if (multiple_of > 1)
    t = "whole rows of " + values(multiple_of) +
        (min > 0 ? " (at least " + std::to_string(min / multiple_of) + ")" : "");
  else if (min == max)
    t = values(min);
  else if (max == SIZE_MAX)
    t = "at least " + values(min);
  else
    t = std::to_string(min) + " to " + values(max);
  return or_empty ? "none or " + t : t;
}

std::string to_string(Reliability r) { return r == Reliability::kReliable ? "reliable" : "best_effort"; }
std::string to_string(Durability d) { return d == Durability::kVolatile ? "volatile" : "transient_local"; }

}  // namespace wysiwyf
