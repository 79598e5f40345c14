#pragma once
// Where the kernel looks for component libraries, message libraries and configuration files, the
// same way in a build tree and in an installed prefix: next to the running program (a test finds
// the components built beside it), next to libwysiwyf_core.so (lib/wysiwyf/ and
// share/wysiwyf/config/ of its prefix), and first in the folders of an environment variable.
#include <string>
#include <vector>

namespace wysiwyf {

// $WYSIWYF_COMPONENT_PATH, then <program dir>/lib/wysiwyf, <program dir>/../lib/wysiwyf, then
// <core library dir>/wysiwyf (existing folders only, no repeats).
std::vector<std::string> component_search_dirs();

// <dir>/messages of every component folder: message libraries (wysiwyf_add_messages).
std::vector<std::string> message_library_dirs();

// $WYSIWYF_CONFIG_PATH, then the prefix's share/wysiwyf/config, then (a build tree's core only)
// the source tree's config/.
std::vector<std::string> config_search_dirs();

// $WYSIWYF_IDL_PATH, then the prefix's share/wysiwyf/idl, then (a build tree's core only) the
// source tree's interfaces/kernel and interfaces/msgs: the IDL that monitoring tools give as
// schemas.
std::vector<std::string> idl_search_dirs();

// The folder of libwysiwyf_core.so, and of the running program (empty when unknown).
std::string core_library_dir();
std::string program_dir();

}  // namespace wysiwyf
