#pragma once
// Haptic registration: while the device is attached to a virtual object (the supervisor's
// Attachment), every plate pose against where the attachment holds it on the moving object
// (base_T_obj * obj_T_dev at the plate sample's stamp): p50/p99/max per attachment and over the
// run, the largest over the attachment's first onset_window (the object starting to move under
// the push, the arm following), how deep the plate went past the held face, and the user's peak
// force. One HapticRegistration when the device lets go.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "pose_history.hpp"
#include "registration_stats.hpp"
#include "wysiwyf/msgs.hpp"

namespace wysiwyf::display {

class AttachmentRegistration {
 public:
  explicit AttachmentRegistration(std::int64_t onset_window_ns = 0) : onset_window_ns_(onset_window_ns) {}

  // The contact the user is on (the latest touch) and the force they push with (their PUSH event),
  // reported with the attachment.
  void set_contact(std::uint32_t contact) { contact_ = contact; }
  void set_push_force(double newton) { push_force_ = newton; }
  // The user's force now (N): the attachment's peak force.
  void force(double newton);

  bool attached() const { return attachment_.has_value(); }
  // The device holds `body` at obj_T_dev from t on.
  void attach(std::size_t body, const Eigen::Isometry3d& obj_T_dev, const std::string& feature, std::int64_t t);
  // Measures every plate sample since the last one measured, up to t and to the newest object pose.
  void measure_until(std::int64_t t, const PoseHistory& poses);
  struct Detached {
    msg::HapticRegistration registration;
    std::string line;  // for the log
  };
  // The device let go at t: the attachment's figures (kept for the summary).
  Detached detach(std::int64_t t);

  // The latest plate sample's error while attached (for the time series); none when not attached.
  std::optional<double> latest_mm() const { return attached() ? last_mm_ : std::nullopt; }
  // The whole run's figures, for the log; empty without any sample.
  std::string run_line() const;
  // The summary's "haptic_registration" member.
  void write_json(std::ostream& j) const;

 private:
  struct Attachment {
    std::size_t body = 0;
    Eigen::Isometry3d obj_T_dev = Eigen::Isometry3d::Identity();
    std::string feature;
    std::int64_t since = 0, measured_until = 0;
    RegistrationStats all, onset;
    double peak_force = -1;  // N, the user's largest force while attached (-1: no wrench)
    double overshoot = 0;    // m, the plate's deepest past the held face (along its normal, into the object)
  };

  std::int64_t onset_window_ns_;
  std::optional<Attachment> attachment_;
  RegistrationStats run_;
  std::optional<double> last_mm_;
  std::uint32_t contact_ = 0;
  double push_force_ = -1;  // N, the user's last push target (-1: none)
  std::uint64_t seq_ = 0;
  std::vector<msg::HapticRegistration> registrations_;
};

}  // namespace wysiwyf::display
