#include "contact_outcomes.hpp"

#include <cmath>
#include <limits>

#include "summary_json.hpp"
#include "wysiwyf/kernel_msgs.hpp"

namespace wysiwyf::display {

std::int64_t ContactOutcomes::still_since(const PoseTrack& plate, std::int64_t t) const {
  for (auto it = plate.rbegin(); it != plate.rend(); ++it) {
    if (it->t > t) continue;
    const PoseSample* before = pose_at(plate, it->t - 100'000'000);
    if (before && it->t > before->t &&
        (it->pose.translation() - before->pose.translation()).norm() / ((it->t - before->t) * 1e-9) > still_speed_)
      return it->t;
  }
  return plate.front().t;
}

const msg::ContactReport& ContactOutcomes::measure(const msg::UserEvent& event, std::int64_t t,
                                                   const haptics::Scene& scene, const PoseHistory& poses) {
  msg::ContactReport r;
  fill_header(r.header(), t, reports_.size(), "base");
  r.contact(event.contact());
  r.feature(event.feature());
  r.hit(event.kind() == msg::USER_TOUCH);
  r.still_before_s(-1);
  r.offset_mm(-1);
  r.angle_deg(-1);
  const haptics::DisplayFeature* f = scene.feature(event.feature().c_str());
  const PoseSample* plate = pose_at(poses.plate(), t);
  if (f && plate && !poses.object(static_cast<std::size_t>(f->body)).empty()) {
    r.still_before_s(static_cast<double>(t - still_since(poses.plate(), t)) * 1e-9);
    const Eigen::Isometry3d base_T_obj = pose_at(poses.object(static_cast<std::size_t>(f->body)), t)->pose;
    double best_angle = std::numeric_limits<double>::infinity(), offset = 0;
    for (int k = 0; k < 4; ++k) {
      const Eigen::Isometry3d want =
          base_T_obj * f->obj_T_plate * Eigen::AngleAxisd(k * M_PI / 2, Eigen::Vector3d::UnitZ());
      const double angle = Eigen::Quaterniond(want.linear()).angularDistance(Eigen::Quaterniond(plate->pose.linear()));
      if (angle < best_angle) best_angle = angle, offset = (want.translation() - plate->pose.translation()).norm();
    }
    r.offset_mm(offset * 1e3);
    r.angle_deg(best_angle * 180 / M_PI);
  }
  reports_.push_back(r);
  return reports_.back();
}

std::string ContactOutcomes::line(const msg::ContactReport& r) {
  return "contact " + std::to_string(r.contact()) + " (" + r.feature().c_str() + "): " + (r.hit() ? "hit" : "MISS") +
         ", plate still " + std::to_string(static_cast<int>(r.still_before_s() * 1e3)) + " ms before the finger, " +
         std::to_string(r.offset_mm()) + " mm / " + std::to_string(r.angle_deg()) + " deg from the feature";
}

std::string ContactOutcomes::tally() const {
  int hits = 0;
  for (const auto& r : reports_) hits += r.hit() ? 1 : 0;
  return std::to_string(reports_.size()) + " contact(s), " + std::to_string(hits) + " hit(s)";
}

void ContactOutcomes::write_json(std::ostream& j) const {
  j << "\"contacts\": [";
  for (std::size_t i = 0; i < reports_.size(); ++i) {
    const auto& r = reports_[i];
    j << (i ? "," : "") << "\n    {\"contact\": " << r.contact()
      << ", \"feature\": " << json_quoted(r.feature().c_str()) << ", \"hit\": " << (r.hit() ? "true" : "false")
      << ", \"still_before_ms\": " << json_number(r.still_before_s() * 1e3)
      << ", \"offset_mm\": " << json_number(r.offset_mm()) << ", \"angle_deg\": " << json_number(r.angle_deg()) << "}";
  }
  j << "\n  ]";
}

}  // namespace wysiwyf::display
