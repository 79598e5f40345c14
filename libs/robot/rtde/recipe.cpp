#include "rtde/recipe.hpp"

#include <cstring>
#include <stdexcept>

namespace wysiwyf::robot::rtde {

Recipe::Recipe(std::uint8_t id, std::vector<std::string> names, std::vector<FieldType> types)
    : id_(id), names_(std::move(names)), types_(std::move(types)) {
  if (names_.size() != types_.size())
    throw std::invalid_argument("RTDE recipe: " + std::to_string(names_.size()) + " names but " +
                                std::to_string(types_.size()) + " types");
  for (std::size_t i = 0; i < names_.size(); ++i) {
    if (names_[i].empty()) throw std::invalid_argument("RTDE recipe: field " + std::to_string(i) + " has no name");
    for (std::size_t j = 0; j < i; ++j)
      if (names_[j] == names_[i]) throw std::invalid_argument("RTDE recipe: field '" + names_[i] + "' twice");
    offsets_.push_back(values_size_);
    values_size_ += field_size(types_[i]);
  }
  if (kHeaderSize + 1 + values_size_ > kMaxPackageSize)
    throw std::invalid_argument("RTDE recipe: a package of its " + std::to_string(names_.size()) + " fields is " +
                                std::to_string(kHeaderSize + 1 + values_size_) + " bytes, over the " +
                                std::to_string(kMaxPackageSize) + " this reader accepts");
}

std::optional<std::size_t> Recipe::index(std::string_view name) const {
  for (std::size_t i = 0; i < names_.size(); ++i)
    if (names_[i] == name) return i;
  return std::nullopt;
}

RecipeValues::RecipeValues(const Recipe& recipe) : recipe_(&recipe), bytes_(recipe.values_size(), 0) {}

bool RecipeValues::read(const std::uint8_t* payload, std::size_t size) {
  if (size != 1 + recipe_->values_size() || payload[0] != recipe_->id()) return false;
  for (std::size_t i = 0; i < recipe_->size(); ++i)
    if (recipe_->type(i) == FieldType::kBool && payload[1 + recipe_->offset(i)] > 1) return false;
  std::memcpy(bytes_.data(), payload + 1, recipe_->values_size());
  return true;
}

std::size_t RecipeValues::at(std::size_t i, FieldType expected) const {
  if (i >= recipe_->size() || recipe_->type(i) != expected)
    throw std::invalid_argument(
        "RTDE recipe " + std::to_string(recipe_->id()) + ": field " + std::to_string(i) +
        (i < recipe_->size() ? " ('" + recipe_->name(i) + "') is " + to_string(recipe_->type(i)) : " does not exist") +
        ", read or written as " + to_string(expected));
  return recipe_->offset(i);
}

std::uint64_t RecipeValues::load(std::size_t offset, std::size_t n) const {
  std::uint64_t v = 0;
  for (std::size_t k = 0; k < n; ++k) v = (v << 8) | bytes_[offset + k];
  return v;
}

void RecipeValues::store(std::size_t offset, std::size_t n, std::uint64_t v) {
  for (std::size_t k = n; k-- > 0; v >>= 8) bytes_[offset + k] = static_cast<std::uint8_t>(v);
}

namespace {
double to_double(std::uint64_t bits) {
  double v;
  std::memcpy(&v, &bits, sizeof v);
  return v;
}
std::uint64_t to_bits(double v) {
  std::uint64_t bits;
  std::memcpy(&bits, &v, sizeof bits);
  return bits;
}
}  // namespace

bool RecipeValues::get_bool(std::size_t i) const { return load(at(i, FieldType::kBool), 1) != 0; }
std::uint8_t RecipeValues::get_uint8(std::size_t i) const {
  return static_cast<std::uint8_t>(load(at(i, FieldType::kUint8), 1));
}
std::uint32_t RecipeValues::get_uint32(std::size_t i) const {
  return static_cast<std::uint32_t>(load(at(i, FieldType::kUint32), 4));
}
std::uint64_t RecipeValues::get_uint64(std::size_t i) const { return load(at(i, FieldType::kUint64), 8); }
std::int32_t RecipeValues::get_int32(std::size_t i) const {
  return static_cast<std::int32_t>(static_cast<std::uint32_t>(load(at(i, FieldType::kInt32), 4)));
}
double RecipeValues::get_double(std::size_t i) const { return to_double(load(at(i, FieldType::kDouble), 8)); }

std::array<double, 3> RecipeValues::get_vector3d(std::size_t i) const {
  const std::size_t o = at(i, FieldType::kVector3d);
  return {to_double(load(o, 8)), to_double(load(o + 8, 8)), to_double(load(o + 16, 8))};
}

std::array<double, 6> RecipeValues::get_vector6d(std::size_t i) const {
  const std::size_t o = at(i, FieldType::kVector6d);
  std::array<double, 6> v{};
  for (std::size_t k = 0; k < 6; ++k) v[k] = to_double(load(o + 8 * k, 8));
  return v;
}

std::array<std::int32_t, 6> RecipeValues::get_vector6int32(std::size_t i) const {
  const std::size_t o = at(i, FieldType::kVector6Int32);
  std::array<std::int32_t, 6> v{};
  for (std::size_t k = 0; k < 6; ++k) v[k] = static_cast<std::int32_t>(static_cast<std::uint32_t>(load(o + 4 * k, 4)));
  return v;
}

std::array<std::uint32_t, 6> RecipeValues::get_vector6uint32(std::size_t i) const {
  const std::size_t o = at(i, FieldType::kVector6Uint32);
  std::array<std::uint32_t, 6> v{};
  for (std::size_t k = 0; k < 6; ++k) v[k] = static_cast<std::uint32_t>(load(o + 4 * k, 4));
  return v;
}

void RecipeValues::set_bool(std::size_t i, bool v) { store(at(i, FieldType::kBool), 1, v ? 1 : 0); }
void RecipeValues::set_uint8(std::size_t i, std::uint8_t v) { store(at(i, FieldType::kUint8), 1, v); }
void RecipeValues::set_uint32(std::size_t i, std::uint32_t v) { store(at(i, FieldType::kUint32), 4, v); }
void RecipeValues::set_uint64(std::size_t i, std::uint64_t v) { store(at(i, FieldType::kUint64), 8, v); }
void RecipeValues::set_int32(std::size_t i, std::int32_t v) {
  store(at(i, FieldType::kInt32), 4, static_cast<std::uint32_t>(v));
}
void RecipeValues::set_double(std::size_t i, double v) { store(at(i, FieldType::kDouble), 8, to_bits(v)); }

void RecipeValues::set_vector3d(std::size_t i, const std::array<double, 3>& v) {
  const std::size_t o = at(i, FieldType::kVector3d);
  for (std::size_t k = 0; k < 3; ++k) store(o + 8 * k, 8, to_bits(v[k]));
}

void RecipeValues::set_vector6d(std::size_t i, const std::array<double, 6>& v) {
  const std::size_t o = at(i, FieldType::kVector6d);
  for (std::size_t k = 0; k < 6; ++k) store(o + 8 * k, 8, to_bits(v[k]));
}

void RecipeValues::set_vector6int32(std::size_t i, const std::array<std::int32_t, 6>& v) {
  const std::size_t o = at(i, FieldType::kVector6Int32);
  for (std::size_t k = 0; k < 6; ++k) store(o + 4 * k, 4, static_cast<std::uint32_t>(v[k]));
}

void RecipeValues::set_vector6uint32(std::size_t i, const std::array<std::uint32_t, 6>& v) {
  const std::size_t o = at(i, FieldType::kVector6Uint32);
  for (std::size_t k = 0; k < 6; ++k) store(o + 4 * k, 4, v[k]);
}

}  // namespace wysiwyf::robot::rtde
