// wrench_script: a scripted force/torque stream, linear between timed keyframes; stands in for
// the user's hand on the wrist sensor when the haptic side is tested without a user.
#include <cmath>

#include "keyframes/keyframes.hpp"
#include "wysiwyf/component.hpp"
#include "wysiwyf/msg_eigen.hpp"

namespace wysiwyf::io {

class WrenchScript final : public Component {
 public:
  void configure(Context& ctx) override {
    ctx.summary("scripted force/torque, linear between timed keyframes");
    const auto keyframes = ctx.param<std::vector<double>>(
        "keyframes", {0, 0, 0, 0, 0, 0, 0}, "rows of [t s, fx fy fz N, tx ty tz N.m], times from 0 strictly increasing",
        std::nullopt, Length::rows_of(7, 1));
    loop_ = ctx.param<bool>("loop", false, "start again after the last keyframe");
    frame_id_ = ctx.param<std::string>("frame_id", "sensor", "frame the wrench is expressed in");
    wrench_ = ctx.output<msg::WrenchStamped>("wrench", "the scripted wrench at each tick");
    try {
      table_ = std::make_unique<Keyframes>(keyframes, 6);
    } catch (const std::invalid_argument& e) {
      ctx.reject("keyframes", e.what());
    }
  }

  void tick(Time now) override {
    const Keyframes::Segment seg = table_->at(time_.at(now.ns, table_->end_time(), loop_));
    const double* a = table_->values(seg.from);
    const double* b = table_->values(seg.to);
    msgs::Vector6d v;
    for (int i = 0; i < 6; ++i) v[i] = a[i] + seg.tau * (b[i] - a[i]);
    fill_header(msg_.header(), now.ns, seq_++, frame_id_.c_str());
    msgs::to_msg(v, msg_.wrench());
    wrench_.write(msg_);
  }

 private:
  std::unique_ptr<Keyframes> table_;
  bool loop_ = false;
  std::string frame_id_;
  ScriptTime time_;
  std::uint64_t seq_ = 0;
  msg::WrenchStamped msg_;
  Output<msg::WrenchStamped> wrench_;
};

}  // namespace wysiwyf::io

WYSIWYF_COMPONENT(wysiwyf::io::WrenchScript, "wrench_script")
