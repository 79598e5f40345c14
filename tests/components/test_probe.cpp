// Test component: JointState in -> JointState out, recording what it sees, optionally failing
// on purpose in a chosen lifecycle phase. Used by the kernel tests only.
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <thread>

#include "wysiwyf/component.hpp"
#include "wysiwyf/msgs.hpp"

namespace {

class TestProbe final : public wysiwyf::Component {
 public:
  void configure(wysiwyf::Context& ctx) override {
    ctx.summary("kernel test probe: JointState in, JointState out, records and fails on request");
    gain_ = ctx.param<double>("gain", 0.5, "out.position[0] = t + gain * (sum of inputs)", wysiwyf::Range{-10, 10});
    fail_phase_ = ctx.param_choice("fail_phase", "none", "lifecycle phase that throws on purpose",
                                   {"none", "configure", "activate", "tick", "deactivate"});
    fail_tick_ =
        ctx.param<int>("fail_tick", 0, "with fail_phase tick: the tick index that throws", wysiwyf::Range{0, 1e9});
    record_ = ctx.param<std::string>("record", "", "file receiving every input sample (hex floats) at deactivate");
    lifecycle_log_ = ctx.param<std::string>("lifecycle_log", "", "file to append lifecycle events to");
    stop_after_ = ctx.param<int>("stop_after_received", 0, "ask the pipeline to stop after this many inputs (0: never)",
                                 wysiwyf::Range{0, 1e9});
    tick_sleep_us_ =
        ctx.param<int>("tick_sleep_us", 0, "sleep this long in every tick (overrun tests)", wysiwyf::Range{0, 1e6});
    sleep_ticks_ = ctx.param<int>("sleep_ticks", 0, "with tick_sleep_us: only the first this many ticks sleep (0: all)",
                                  wysiwyf::Range{0, 1e9});
    emit_nan_ = ctx.param<bool>("emit_nan", false, "write NaN in out.position[0] (bad-input tests)");
    hold_ticks_ = ctx.param<std::array<double, 2>>(
        "hold_ticks", {-1, -1}, "report holding from the first tick index to the second (health tests)");
    fault_tick_ =
        ctx.param<int>("fault_tick", -1, "report a fault from this tick index (health tests)", wysiwyf::Range{-1, 1e9});
    // Parameter shapes and a relation between two parameters, for the validator's tests.
    weights_ = ctx.param<std::array<double, 3>>("weights", {1, 0, 0}, "three weights (a fixed-size list)",
                                                wysiwyf::Range{-1, 1});
    window_ = ctx.param<std::vector<double>>("window", {}, "rows of [start s, end s]", std::nullopt,
                                             wysiwyf::Length::rows_of(2));
    const double lo = ctx.param<double>("lo", 0, "lower bound (with hi)");
    const double hi = ctx.param<double>("hi", 1, "upper bound, larger than lo");
    if (!(hi > lo)) ctx.reject("hi", "must be larger than lo (" + std::to_string(lo) + ")");
    const bool one_writer =
        ctx.param<bool>("one_writer", false, "in takes one writer, out declares itself it (ownership tests)");
    name_writers_ = ctx.param<bool>("name_writers", false, "log each new process its input's samples come from");
    const bool optional_in = ctx.param<bool>("optional_in", false, "in is optional (unconnected-input tests)");
    const wysiwyf::Qos in_qos =
                           optional_in ? wysiwyf::Qos::reliable(100).optional_input() : wysiwyf::Qos::reliable(100),
                       out_qos;
    in_ = ctx.input<wysiwyf::msg::JointState>("in", "samples to record", one_writer ? in_qos.one_writer() : in_qos);
    out_ = ctx.output<wysiwyf::msg::JointState>("out", "t + gain * sum of inputs, in position[0]",
                                                one_writer ? out_qos.one_writer() : out_qos);
    if (ctx.mode() == wysiwyf::Context::Mode::kRun) event("configure");  // validation configures too
    if (fail_phase_ == "configure") throw std::runtime_error("configure failed on purpose");
  }
  void activate() override {
    event("activate");
    if (fail_phase_ == "activate") throw std::runtime_error("activate failed on purpose");
  }
  void tick(wysiwyf::Time now) override {
    if (fail_phase_ == "tick" && ticks_ == fail_tick_) throw std::runtime_error("tick failed on purpose");
    if (fault_tick_ >= 0 && ticks_ >= fault_tick_)
      report_health(wysiwyf::Health::kFault, "told to fault at tick " + std::to_string(fault_tick_));
    else if (ticks_ >= hold_ticks_[0] && ticks_ < hold_ticks_[1])
      report_health(wysiwyf::Health::kHolding,
                    "told to hold at tick " + std::to_string(static_cast<int>(hold_ticks_[0])));
    else
      report_health(wysiwyf::Health::kOk);
    ++ticks_;
    if (tick_sleep_us_ > 0 && (sleep_ticks_ == 0 || ticks_ <= sleep_ticks_))
      std::this_thread::sleep_for(std::chrono::microseconds(tick_sleep_us_));
    double sum = 0;
    while (in_.take(sample_)) {
      if (name_writers_ && in_.writer() != last_writer_) {
        last_writer_ = in_.writer();
        log("samples from process '" + last_writer_ + "'");
      }
      if (sample_.position().empty() || !std::isfinite(sample_.position()[0])) {
        reject(in_, "position[0] is not finite");
        continue;
      }
      char line[160];
      std::snprintf(line, sizeof line, "%lld %llu %a %a\n", static_cast<long long>(now.ns),
                    static_cast<unsigned long long>(sample_.header().seq()), sample_.position()[0],
                    static_cast<double>(sample_.header().stamp_ns()));
      recorded_ += line;
      sum += sample_.position()[0];
      if (stop_after_ > 0 && ++received_ == stop_after_) request_stop("received " + std::to_string(received_));
    }
    wysiwyf::msg::JointState out;
    out.header().stamp_ns(now.ns);
    out.header().seq(seq_++);
    out.position().resize(1);
    out.position()[0] = emit_nan_ ? std::nan("") : now.seconds() + gain_ * std::sin(sum);
    out_.write(out);
  }
  void deactivate() override {
    event("deactivate");
    if (!record_.empty()) std::ofstream(record_) << recorded_;
    if (fail_phase_ == "deactivate") throw std::runtime_error("deactivate failed on purpose");
  }
  void hold() noexcept override { event("hold"); }

 private:
  void event(const std::string& what) {
    if (!lifecycle_log_.empty()) std::ofstream(lifecycle_log_, std::ios::app) << instance_name() << " " << what << "\n";
  }

  double gain_ = 0;
  bool emit_nan_ = false, name_writers_ = false;
  std::string last_writer_;
  std::array<double, 3> weights_{};
  std::vector<double> window_;
  std::string fail_phase_, record_, lifecycle_log_;
  int tick_sleep_us_ = 0, sleep_ticks_ = 0;
  int fail_tick_ = 0, stop_after_ = 0, ticks_ = 0, received_ = 0, fault_tick_ = -1;
  std::array<double, 2> hold_ticks_{-1, -1};
  std::uint64_t seq_ = 0;
  std::string recorded_;
  wysiwyf::msg::JointState sample_;
  wysiwyf::Input<wysiwyf::msg::JointState> in_;
  wysiwyf::Output<wysiwyf::msg::JointState> out_;
};

}  // namespace

WYSIWYF_COMPONENT(TestProbe, "test_probe")
