#pragma once
// Declared parameters: type, default, range and a one-line description, so a pipeline is checked
// before it runs and `wysiwyf components describe` can print them.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace wysiwyf {

enum class ParamType { kBool, kInt, kDouble, kString, kDoubleList, kStringList };
std::string to_string(ParamType t);

// Inclusive numeric range; for lists it applies to each element.
struct Range {
  double min;
  double max;
};

struct ParamSpec {
  std::string name;
  ParamType type = ParamType::kDouble;
  std::string default_value;  // as YAML text
  std::string description;
  std::optional<Range> range;
  std::vector<std::string> choices;  // for strings: the allowed values (empty: any)
};

template <class T>
struct ParamTypeOf;
template <> struct ParamTypeOf<bool> { static constexpr ParamType value = ParamType::kBool; };
template <> struct ParamTypeOf<int> { static constexpr ParamType value = ParamType::kInt; };
template <> struct ParamTypeOf<std::int64_t> { static constexpr ParamType value = ParamType::kInt; };
template <> struct ParamTypeOf<double> { static constexpr ParamType value = ParamType::kDouble; };
template <> struct ParamTypeOf<std::string> { static constexpr ParamType value = ParamType::kString; };
template <> struct ParamTypeOf<std::vector<double>> { static constexpr ParamType value = ParamType::kDoubleList; };
template <> struct ParamTypeOf<std::vector<std::string>> { static constexpr ParamType value = ParamType::kStringList; };

}  // namespace wysiwyf
