#include "yaml_scalar.hpp"

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <limits>

namespace wysiwyf::detail {

bool scalar_to_bool(const YAML::Node& node, bool& out) {
  if (!node.IsScalar()) return false;
  const std::string& s = node.Scalar();
  if (s == "true" || s == "True" || s == "TRUE") return out = true, true;
  if (s == "false" || s == "False" || s == "FALSE") return out = false, true;
  return false;
}

bool scalar_to_int64(const YAML::Node& node, std::int64_t& out) {
  if (!node.IsScalar()) return false;
  const std::string& s = node.Scalar();
  std::size_t i = 0;
  bool negative = false;
  if (i < s.size() && (s[i] == '+' || s[i] == '-')) negative = s[i++] == '-';
  int base = 10;
  if (s.compare(i, 2, "0x") == 0)
    base = 16, i += 2;
  else if (s.compare(i, 2, "0o") == 0)
    base = 8, i += 2;
  if (i >= s.size()) return false;
  for (std::size_t k = i; k < s.size(); ++k) {
    const char c = s[k];
    const bool ok = base == 16  ? std::isxdigit(static_cast<unsigned char>(c)) != 0
                    : base == 8 ? (c >= '0' && c <= '7')
                                : (c >= '0' && c <= '9');
    if (!ok) return false;
  }
  errno = 0;
  const unsigned long long magnitude = std::strtoull(s.c_str() + i, nullptr, base);
  if (errno == ERANGE) return false;
  const auto max = static_cast<unsigned long long>(std::numeric_limits<std::int64_t>::max());
  if (magnitude > max + (negative ? 1 : 0)) return false;
  out = negative ? static_cast<std::int64_t>(0 - magnitude) : static_cast<std::int64_t>(magnitude);
  return true;
}

bool scalar_to_int(const YAML::Node& node, int& out) {
  std::int64_t v = 0;
  if (!scalar_to_int64(node, v) || v < std::numeric_limits<int>::min() || v > std::numeric_limits<int>::max())
    return false;
  out = static_cast<int>(v);
  return true;
}

bool scalar_to_double(const YAML::Node& node, double& out) {
  std::int64_t integer = 0;
  if (scalar_to_int64(node, integer)) return out = static_cast<double>(integer), true;
  if (!node.IsScalar()) return false;
  // [-+]? (digits [. digits?] | . digits) ([eE] [-+]? digits)?
  const std::string& s = node.Scalar();
  std::size_t i = 0, digits = 0;
  if (i < s.size() && (s[i] == '+' || s[i] == '-')) ++i;
  for (; i < s.size() && std::isdigit(static_cast<unsigned char>(s[i])); ++i) ++digits;
  if (i < s.size() && s[i] == '.')
    for (++i; i < s.size() && std::isdigit(static_cast<unsigned char>(s[i])); ++i) ++digits;
  if (digits == 0) return false;
  if (i < s.size() && (s[i] == 'e' || s[i] == 'E')) {
    ++i;
    if (i < s.size() && (s[i] == '+' || s[i] == '-')) ++i;
    std::size_t exponent_digits = 0;
    for (; i < s.size() && std::isdigit(static_cast<unsigned char>(s[i])); ++i) ++exponent_digits;
    if (exponent_digits == 0) return false;
  }
  if (i != s.size()) return false;
  const double v = std::strtod(s.c_str(), nullptr);
  if (!std::isfinite(v)) return false;
  out = v;
  return true;
}

}  // namespace wysiwyf::detail
