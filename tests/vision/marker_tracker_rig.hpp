#pragma once
// The marker tracker's test rig: camera_sim filming the arm, and marker_tracker instances fed
// its images, camera info and the joints (through the component Harness), with what each said
// about the last image and the camera's ground truth beside it.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "puma_model/puma_model.hpp"
#include "wysiwyf/harness.hpp"
#include "wysiwyf/msg_eigen.hpp"

namespace wysiwyf::vision::tracker_rig {

constexpr std::int64_t kFrameNs = 40'000'000;  // 25 Hz

inline std::string config(const std::string& file) { return std::string(WYSIWYF_CONFIG_DIR) + "/" + file; }

inline double translation_error(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return (a.translation() - b.translation()).norm();
}
inline double rotation_error_deg(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return Eigen::AngleAxisd(a.linear().transpose() * b.linear()).angle() * 180.0 / M_PI;
}

// One tracker instance beside the camera, and what it said about the last image.
struct Tracker {
  Tracker(const std::string& params)
      : h("marker_tracker", params, 25),
        image(h.feed<msg::Image>("image")),
        info(h.feed<msg::CameraInfo>("camera_info")),
        joints(h.feed<msg::JointState>("joint_state")),
        eye_T_base(h.watch<msg::PoseStamped>("eye_T_base")),
        eye_T_dev(h.watch<msg::PoseStamped>("eye_T_dev")),
        markers(h.watch<msg::MarkerObservation>("markers")),
        base_cov(h.watch<msg::PoseWithCovariance>("eye_T_base_covariance")) {
    h.activate();
  }
  Harness h;
  Output<msg::Image> image;
  Output<msg::CameraInfo> info;
  Output<msg::JointState> joints;
  Input<msg::PoseStamped> eye_T_base, eye_T_dev;
  Input<msg::MarkerObservation> markers;
  Input<msg::PoseWithCovariance> base_cov;
  // After the last image:
  bool has_pose = false;
  Eigen::Isometry3d base = Eigen::Isometry3d::Identity(), dev = Eigen::Isometry3d::Identity();
  msg::MarkerObservation obs;
  Eigen::Matrix<double, 6, 1> base_sigma = Eigen::Matrix<double, 6, 1>::Zero();  // of eye_T_base (m, rad)
};

// camera_sim filming the arm as it follows `joints_at(t)`, feeding every tracker.
class Rig {
 public:
  Rig(const std::string& camera_params, std::vector<std::string> tracker_params)
      : model_(config("robots/puma560.urdf"), "flange"), cam_("camera_sim", camera_params, 25) {
    joints_in_ = cam_.feed<msg::JointState>("joint_state");
    image_ = cam_.watch<msg::Image>("image");
    info_ = cam_.watch<msg::CameraInfo>("camera_info");
    true_base_ = cam_.watch<msg::PoseStamped>("true_eye_T_base");
    true_dev_ = cam_.watch<msg::PoseStamped>("true_eye_T_dev");
    cam_.activate();
    for (const auto& p : tracker_params) trackers_.push_back(std::make_unique<Tracker>(p));
  }

  const robot::PumaModel& model() const { return model_; }
  Tracker& tracker(std::size_t i) { return *trackers_[i]; }

  // One frame at time frame * 40 ms; `edit` may change the image before the trackers see it;
  // `told` (when given) are the joints the trackers are told instead of q (a faulty encoder).
  void step(int frame, const robot::Vector6d& q, const std::function<void(cv::Mat&)>& edit = {},
            const robot::Vector6d* told = nullptr) {
    const Time now{frame * kFrameNs};
    msg::JointState js;
    js.header().stamp_ns(now.ns);
    js.position().resize(6);
    for (int i = 0; i < 6; ++i) js.position()[static_cast<std::size_t>(i)] = q[i];
    joints_in_.write(js);
    msg::JointState told_js = js;
    if (told)
      for (int i = 0; i < 6; ++i) told_js.position()[static_cast<std::size_t>(i)] = (*told)[i];
    cam_.tick(now);
    ASSERT_TRUE(image_.take_latest(img_));
    ASSERT_TRUE(info_.take_latest(info_msg_));
    msg::PoseStamped p;
    ASSERT_TRUE(true_base_.take_latest(p));
    truth_base_ = msgs::to_isometry(p.pose());
    ASSERT_TRUE(true_dev_.take_latest(p));
    truth_dev_ = msgs::to_isometry(p.pose());
    if (edit) {
      cv::Mat rgb(static_cast<int>(img_.height()), static_cast<int>(img_.width()), CV_8UC3, img_.data().data());
      edit(rgb);
    }
    for (auto& t : trackers_) {
      t->joints.write(told ? told_js : js);
      t->info.write(info_msg_);
      t->image.write(img_);
      t->h.tick(now);
      ASSERT_TRUE(t->markers.take_latest(t->obs)) << "the tracker reports on every image";
      t->has_pose = t->eye_T_base.take_latest(p);
      if (t->has_pose) t->base = msgs::to_isometry(p.pose());
      if (t->eye_T_dev.take_latest(p)) t->dev = msgs::to_isometry(p.pose());
      msg::PoseWithCovariance c;
      if (t->base_cov.take_latest(c))
        for (int i = 0; i < 6; ++i) t->base_sigma[i] = std::sqrt(c.covariance()[static_cast<std::size_t>(7 * i)]);
    }
  }

  const Eigen::Isometry3d& truth_base() const { return truth_base_; }
  const Eigen::Isometry3d& truth_dev() const { return truth_dev_; }
  // Where marker i's centre is in the image now (ground truth).
  cv::Point2d true_pixel(const robot::Vector6d& q, int i) const {
    const Eigen::Vector3d p = truth_base_ * model_.fk(q, model_.frame("marker_" + std::to_string(i))).translation();
    return {600 * p.x() / p.z() + 319.5, 600 * p.y() / p.z() + 239.5};
  }

 private:
  robot::PumaModel model_;
  Harness cam_;
  Output<msg::JointState> joints_in_;
  Input<msg::Image> image_;
  Input<msg::CameraInfo> info_;
  Input<msg::PoseStamped> true_base_, true_dev_;
  std::vector<std::unique_ptr<Tracker>> trackers_;
  msg::Image img_;
  msg::CameraInfo info_msg_;
  Eigen::Isometry3d truth_base_ = Eigen::Isometry3d::Identity(), truth_dev_ = Eigen::Isometry3d::Identity();
};

}  // namespace wysiwyf::vision::tracker_rig
