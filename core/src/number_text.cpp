#include "wysiwyf/number_text.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>

namespace wysiwyf {

std::string round_trip_text(double v) {
  char text[64];
  if (!std::isfinite(v)) {  // "nan", "-nan", "inf", "-inf", as printf
    const auto end = std::to_chars(text, text + sizeof text, v, std::chars_format::general).ptr;
    return std::string(text, end);
  }
  // The significant digits of the shortest text that reads back as v (Ryu, in the standard
  // library), then printf's %.Ng with N of them and at least 6: the closest N-digit decimal reads
  // back too. (No search over N through streams and strtod: `topic echo` formats every number of
  // a 1 kHz stream here.)
  const char* begin = text;
  const char* shortest_end = std::to_chars(text, text + sizeof text, v, std::chars_format::scientific).ptr;
  const char* exponent = std::find(begin, shortest_end, 'e');
  const int digits = static_cast<int>(std::count_if(begin, exponent, [](char c) { return c >= '0' && c <= '9'; }));
  const auto end = std::to_chars(text, text + sizeof text, v, std::chars_format::general, std::max(6, digits)).ptr;
  return std::string(text, end);
}

}  // namespace wysiwyf
