// wrench_lowpass: a first-order low-pass filter on a force/torque stream (sensor noise off the
// wrist F/T signal before the admittance loop). Frame and stamp pass through unchanged.
#include <array>
#include <cmath>

#include "wysiwyf/component.hpp"
#include "wysiwyf/msgs.hpp"

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
    while (in_.take(sample_)) {
      auto& w = sample_.wrench();
      const std::array<double, 6> x{w.force().x(), w.force().y(), w.force().z(),
                                    w.torque().x(), w.torque().y(), w.torque().z()};
      const std::int64_t stamp = sample_.header().stamp_ns();
      if (last_stamp_ < 0) {
        y_ = x;  // start at the first sample, not at zero
      } else {
        // Exact for the time between samples (jittery streams filter alike), taking each sample
        // as the input over the interval that ends at its stamp: no added delay.
        const double dt = static_cast<double>(std::max<std::int64_t>(stamp - last_stamp_, 0)) * 1e-9;
        const double a = 1.0 - std::exp(-2.0 * M_PI * cutoff_hz_ * dt);
        for (int i = 0; i < 6; ++i) y_[i] += a * (x[i] - y_[i]);
      }
      last_stamp_ = stamp;
      w.force().x(y_[0]);
      w.force().y(y_[1]);
      w.force().z(y_[2]);
      w.torque().x(y_[3]);
      w.torque().y(y_[4]);
      w.torque().z(y_[5]);
      out_.write(sample_);
    }
  }

 private:
  double cutoff_hz_ = 0;
  std::array<double, 6> y_{};
  std::int64_t last_stamp_ = -1;
  msg::WrenchStamped sample_;  // reused: no allocation per tick
  Input<msg::WrenchStamped> in_;
  Output<msg::WrenchStamped> out_;
};

}  // namespace wysiwyf::io

WYSIWYF_COMPONENT(wysiwyf::io::WrenchLowpass, "wrench_lowpass")
