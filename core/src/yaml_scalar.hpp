#pragma once
// The one set of rules by which a YAML scalar becomes a bool, an integer or a number, for the
// pipeline file's own keys (rate, domain, enabled, ...) and for component parameters alike
// (YAML 1.2 core schema, strict): true/True/TRUE, false/False/FALSE; integers in decimal, 0x
// hex or 0o octal; numbers as integers or decimals with an exponent. No .inf or .nan, no "yes",
// no "1.5" as an integer.
#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <string>

namespace wysiwyf::detail {

bool scalar_to_bool(const YAML::Node& node, bool& out);
bool scalar_to_int64(const YAML::Node& node, std::int64_t& out);
bool scalar_to_int(const YAML::Node& node, int& out);
bool scalar_to_double(const YAML::Node& node, double& out);  // finite only

}  // namespace wysiwyf::detail
