#pragma once
/// @file
/// Finding a configuration file a parameter names (a robot, a scene, a calibration): the path as
/// given (absolute, or relative to the working directory), then each folder of
/// config_search_dirs() ($WYSIWYF_CONFIG_PATH, the prefix's share/wysiwyf/config, a build tree's
/// config/). Throws std::invalid_argument naming every place it looked.
#include <string>

namespace wysiwyf {

/// The configuration file `path` names: the path as given (absolute, or relative to the working
/// directory), then `path` in each folder of config_search_dirs(). Throws std::invalid_argument
/// naming every place it looked.
std::string find_config_file(const std::string& path);

/// `relative` in the first of config_search_dirs() that has it; empty when none does.
std::string find_in_config_dirs(const std::string& relative);

}  // namespace wysiwyf
