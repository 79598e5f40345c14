#pragma once
/// @file
/// Declared parameters: type, default, range, list length and a one-line description, so a
/// pipeline is checked before it runs and `wysiwyf components describe` can print them.
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace wysiwyf {

/// The type of a declared parameter, as pipelines write its value.
enum class ParamType {
  kBool,        ///< bool
  kInt,         ///< int or int64_t
  kDouble,      ///< double
  kString,      ///< std::string
  kDoubleList,  ///< `std::vector<double>` or `std::array<double, N>`
  kStringList   ///< `std::vector<std::string>`
};
/// The type's name in messages: "bool", "int", "double", "string", "list of double", "list of string".
std::string to_string(ParamType t);

/// Inclusive numeric range; for lists it applies to each element.
struct Range {
  double min;  ///< the smallest value accepted
  double max;  ///< the largest value accepted
};

/// How many elements a list parameter may have.
struct Length {
  std::size_t min = 0;          ///< the fewest elements
  std::size_t max = SIZE_MAX;   ///< the most elements
  std::size_t multiple_of = 1;  ///< rows of this many values
  bool or_empty = false;        ///< the empty list is accepted too (an optional value)

  /// Exactly n values.
  static Length exactly(std::size_t n) { return Length{n, n, 1, false}; }
  /// n values, or none at all ("not given").
  static Length exactly_or_empty(std::size_t n) { return Length{n, n, 1, true}; }
  /// n values or more.
  static Length at_least(std::size_t n) { return Length{n, SIZE_MAX, 1, false}; }
  /// Whole rows of `width` values (at least `min_rows` of them).
  static Length rows_of(std::size_t width, std::size_t min_rows = 0) {
    return Length{width * min_rows, SIZE_MAX, width, false};
  }
  /// Whether a list of n elements has an accepted length.
  bool accepts(std::size_t n) const { return (or_empty && n == 0) || (n >= min && n <= max && n % multiple_of == 0); }
  std::string text() const;  ///< "3 values", "none or 4 values", "whole rows of 7 values", ...
};

/// A declared parameter, as `wysiwyf components describe` prints it and the validator checks it.
struct ParamSpec {
  std::string name;                     ///< the parameter's name in the pipeline's `params`
  ParamType type = ParamType::kDouble;  ///< the type its value must have
  std::string default_value;            ///< as YAML text
  std::string description;              ///< the one-line description the component gave
  std::optional<Range> range;           ///< for numbers (each element of a list): the accepted values
  std::vector<std::string> choices;     ///< for strings: the allowed values (empty: any)
  std::optional<Length> length;         ///< for lists
};

/// The ParamType of C++ type T, for the types Context::param() accepts.
template <class T>
struct ParamTypeOf;
/// A bool parameter is ParamType::kBool.
template <>
struct ParamTypeOf<bool> {
  static constexpr ParamType value = ParamType::kBool;  ///< ParamType::kBool
};
/// An int parameter is ParamType::kInt.
template <>
struct ParamTypeOf<int> {
  static constexpr ParamType value = ParamType::kInt;  ///< ParamType::kInt
};
/// An int64_t parameter is ParamType::kInt.
template <>
struct ParamTypeOf<std::int64_t> {
  static constexpr ParamType value = ParamType::kInt;  ///< ParamType::kInt
};
/// A double parameter is ParamType::kDouble.
template <>
struct ParamTypeOf<double> {
  static constexpr ParamType value = ParamType::kDouble;  ///< ParamType::kDouble
};
/// A string parameter is ParamType::kString.
template <>
struct ParamTypeOf<std::string> {
  static constexpr ParamType value = ParamType::kString;  ///< ParamType::kString
};
/// A list of doubles is ParamType::kDoubleList.
template <>
struct ParamTypeOf<std::vector<double>> {
  static constexpr ParamType value = ParamType::kDoubleList;  ///< ParamType::kDoubleList
};
/// A list of strings is ParamType::kStringList.
template <>
struct ParamTypeOf<std::vector<std::string>> {
  static constexpr ParamType value = ParamType::kStringList;  ///< ParamType::kStringList
};

}  // namespace wysiwyf
