// surface_planner: its inputs taken and checked, its setpoint and status written.
#include "surface_planner.hpp"

#include "wysiwyf/msg_checks.hpp"

#include <cmath>
#include <string>

namespace wysiwyf::display {

void SurfacePlanner::read_inputs(std::int64_t now_ns) {
  while (take_checked(hand_in_, hand_msg_)) {
    if (hand_msg_.status() == msg::TRACKING_LOST) continue;
    if (std::string why = msgs::frame_problem(hand_msg_.header(), "base"); !why.empty()) {
      reject(hand_in_, why + " (a tracker that does not know the camera's pose yet?)");
      continue;
    }
    const std::int64_t stamp = hand_msg_.header().stamp_ns() ? hand_msg_.header().stamp_ns() : now_ns;
    // A hand stamped ahead of now would stay "known" until long after it is gone.
    if (elapsed_ns(stamp, now_ns) > hand_max_lead_ns_) {
      reject(hand_in_, "stamped " + std::to_string(seconds(elapsed_ns(stamp, now_ns))) +
                           " s ahead of this pipeline's clock (hand_max_lead)");
      continue;
    }
    const Vec3 p = msgs::to_eigen(hand_msg_.position());
    const double variance =
        std::max(1e-8, (hand_msg_.covariance()[0] + hand_msg_.covariance()[4] + hand_msg_.covariance()[8]) / 3);
    hand_.update(stamp, p, variance);
  }
  while (take_checked(objects_in_, object_msg_)) {
    const int body = scene_.body_index(object_msg_.child_frame_id().c_str());
    if (body < 0) continue;
    base_T_obj_[static_cast<std::size_t>(body)] = msgs::to_isometry(object_msg_.pose());
  }
  while (take_checked(joints_in_, joints_msg_)) {
    if (std::string why = msgs::joint_positions(joints_msg_, model_->dof(), q_); !why.empty()) {
      reject(joints_in_, why);
      continue;
    }
    have_joints_ = true, joints_ns_ = now_ns;
  }
  while (take_checked(device_in_, device_msg_)) {
    const Eigen::Isometry3d T = msgs::to_isometry(device_msg_.pose());
    device_ = T, have_device_ = true, device_ns_ = now_ns;
    // The plate's speed over the last 100 ms (one encoder step moves it 0.06 mm: per sample,
    // quantisation alone would read as centimetres a second).
    device_history_.push_back({now_ns, T.translation()});
    while (device_history_.size() > 2 && now_ns - device_history_[1].first >= 100'000'000) device_history_.pop_front();
    const auto& [then_ns, then] = device_history_.front();
    if (now_ns > then_ns) device_speed_ = (T.translation() - then).norm() / seconds(now_ns - then_ns);
  }
  while (mode_in_.take(mode_msg_)) mode_ = mode_msg_.mode();
  while (take_checked(commanded_in_, commanded_msg_)) {
    commanded_ = msgs::to_isometry(commanded_msg_.pose()), have_commanded_ = true;
  }
}

void SurfacePlanner::report(std::int64_t now_ns, bool hand_known, const Vec3& hand, double ssm) {
  const bool at_target = path_.done() && target_feature_;
  const double offset = (device_.translation() - target_.translation()).norm();
  if (!target_feature_) {
    status_.state(msg::PLAN_IDLE);
    status_.reason(hand_known ? "no feature chosen yet" : "no hand in view");
  } else if (!unreachable_.empty() && path_.done()) {
    status_.state(msg::PLAN_UNREACHABLE);
    status_.reason(unreachable_.substr(0, 127));
  } else if (at_target && (was_in_place_ ? offset <= 2 * in_place_ && device_speed_ < 2 * still_speed_  // hysteresis
                                         : offset <= in_place_ && device_speed_ < still_speed_)) {
    status_.state(msg::PLAN_IN_PLACE);
  } else if (!path_.done() && ssm <= 0 && kappa_ <= 0) {
    status_.state(msg::PLAN_WAITING);
    status_.reason(("the hand is " + std::to_string(monitor_->separation() * 1e3) + " mm from the " +
                    monitor_->nearest_part() + ", within the protective distance")
                       .substr(0, 127));
  } else {
    status_.state(msg::PLAN_MOVING);
  }
  status_.feature(target_feature_ ? target_feature_->name : std::string());
  status_.body(target_feature_ ? scene_.models[static_cast<std::size_t>(target_feature_->body)].name : std::string());
  msgs::to_msg(target_, status_.base_T_target());
  const double eta = status_.state() == msg::PLAN_IN_PLACE ? 0.0 : path_.remaining_time() + settle_time_;
  status_.eta(eta);
  double hand_eta = -1;
  if (hand_known && target_feature_) {
    const Eigen::Isometry3d obj_T_base = base_T_obj_[static_cast<std::size_t>(target_feature_->body)].inverse();
    const double d = target_feature_->distance(obj_T_base * hand);
    const Vec3 touch = base_T_obj_[static_cast<std::size_t>(target_feature_->body)] * target_feature_->touch;
    const double closing = hand_.significant_velocity().dot((touch - hand).normalized());
    if (closing > 0.1) hand_eta = d / closing;
    if (hand_eta >= 0 && eta > hand_eta && status_.state() == msg::PLAN_MOVING)
      status_.reason(("late: the plate needs " + std::to_string(eta) + " s, the hand arrives in " +
                      std::to_string(hand_eta) + " s")
                         .substr(0, 127));
  }
  status_.hand_eta(hand_eta);
  was_in_place_ = status_.state() == msg::PLAN_IN_PLACE;
  status_.separation(hand_known ? monitor_->separation() : -1);
  status_.speed_limit(hand_known ? monitor_->allowed_speed() : monitor_->speed_without_hand());
  publish_status(now_ns);
}

void SurfacePlanner::fault(std::int64_t now_ns, const std::string& why) {
  status_.state(msg::PLAN_FAULT);
  status_.reason(why.substr(0, 127));
  kappa_ = 0;
  path_.clear();
  publish_status(now_ns);
}

void SurfacePlanner::publish(std::int64_t now_ns, const Vec3& v, const Vec3& w) {
  fill_header(setpoint_msg_.header(), now_ns, setpoint_seq_++, "base");
  setpoint_msg_.child_frame_id("dev");
  msgs::to_msg(cmd_, setpoint_msg_.pose());
  msgs::to_msg(v, w, setpoint_msg_.twist());
  setpoint_msg_.source("surface");
  setpoint_msg_.sensed_ns(sensed_ns_);
  setpoint_out_.write(setpoint_msg_);
}

void SurfacePlanner::publish_status(std::int64_t now_ns) {
  fill_header(status_.header(), now_ns, seq_++, "base");
  status_out_.write(status_);
}

}  // namespace wysiwyf::display
