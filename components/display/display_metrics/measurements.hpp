#pragma once
// The run's measurements together, each part with its own state, and what is written from all of
// them: the end-of-run log lines, summary.json (one member per measurement, units in the keys) and
// the run report's time-series row. The parts:
//
//   ContactOutcomes         each touch or miss: hit, plate still before the finger, plate offset
//   AttachmentRegistration  the plate against where the attachment holds it on the moving object
//   VisualRegistration      the moving bodies drawn through the tracked camera pose against the true
//   BleedThrough            real device pixels the user sees
//   SetpointTiming          setpoint to motion, sensor sample to setpoint
//   VisualLatency           camera frame to composite
//   ContactTiming           per touch, when the force rose and when the user saw it
//   LoopHealth              the kernel's per-component diagnostics
//
// all measured against PoseHistory: the plate's and the virtual objects' poses by stamp.
#include <string>
#include <vector>

#include "attachment_registration.hpp"
#include "bleed_through.hpp"
#include "contact_outcomes.hpp"
#include "contact_timing.hpp"
#include "loop_health.hpp"
#include "pose_history.hpp"
#include "run_report.hpp"
#include "scene/scene.hpp"
#include "setpoint_timing.hpp"
#include "visual_latency.hpp"
#include "visual_registration.hpp"

namespace wysiwyf::display {

struct Measurements {
  PoseHistory poses;  // the truth the others measure against
  ContactOutcomes contacts;
  AttachmentRegistration haptic;
  VisualRegistration visual;
  BleedThrough bleed;
  SetpointTiming setpoint_timing;
  VisualLatency latency;
  ContactTiming contact_timing;
  LoopHealth health;
  int mode = -1;  // the display's mode (DisplayModeKind) for the time series; -1: none heard

  // With this tick's samples in: the attachment's registration up to now_ns, the visual
  // registration of the images whose true pose has come, the touches' timing; then forgets the
  // forces and frames older than the pose history.
  void measure_until(std::int64_t now_ns, const haptics::Scene& scene);
  // The figures of the run for the log, after the contacts' tally and the last attachment's.
  std::vector<std::string> end_lines() const;
  // The text of summary.json.
  std::string summary_json() const;
  // The latest of each signal at t_s (the cube: the scene's first dynamic body).
  TimeSeriesRow time_series_row(double t_s, const haptics::Scene& scene) const;
};

}  // namespace wysiwyf::display
