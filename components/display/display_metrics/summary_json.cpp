#include "summary_json.hpp"

#include <cmath>
#include <sstream>

namespace wysiwyf::display {

std::string json_number(double v) {
  if (!std::isfinite(v)) return "null";
  std::ostringstream o;
  o.precision(9);
  o << v;
  return o.str();
}

std::string json_quoted(const std::string& text) {
  std::string q = "\"";
  for (char c : text) q += c == '"' || c == '\\' ? std::string("\\") + c : std::string(1, c);
  return q + "\"";
}

std::string json_figures(const stats::Percentiles& p, const std::string& unit, const std::string& prefix) {
  return "\"" + prefix + "p50_" + unit + "\": " + json_number(p.percentile(50)) + ", \"" + prefix + "p99_" + unit +
         "\": " + json_number(p.percentile(99)) + ", \"" + prefix + "max_" + unit + "\": " + json_number(p.max());
}

}  // namespace wysiwyf::display
