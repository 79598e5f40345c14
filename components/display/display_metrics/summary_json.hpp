#pragma once
// The pieces of the run's summary.json that every measurement writes its section with: numbers
// (non-finite ones as null), quoted strings, and a figure's p50/p99/max members.
#include <string>

#include "stats/percentiles.hpp"

namespace wysiwyf::display {

// `v` with 9 significant digits; "null" when not finite (JSON has no NaN).
std::string json_number(double v);
// `text` in double quotes, with '"' and '\' escaped.
std::string json_quoted(const std::string& text);
// One figure's "<prefix>p50_<unit>", "<prefix>p99_<unit>" and "<prefix>max_<unit>" members.
std::string json_figures(const stats::Percentiles& p, const std::string& unit, const std::string& prefix = "");

}  // namespace wysiwyf::display
