#pragma once
// The instance of a keyed type's sample, computed from its CDR bytes through the type's dynamic
// description (this build's types or a message library), as a writer compiled with the type
// computes it: the player writes keyed topics (the kernel's diagnostics, one instance per
// component) with their keys, so every reader keeps each instance's history apart.
#include <string>

#include "raw_cdr_type.hpp"

namespace wysiwyf::cli {

// The key function of `type_name`, or an empty one with `searched` saying where it was looked
// for when no description of the type is found.
RawCdrType::KeyOf dynamic_key_of(const std::string& type_name, std::string& searched);

}  // namespace wysiwyf::cli
