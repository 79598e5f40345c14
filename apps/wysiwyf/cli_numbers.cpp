// The command line's number options: one check for every command.
#include <cmath>

#include "cli.hpp"

namespace wysiwyf::cli {

double number_option(Args& args, const std::string& name, double fallback, double min, double max,
                     const std::string& expected) {
  const auto v = args.value(name);
  if (!v) return fallback;
  try {
    std::size_t used = 0;
    const double x = std::stod(*v, &used);
    if (used == v->size() && std::isfinite(x) && x >= min && x <= max) return x;
  } catch (const std::logic_error&) {  // std::invalid_argument, std::out_of_range
  }
  throw UsageError(name + ": found '" + *v + "'; expected " + expected);
}

long whole_option(Args& args, const std::string& name, long fallback, long min, long max, const std::string& expected) {
  const auto v = args.value(name);
  if (!v) return fallback;
  try {
    std::size_t used = 0;
    const long x = std::stol(*v, &used);
    if (used == v->size() && x >= min && x <= max) return x;
  } catch (const std::logic_error&) {
  }
  throw UsageError(name + ": found '" + *v + "'; expected " + expected);
}

}  // namespace wysiwyf::cli
