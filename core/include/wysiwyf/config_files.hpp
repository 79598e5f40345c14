#pragma once
// Finding a configuration file a parameter names (a robot, a scene, a calibration): the path as
// given (absolute, or relative to the working directory), then each folder of
// $WYSIWYF_CONFIG_PATH (colon-separated), then this tree's config/ folder, then the installed
// share/wysiwyf/config. Throws std::invalid_argument naming every place it looked.
#include <string>

namespace wysiwyf {

std::string find_config_file(const std::string& path);

}  // namespace wysiwyf
