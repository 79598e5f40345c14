#pragma once
// A double as the shortest decimal text that reads back as the same value (at least 6
// significant digits): what the tools print (YAML of samples, parameter defaults).
#include <string>

namespace wysiwyf {

std::string round_trip_text(double v);

}  // namespace wysiwyf
