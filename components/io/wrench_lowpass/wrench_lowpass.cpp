// wrench_lowpass: a first-order low-pass filter on a force/torque stream (sensor noise off the
// wrist F/T signal before the admittance loop). Frame and stamp pass through unchanged.
#include <cmath>

#include "wysiwyf/component.hpp"
#include "wysiwyf/msg_checks.hpp"
#include "wysiwyf/msg_eigen.hpp"

namespace wysiwyf::io {

class WrenchLowpass final : public Component {
 public:
  void configure(Context& ctx) override {
    ctx.summary("first-order low-pass filter on a wrench stream");
    cutoff_hz_ = ctx.param<double>("cutoff_hz", 30.0, "filter cut-off frequency", Range{0.1, 5000});
    in_ = ctx.input<msg::WrenchStamped>("raw", "unfiltered wrench", Qos::sensor(16));
    out_ = ctx.output<msg::WrenchStamped>("filtered", "filtered wrench, same frame and stamp");
  }

  void tick(Time) override {
    while (take_checked(in_, sample_)) {  // (one NaN would stay in the filter's state for good)
      const msgs::Vector6d x = msgs::to_vector6(sample_.wrench());
      const std::int64_t stamp = sample_.header().stamp_ns();
      if (last_stamp_ < 0) {
        y_ = x;  // start at the first sample, not at zero
      } else {
        // Exact for the time between samples (jittery streams filter alike), taking each sample
        // as the input over the interval that ends at its stamp: no added delay.
        const double dt = static_cast<double>(std::max<std::int64_t>(stamp - last_stamp_, 0)) * 1e-9;
        const double a = 1.0 - std::exp(-2.0 * M_PI * cutoff_hz_ * dt);
        y_ += a * (x - y_);
      }
      last_stamp_ = stamp;
      msgs::to_msg(y_, sample_.wrench());
      out_.write(sample_);
    }
  }

 private:
  double cutoff_hz_ = 0;
  msgs::Vector6d y_ = msgs::Vector6d::Zero();
  std::int64_t last_stamp_ = -1;
  msg::WrenchStamped sample_;  // reused: no allocation per tick
  Input<msg::WrenchStamped> in_;
  Output<msg::WrenchStamped> out_;
};

}  // namespace wysiwyf::io

WYSIWYF_COMPONENT(wysiwyf::io::WrenchLowpass, "wrench_lowpass")
