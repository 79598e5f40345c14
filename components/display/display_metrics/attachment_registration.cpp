#include "attachment_registration.hpp"

#include <algorithm>

#include "summary_json.hpp"
#include "wysiwyf/kernel_msgs.hpp"

namespace wysiwyf::display {

void AttachmentRegistration::force(double newton) {
  if (attachment_) attachment_->peak_force = std::max(attachment_->peak_force, newton);
}

void AttachmentRegistration::attach(std::size_t body, const Eigen::Isometry3d& obj_T_dev, const std::string& feature,
                                    std::int64_t t) {
  attachment_.emplace();
  attachment_->body = body;
  attachment_->obj_T_dev = obj_T_dev;
  attachment_->feature = feature;
  attachment_->since = t;
  attachment_->measured_until = t - 1;
}

void AttachmentRegistration::measure_until(std::int64_t t, const PoseHistory& poses) {
  Attachment& a = *attachment_;
  const PoseTrack& object = poses.object(a.body);
  if (object.empty()) return;
  t = std::min(t, object.back().t);
  const PoseTrack& plate = poses.plate();
  const std::int64_t from = std::max(a.measured_until, a.since - 1);
  for (auto it = std::upper_bound(plate.begin(), plate.end(), from,
                                  [](std::int64_t v, const PoseSample&s) { return v < s.t; });
       it != plate.end() && it->t <= t; ++it) {
    const PoseSample& s = *it;
    const Eigen::Isometry3d want = pose_at(object, s.t)->pose * a.obj_T_dev;
    const RegistrationError e = registration_error(want, s.pose);
    a.overshoot = std::max(a.overshoot, -(want.inverse() * s.pose.translation()).z());  // (z: out of the face)
    last_mm_ = e.mm;
    a.all.add(e, s.t);
    run_.add(e, s.t);
    if (s.t - a.since <= onset_window_ns_) a.onset.add(e, s.t);
    a.measured_until = s.t;
  }
}

AttachmentRegistration::Detached AttachmentRegistration::detach(std::int64_t t) {
  const Attachment& a = *attachment_;
  msg::HapticRegistration r;
  fill_header(r.header(), t, seq_++, "base");
  r.contact(contact_);
  r.feature(a.feature);
  r.samples(static_cast<std::uint32_t>(a.all.mm.samples()));
  r.p50_mm(a.all.mm.percentile(50));
  r.p99_mm(a.all.mm.percentile(99));
  r.max_mm(a.all.mm.max());
  r.max_deg(a.all.deg.max());
  r.onset_max_mm(a.onset.mm.max());
  r.onset_max_deg(a.onset.deg.max());
  r.peak_force_n(a.peak_force);
  r.push_force_n(push_force_);
  r.overshoot_mm(a.overshoot * 1e3);
  registrations_.push_back(r);
  std::string line =
      "contact " + std::to_string(contact_) + " (" + a.feature + ") attached " +
      std::to_string(static_cast<double>(t - a.since) * 1e-9) + " s: plate from the held feature p50 " +
      std::to_string(r.p50_mm()) + " mm, p99 " + std::to_string(r.p99_mm()) + " mm, max " + std::to_string(r.max_mm()) +
      " mm (at " + std::to_string(static_cast<double>(a.all.mm.max_at()) * 1e-9) + " s) / " +
      std::to_string(r.max_deg()) + " deg; onset max " + std::to_string(r.onset_max_mm()) + " mm / " +
      std::to_string(r.onset_max_deg()) + " deg; peak force " + std::to_string(r.peak_force_n()) + " N (push " +
      std::to_string(r.push_force_n()) + " N); deepest past the face " + std::to_string(r.overshoot_mm()) + " mm";
  attachment_.reset();
  return {r, line};
}

std::string AttachmentRegistration::run_line() const {
  if (run_.mm.samples() == 0) return "";
  return "haptic registration while attached, the whole run: p50 " + std::to_string(run_.mm.percentile(50)) +
         " mm, p99 " + std::to_string(run_.mm.percentile(99)) + " mm, max " + std::to_string(run_.mm.max()) + " mm / " +
         std::to_string(run_.deg.max()) + " deg over " + std::to_string(run_.mm.samples()) + " samples";
}

void AttachmentRegistration::write_json(std::ostream& j) const {
  j << "\"haptic_registration\": {\n    \"attachments\": [";
  for (std::size_t i = 0; i < registrations_.size(); ++i) {
    const auto& r = registrations_[i];
    j << (i ? "," : "") << "\n      {\"contact\": " << r.contact()
      << ", \"feature\": " << json_quoted(r.feature().c_str()) << ", \"samples\": " << r.samples()
      << ", \"p50_mm\": " << json_number(r.p50_mm()) << ", \"p99_mm\": " << json_number(r.p99_mm())
      << ", \"max_mm\": " << json_number(r.max_mm()) << ", \"max_deg\": " << json_number(r.max_deg())
      << ", \"onset_max_mm\": " << json_number(r.onset_max_mm())
      << ", \"onset_max_deg\": " << json_number(r.onset_max_deg())
      << ", \"peak_force_n\": " << json_number(r.peak_force_n())
      << ", \"push_force_n\": " << json_number(r.push_force_n())
      << ", \"overshoot_mm\": " << json_number(r.overshoot_mm()) << "}";
  }
  double overshoot = 0;
  for (const auto& r : registrations_) overshoot = std::max(overshoot, r.overshoot_mm());
  j << "\n    ],\n    \"run\": {\"samples\": " << run_.mm.samples() << ", " << json_figures(run_.mm, "mm")
    << ", \"max_deg\": " << json_number(run_.deg.max()) << ", \"overshoot_mm\": " << json_number(overshoot) << "}\n  }";
}

}  // namespace wysiwyf::display
