#pragma once
// The frames the display needs on its arm, whatever the arm: the wrist sensor, the plate, its
// four lamps and its knob, each a URDF link fixed to the arm's last body, with what each is for.
// A lab's URDF that lacks one is refused by name, file and purpose before anything moves.
#include <memory>
#include <string>
#include <vector>

#include "arm_model/arm_model.hpp"

namespace wysiwyf::robot {

struct DisplayFrame {
  const char* name;     // the URDF link
  const char* purpose;  // what the display uses it for
};

// Every frame the display reads, in the order a URDF usually lists them.
const std::vector<DisplayFrame>& display_frames();

// What the display uses frame `name` for, or "" when it is none of display_frames().
std::string display_frame_purpose(const std::string& name);

// Loads the arm of `urdf_path` with its tip frame after checking that the file has every link of
// display_frames(). Throws std::runtime_error naming the file, the first missing frame and what it
// is for (and the file's links), or the model's own error for anything else.
std::unique_ptr<ArmModel> load_display_arm(const std::string& urdf_path, const std::string& tip);

}  // namespace wysiwyf::robot
