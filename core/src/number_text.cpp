#include "wysiwyf/number_text.hpp"

#include <cstdlib>
#include <iomanip>
#include <limits>
#include <sstream>

namespace wysiwyf {

std::string round_trip_text(double v) {
  for (int p = 6; p <= 17; ++p) {
    std::ostringstream t;
    t << std::setprecision(p) << v;
    if (std::strtod(t.str().c_str(), nullptr) == v) return t.str();  // strtod: no throw on denormals
  }
  std::ostringstream s;  // NaN never compares equal
  s << std::setprecision(std::numeric_limits<double>::max_digits10) << v;
  return s.str();
}

}  // namespace wysiwyf
