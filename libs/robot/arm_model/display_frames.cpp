#include "arm_model/display_frames.hpp"

#include <stdexcept>

#include <urdf_parser/urdf_parser.h>

namespace wysiwyf::robot {

const std::vector<DisplayFrame>& display_frames() {
  static const std::vector<DisplayFrame> frames = {
      {"flange", "the tool flange the sensor and plate are mounted on"},
      {"ft_sensor", "the wrist force/torque sensor's measuring frame: the user's push on the plate is read there"},
      {"dev", "the plate's front face: where the display puts the plate, and the pose the trackers see"},
      {"marker_0", "lamp 0 of the plate: the camera's pose is tracked from the four lamps"},
      {"marker_1", "lamp 1 of the plate: the camera's pose is tracked from the four lamps"},
      {"marker_2", "lamp 2 of the plate: the camera's pose is tracked from the four lamps"},
      {"marker_3", "lamp 3 of the plate: the camera's pose is tracked from the four lamps"},
      {"knob", "the plate's knob, which displays the virtual knob"},
  };
  return frames;
}

std::string display_frame_purpose(const std::string& name) {
  for (const DisplayFrame& f : display_frames())
    if (name == f.name) return f.purpose;
  return {};
}

std::unique_ptr<ArmModel> load_display_arm(const std::string& urdf_path, const std::string& tip) {
  // urdfdom reads the file once here to name a missing frame; a file it cannot read is left to
  // ArmModel, whose error says what is wrong with it.
  if (const urdf::ModelInterfaceSharedPtr urdf = urdf::parseURDFFile(urdf_path)) {
    for (const DisplayFrame& f : display_frames()) {
      if (urdf->getLink(f.name)) continue;
      std::string links;
      for (const auto& [name, link] : urdf->links_) links += (links.empty() ? "" : ", ") + name;
      throw std::runtime_error(urdf_path + " has no link '" + f.name + "', " + f.purpose +
                               " (the display needs it on every arm; docs/porting.md; the file's links: " + links +
                               ")");
    }
  }
  return std::make_unique<ArmModel>(urdf_path, tip);
}

}  // namespace wysiwyf::robot
