#pragma once
// An RTDE recipe (the fields of one data package, in order, with their types) and the values of
// one package of it, kept as the bytes on the wire and read or written field by field. Set up
// once per connection; reading and writing a package allocates nothing.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "rtde/protocol.hpp"

namespace wysiwyf::robot::rtde {

class Recipe {
 public:
  Recipe() = default;
  // Throws std::invalid_argument when names and types differ in number, a name is empty or
  // repeated, or a package of the recipe would exceed kMaxPackageSize.
  Recipe(std::uint8_t id, std::vector<std::string> names, std::vector<FieldType> types);

  // The id the controller gave the recipe (1..255; 0: none).
  std::uint8_t id() const { return id_; }
  // The number of fields.
  std::size_t size() const { return names_.size(); }
  const std::string& name(std::size_t i) const { return names_.at(i); }
  FieldType type(std::size_t i) const { return types_.at(i); }
  // Where field i starts among the values (after the recipe id byte).
  std::size_t offset(std::size_t i) const { return offsets_.at(i); }
  // The values' size in bytes (a data package's payload is one byte more: the recipe id).
  std::size_t values_size() const { return values_size_; }
  // The index of the field called `name`, or none.
  std::optional<std::size_t> index(std::string_view name) const;

 private:
  std::uint8_t id_ = 0;
  std::vector<std::string> names_;
  std::vector<FieldType> types_;
  std::vector<std::size_t> offsets_;
  std::size_t values_size_ = 0;
};

class RecipeValues {
 public:
  // All zero. The recipe must outlive the values.
  explicit RecipeValues(const Recipe& recipe);

  const Recipe& recipe() const { return *recipe_; }
  // The values as on the wire (big-endian, in the recipe's order).
  const std::vector<std::uint8_t>& bytes() const { return bytes_; }

  // Takes the values of a data package's payload (its recipe id byte first). False, and nothing
  // changed, when the id is not the recipe's, the size is not the recipe's, or a BOOL is neither
  // 0 nor 1.
  bool read(const std::uint8_t* payload, std::size_t size);

  // Field i's value. Each throws std::invalid_argument when field i has another type (a
  // programming error, not bad input: the recipe's types are known when it is set up).
  bool get_bool(std::size_t i) const;
  std::uint8_t get_uint8(std::size_t i) const;
  std::uint32_t get_uint32(std::size_t i) const;
  std::uint64_t get_uint64(std::size_t i) const;
  std::int32_t get_int32(std::size_t i) const;
  double get_double(std::size_t i) const;
  std::array<double, 3> get_vector3d(std::size_t i) const;
  std::array<double, 6> get_vector6d(std::size_t i) const;
  std::array<std::int32_t, 6> get_vector6int32(std::size_t i) const;
  std::array<std::uint32_t, 6> get_vector6uint32(std::size_t i) const;

  void set_bool(std::size_t i, bool v);
  void set_uint8(std::size_t i, std::uint8_t v);
  void set_uint32(std::size_t i, std::uint32_t v);
  void set_uint64(std::size_t i, std::uint64_t v);
  void set_int32(std::size_t i, std::int32_t v);
  void set_double(std::size_t i, double v);
  void set_vector3d(std::size_t i, const std::array<double, 3>& v);
  void set_vector6d(std::size_t i, const std::array<double, 6>& v);
  void set_vector6int32(std::size_t i, const std::array<std::int32_t, 6>& v);
  void set_vector6uint32(std::size_t i, const std::array<std::uint32_t, 6>& v);

 private:
  // The bytes of field i, after checking its type.
  std::size_t at(std::size_t i, FieldType expected) const;
  std::uint64_t load(std::size_t offset, std::size_t n) const;
  void store(std::size_t offset, std::size_t n, std::uint64_t v);

  const Recipe* recipe_;
  std::vector<std::uint8_t> bytes_;
};

}  // namespace wysiwyf::robot::rtde
