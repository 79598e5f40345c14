#include "visual_registration.hpp"

#include <algorithm>

#include "summary_json.hpp"

namespace wysiwyf::display {

void VisualRegistration::measure(const haptics::Scene& scene, const PoseHistory& poses) {
  while (true_poses_.size() > kKept) true_poses_.pop_front();
  // No pixels without intrinsics; no truth on real hardware: nothing to keep.
  while (!tracked_.empty() && (!(K_[0] > 0) || tracked_.size() > kKept)) tracked_.pop_front();
  while (!tracked_.empty()) {
    const PoseSample& drawn = tracked_.front();
    const auto truth =
        std::find_if(true_poses_.begin(), true_poses_.end(), [&](const PoseSample& s) { return s.t == drawn.t; });
    if (truth == true_poses_.end()) {
      if (true_poses_.empty() || true_poses_.back().t <= drawn.t) break;  // may still come
      tracked_.pop_front();                                               // never coming
      continue;
    }
    corners_.clear();
    for (std::size_t b = 0; b < scene.models.size(); ++b) {
      if (!scene.models[b].dynamic || poses.object(b).empty()) continue;
      const Eigen::Isometry3d base_T_obj = pose_at(poses.object(b), drawn.t)->pose;
      const Eigen::Vector3d h = scene.models[b].half_extents;
      for (int c = 0; c < 8; ++c)
        corners_.push_back(base_T_obj *
                           Eigen::Vector3d(c & 1 ? h.x() : -h.x(), c & 2 ? h.y() : -h.y(), c & 4 ? h.z() : -h.z()));
    }
    if (!corners_.empty()) {
      const VisualError e = visual_error(drawn.pose, truth->pose, corners_, K_);
      mm_.add(e.mm, drawn.t);
      last_mm_ = e.mm;
      px_.add(e.px, drawn.t);
    }
    tracked_.pop_front();
  }
}

std::string VisualRegistration::end_line() const {
  if (mm_.samples() == 0) return "";
  return "visual registration (the moving bodies' corners, tracked against true camera pose) over " +
         std::to_string(mm_.samples()) + " images: p50 " + std::to_string(mm_.percentile(50)) + " mm / " +
         std::to_string(px_.percentile(50)) + " px, p99 " + std::to_string(mm_.percentile(99)) + " mm / " +
         std::to_string(px_.percentile(99)) + " px, max " + std::to_string(mm_.max()) + " mm / " +
         std::to_string(px_.max()) + " px";
}

void VisualRegistration::write_json(std::ostream& j) const {
  j << "\"visual_registration\": {\"images\": " << mm_.samples() << ", " << json_figures(mm_, "mm") << ", "
    << json_figures(px_, "px") << "}";
}

}  // namespace wysiwyf::display
