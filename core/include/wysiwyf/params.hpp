#pragma once
// Declared parameters: type, default, range, list length and a one-line description, so a
// pipeline is checked before it runs and `wysiwyf components describe` can print them.
#include <array>
#include <cstddef>
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

// How many elements a list parameter may have.
struct Length {
  std::size_t min = 0;
  std::size_t max = SIZE_MAX;
  std::size_t multiple_of = 1;  // rows of this many values
  bool or_empty = false;        // the empty list is accepted too (an optional value)

  static Length exactly(std::size_t n) { return Length{n, n, 1, false}; }
  // n values, or none at all ("not given").
  static Length exactly_or_empty(std::size_t n) { return Length{n, n, 1, true}; }
  static Length at_least(std::size_t n) { return Length{n, SIZE_MAX, 1, false}; }
  // Whole rows of `width` values (at least `min_rows` of them).
  static Length rows_of(std::size_t width, std::size_t min_rows = 0) {
    return Length{width * min_rows, SIZE_MAX, width, false};
  }
  bool accepts(std::size_t n) const { return (or_empty && n == 0) || (n >= min && n <= max && n % multiple_of == 0); }
  std::string text() const;  // "3 values", "0 or 4 values", "rows of 7 values", ...
};

struct ParamSpec {
  std::string name;
  ParamType type = ParamType::kDouble;
  std::string default_value;  // as YAML text
  std::string description;
  std::optional<Range> range;
  std::vector<std::string> choices;  // for strings: the allowed values (empty: any)
  std::optional<Length> length;      // for lists
};

template <class T>
struct ParamTypeOf;
template <>
struct ParamTypeOf<bool> {
  static constexpr ParamType value = ParamType::kBool;
};
template <>
struct ParamTypeOf<int> {
  static constexpr ParamType value = ParamType::kInt;
};
template <>
struct ParamTypeOf<std::int64_t> {
  static constexpr ParamType value = ParamType::kInt;
};
template <>
struct ParamTypeOf<double> {
  static constexpr ParamType value = ParamType::kDouble;
};
template <>
struct ParamTypeOf<std::string> {
  static constexpr ParamType value = ParamType::kString;
};
template <>
struct ParamTypeOf<std::vector<double>> {
  static constexpr ParamType value = ParamType::kDoubleList;
};
template <>
struct ParamTypeOf<std::vector<std::string>> {
  static constexpr ParamType value = ParamType::kStringList;
};

}  // namespace wysiwyf
