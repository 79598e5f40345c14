// hand_tracker_sim: a hand tracker made from the simulation's truth, with the faults of a real one:
// Gaussian noise, a latency (each position is published that much after the hand was there,
// stamped with when it was there), random dropouts and scripted outages (published as LOST),
// glitches (the position off by a fixed offset for a while: a tracker locked onto something else)
// and stale stamps (published as if seen that much earlier). For
// tests, and for studying how tracking quality limits the display; the stereo hand point and the
// fingertip marker tracker publish the same HandPosition, so sources swap by one `type:` line.
#include <deque>
#include <random>

#include "wysiwyf/component.hpp"
#include "wysiwyf/msg_eigen.hpp"

namespace wysiwyf::vision {

class HandTrackerSim final : public Component {
 public:
  void configure(Context& ctx) override {
    ctx.summary("hand tracking from the simulated fingertip, with noise, latency and dropouts");
    noise_ = ctx.param<double>("noise", 0.002, "m, sigma of the Gaussian noise per axis", Range{0, 1});
    latency_ns_ = static_cast<std::int64_t>(
        ctx.param<double>("latency", 0.01, "s from the hand being somewhere to its position being published",
                          Range{0, 1}) *
        1e9);
    dropout_ = ctx.param<double>("dropout", 0.0, "probability that a sample is lost (published as LOST)", Range{0, 1});
    outages_ = ctx.param<std::vector<double>>("outages", {}, "rows [from s, to s]: the hand is not seen at all",
                                              Range{0, 1e9}, Length::rows_of(2));
    glitches_ = ctx.param<std::vector<double>>(
        "glitches", {}, "rows [from s, to s, dx, dy, dz m]: the position published off by (dx, dy, dz)",
        Range{-1e9, 1e9}, Length::rows_of(5));
    stale_ = ctx.param<std::vector<double>>(
        "stale", {}, "rows [from s, to s, age s]: positions stamped age s before the hand was there", Range{0, 1e9},
        Length::rows_of(3));
    seed_ = ctx.param<int>("seed", 7, "noise and dropout seed (runs are repeatable)", Range{0, 1e9});
    in_ = ctx.input<msg::PoseStamped>("hand_pose", "the fingertip's true position (arm_sim, base frame)",
                                      Qos::sensor(64));
    out_ = ctx.output<msg::HandPosition>("hand", "the tracked fingertip, base frame", Qos::sensor(4));
  }

  void activate() override { rng_.seed(static_cast<std::uint64_t>(seed_)); }

  void tick(Time now) override {
    while (in_.take(sample_)) {
      const Eigen::Vector3d p = msgs::to_eigen(sample_.pose().position());
      if (!p.allFinite()) {
        reject(in_, "a non-finite position");
        continue;
      }
      seen_.push_back({sample_.header().stamp_ns() ? sample_.header().stamp_ns() : now.ns, p});
    }
    // The newest position old enough to be out of the tracker by now.
    bool have = false;
    Seen latest;
    while (!seen_.empty() && seen_.front().stamp_ns <= now.ns - latency_ns_) {
      latest = seen_.front();
      seen_.pop_front();
      have = true;
    }
    if (!have) return;
    if (start_ns_ < 0) start_ns_ = latest.stamp_ns;
    const double t = static_cast<double>(latest.stamp_ns - start_ns_) * 1e-9;
    bool lost = uniform_(rng_) < dropout_;
    for (std::size_t i = 0; i + 1 < outages_.size(); i += 2) lost = lost || (t >= outages_[i] && t < outages_[i + 1]);
    Eigen::Vector3d offset = Eigen::Vector3d::Zero();
    for (std::size_t i = 0; i + 4 < glitches_.size(); i += 5)
      if (t >= glitches_[i] && t < glitches_[i + 1])
        offset += Eigen::Vector3d(glitches_[i + 2], glitches_[i + 3], glitches_[i + 4]);
    std::int64_t stamp_ns = latest.stamp_ns;
    for (std::size_t i = 0; i + 2 < stale_.size(); i += 3)
      if (t >= stale_[i] && t < stale_[i + 1]) stamp_ns -= static_cast<std::int64_t>(stale_[i + 2] * 1e9);
    fill_header(msg_.header(), stamp_ns, seq_++, "base");
    msg_.status(lost ? msg::TRACKING_LOST : msg::TRACKING_OK);
    const Eigen::Vector3d noisy =
        latest.p + offset + noise_ * Eigen::Vector3d(normal_(rng_), normal_(rng_), normal_(rng_));
    msgs::to_msg(lost ? Eigen::Vector3d::Zero() : noisy, msg_.position());
    const double var = noise_ * noise_;
    msg_.covariance() = {var, 0, 0, 0, var, 0, 0, 0, var};
    msg_.source("sim");
    out_.write(msg_);
  }

 private:
  struct Seen {
    std::int64_t stamp_ns = 0;
    Eigen::Vector3d p = Eigen::Vector3d::Zero();
  };

  double noise_ = 0.002, dropout_ = 0;
  std::int64_t latency_ns_ = 0, start_ns_ = -1;
  std::vector<double> outages_, glitches_, stale_;
  int seed_ = 7;
  std::mt19937_64 rng_;
  std::normal_distribution<double> normal_{0.0, 1.0};
  std::uniform_real_distribution<double> uniform_{0.0, 1.0};
  std::deque<Seen> seen_;
  std::uint64_t seq_ = 0;
  msg::PoseStamped sample_;
  msg::HandPosition msg_;
  Input<msg::PoseStamped> in_;
  Output<msg::HandPosition> out_;
};

}  // namespace wysiwyf::vision

WYSIWYF_COMPONENT(wysiwyf::vision::HandTrackerSim, "hand_tracker_sim")
