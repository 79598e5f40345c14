#pragma once
// The emulators' numeric options: the whole text must be a finite number in range, or the
// option is refused with what was given and what was expected (never std::stoi's bare "stoi").
#include <cmath>
#include <cstddef>
#include <sstream>
#include <stdexcept>
#include <string>

namespace wysiwyf::apps {

inline double option_number(const std::string& option, const std::string& text, double min, double max) {
  std::size_t used = 0;
  double value = std::nan("");
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text.size() || !std::isfinite(value) || value < min || value > max) {
    std::ostringstream expected;
    expected << "expected a number from " << min << " to " << max;
    throw std::invalid_argument(option + " '" + text + "': " + expected.str());
  }
  return value;
}

inline int option_whole(const std::string& option, const std::string& text, int min, int max) {
  const double value = option_number(option, text, min, max);
  if (value != std::floor(value)) throw std::invalid_argument(option + " '" + text + "': expected a whole number");
  return static_cast<int>(value);
}

}  // namespace wysiwyf::apps
