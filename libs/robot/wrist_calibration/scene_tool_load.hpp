#pragma once
// Where the display reads the tool's load: the scene file's device section (tool_mass, kg;
// tool_com, m in the sensor frame), which admittance_sim, the supervisor, the overlay and
// display_metrics take out of every wrench (scene/tool_load.hpp). The calibration rewrites those
// two lines of a scene file's text and leaves every other line, comments included, as it was.
#include <string>

#include <Eigen/Core>

namespace wysiwyf::robot {

// The scene text with its device's tool_mass and tool_com set (each line replaced where it is,
// keeping its comment, or added at the top of the device block). The result is read back as a
// scene and compared; throws std::runtime_error naming `name` when the text has no block-style
// `device:` section, is not a valid scene, or does not read back as written.
std::string with_tool_load(const std::string& scene_text, const std::string& name, double tool_mass,
                           const Eigen::Vector3d& tool_com);

}  // namespace wysiwyf::robot
