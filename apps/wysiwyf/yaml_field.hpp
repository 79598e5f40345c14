#pragma once
// `topic echo --field a.b.c`: one field of a sample printed as YAML (cdr_to_yaml's text).
#include <string>

namespace wysiwyf::cli {

// The field at `path` ("header.stamp", "position.0", "position[0]": a member by name, a sequence
// element by index) of a YAML mapping, as YAML text: a scalar on one line, else its block. Throws
// std::invalid_argument naming the part of the path that is not there and what is (with the
// closest name).
std::string yaml_field(const std::string& yaml, const std::string& path);

}  // namespace wysiwyf::cli
