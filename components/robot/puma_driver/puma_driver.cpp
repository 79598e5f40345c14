// puma_driver: the real PUMA 560 through its joint controller over puma-link (docs/puma-link.md).
//
// The host half of what arm_sim does, with the same code: every tick (1 kHz) the controller's
// latest state (encoder angles, velocities, torques) is published and checked by the safety gate
// (limits, overspeed, following error, and the wrist force when a `wrench` is connected);
// Cartesian setpoints go through the SetpointFollower (gate screening, RCCL-style tracking, IK)
// and the gate's bounded joint reference goes to the controller, which runs the servo.
//
// The link: no valid state for link_timeout -> the gate faults ("link lost"), commands carry the
// hold flag; when states come back the gate restarts from the measured joints (holding until a
// setpoint near the arm arrives). A fault the controller reports faults the gate too. With
// `lockstep` (for the simulated clock, against apps/puma-link-emulator --lockstep) each tick
// waits for the controller's answer, so the pipeline sees exactly what arm_sim would show.
#include <chrono>
#include <memory>
#include <stdexcept>
#include <tuple>

#include "arm_interface/arm_params.hpp"
#include "arm_interface/arm_ports.hpp"
#include "arm_model/arm_model.hpp"
#include "link_client.hpp"
#include "safety_gate/safety_gate.hpp"
#include "setpoint_following/setpoint_follower.hpp"
#include "wysiwyf/component.hpp"
#include "wysiwyf/config_files.hpp"
#include "wysiwyf/msg_eigen.hpp"

namespace wysiwyf::robot {
namespace {

// The joints a puma-link command and state carry: the PUMA 560's six.
constexpr int kLinkJoints = static_cast<int>(std::tuple_size<link::Joints>::value);

const char* to_string(link::Fault f) {
  switch (f) {
    case link::Fault::kNone: return "none";
    case link::Fault::kCommandTimeout: return "command timeout";
    case link::Fault::kJointLimit: return "joint limit in a command";
    case link::Fault::kBadCommand: return "bad command (step or speed beyond the limits)";
  }
  return "unknown fault code";
}

}  // namespace

class PumaDriver final : public Component {
 public:
  void configure(Context& ctx) override {
    ctx.summary(
        "the real PUMA 560 over puma-link (UDP to its joint controller), behind the same safety gate and "
        "setpoint following as arm_sim");
    host_ = ctx.param<std::string>("host", "127.0.0.1", "the joint controller's IPv4 address");
    port_ = ctx.param<int>("port", link::kDefaultPort, "the controller's puma-link UDP port", Range{1, 65535});
    lockstep_ = ctx.param<bool>("lockstep", false,
                                "wait each tick for the controller's answer (simulated clock, with puma-link-emulator "
                                "--lockstep); off for a real controller on the real clock");
    connect_timeout_ = ctx.param<double>("connect_timeout", 2.0,
                                         "s to wait for the controller's first state at activation", Range{0.01, 60});
    reply_timeout_ = ctx.param<double>("reply_timeout", 0.5,
                                       "lockstep: s of wall time to wait for each answer before counting it missing",
                                       Range{0.001, 60});
    link_timeout_ =
        ctx.param<int>("link_timeout_periods", 3,
                       "ticks without a valid state before the link counts as lost (the arm holds)", Range{1, 1000});
    // ---- the robot, the setpoint tracker and the safety gate (as arm_sim)
    arm_ = declare_arm_params(ctx);

    ports_.declare(ctx, {[this](const auto& in, const std::string& why) { reject(in, why); },
                         [this](const auto& in, const std::string& why) { reject(in, why); },
                         [this](const std::string& line) { log(line); }});
    wrench_in_ = ctx.input<msg::WrenchStamped>(
        "wrench", "the wrist F/T sensor (ft_netft), for the force limit; leave unconnected to go without",
        Qos::sensor(16).optional_input());

    dt_ = arm_.gate.dt;
    model_ = load_arm_model(ctx, arm_);
    if (model_ && model_->dof() != kLinkJoints) {
      ctx.reject("urdf", arm_.urdf_path + " has " + std::to_string(model_->dof()) + " joints; puma-link carries the " +
                             "PUMA 560's " + std::to_string(kLinkJoints));
      model_.reset();
    }
  }

  void activate() override {
    link_ = std::make_unique<link::LinkClient>(host_, static_cast<std::uint16_t>(port_));
    // Where is the arm? Ask (clearing a fault latched in an earlier session) until it answers.
    link::Command query;
    query.query = true;
    query.reset_fault = true;
    const auto deadline = std::chrono::steady_clock::now() + seconds(connect_timeout_);
    bool answered = false;
    while (!answered && std::chrono::steady_clock::now() < deadline) {
      const std::uint32_t seq = link_->send(query);
      answered = link_->wait_for_ack(seq, std::min(seconds(0.05), seconds(connect_timeout_)), state_);
    }
    if (!answered)
      throw std::runtime_error("puma-link: no answer from the controller at " + link_->address() + " within " +
                               std::to_string(connect_timeout_) + " s (is it on, or apps/puma-link-emulator running?)");
    gate_ = std::make_unique<SafetyGate>(arm_.gate);
    follower_ = std::make_unique<SetpointFollower>(*model_, arm_.tip_frame, *gate_, arm_.tracker_hz, dt_);
    ports_.reset_status();
    started_ = false;
    link_lost_ = link_faulted_ = false;
    missed_ = 0;
    seq_ = 0;
  }

  void tick(Time now) override {
    // ---- 1. the controller's state (lockstep: the answer to the last command, already here)
    if (!lockstep_) {
      if (link_->poll_newest(state_)) {
        missed_ = 0;
      } else {
        ++missed_;
      }
    }
    const bool link_up = missed_ < link_timeout_;
    JointVector q(kLinkJoints), qd(kLinkJoints);
    for (int j = 0; j < kLinkJoints; ++j) {
      const auto k = static_cast<std::size_t>(j);
      q[j] = state_.q[k], qd[j] = state_.qd[k];
    }
    if (link_up) publish(now, q, qd);

    if (!started_) {  // the gate starts from the first measurement
      gate_->reset(q, now.ns);
      started_ = true;
    }
    // ---- 2. the link and the controller, then the measurements
    if (!link_up && !link_lost_) {
      link_lost_ = true;
      link_faulted_ = gate_->state() != SafetyState::kFault;  // (another fault stays latched)
      if (link_faulted_)
        gate_->fault("puma-link: no state from " + link_->address() + " for " + std::to_string(missed_) + " periods");
      log("link lost: " + gate_->reason());
    } else if (link_up && link_lost_) {
      link_lost_ = false;
      if (link_faulted_) {
        gate_->reset(q, now.ns);  // start again from where the arm is, holding until a setpoint
        log("link restored: holding at the measured joints until a setpoint near them arrives");
      } else {
        log("link restored; the earlier fault stays latched: " + gate_->reason());
      }
    }
    if (link_up) {
      if (state_.status == link::Status::kFault)
        gate_->fault(std::string("the controller reports a fault: ") + to_string(state_.fault));
      gate_->check_measured(q, qd);
    }
    while (wrench_in_.take(wrench_msg_))
      gate_->check_wrench(msgs::to_eigen(wrench_msg_.wrench().force()), msgs::to_eigen(wrench_msg_.wrench().torque()));

    // ---- 3. setpoints, trajectory generator, 4. the reference
    ports_.take_requests(*gate_, now.ns);
    ports_.take_setpoints(arm_, *follower_, now.ns);
    follower_->update(now.ns);
    const JointVector ref_q = gate_->reference().q, ref_qd = gate_->reference().qd;
    const JointReference& ref = gate_->step(now.ns);

    // ---- 5. to the controller: the reference now and the acceleration to the next period
    // (what arm_sim's servo gets); without a link, hold wherever the arm is.
    link::Command c;
    c.hold = link_lost_;
    for (int j = 0; j < kLinkJoints; ++j) {
      const auto k = static_cast<std::size_t>(j);
      c.q[k] = ref_q[j], c.qd[k] = ref_qd[j], c.qdd[k] = ref.qdd[j];
    }
    const std::uint32_t sent = link_->send(c);
    if (lockstep_) {
      if (link_->wait_for_ack(sent, seconds(reply_timeout_), state_)) {
        missed_ = 0;
      } else {
        ++missed_;
      }
    }
    ports_.publish_status(now.ns, *gate_, follower_->source());
    report_health(ports_.health(*gate_), gate_->reason());  // the kernel logs the changes
  }

  void deactivate() override {
    if (gate_) ports_.log_bursts(*gate_);
    if (!link_) return;
    link::Command c;
    c.hold = true;
    link_->send(c);
    log("stopped: sent " + std::to_string(link_->counters().sent) + " commands, received " +
        std::to_string(link_->counters().received) + " states, dropped " +
        std::to_string(link_->counters().dropped_damaged) + " damaged and " +
        std::to_string(link_->counters().dropped_stale) + " out-of-order");
    link_.reset();
  }

  void hold() noexcept override {
    try {
      if (gate_) gate_->fault("hold: the pipeline stopped on a fault");
      if (link_) {
        link::Command c;
        c.hold = true;
        link_->send(c);
      }
    } catch (...) {
    }
  }

 private:
  static std::chrono::nanoseconds seconds(double s) {
    return std::chrono::nanoseconds(static_cast<std::int64_t>(s * 1e9));
  }

  void publish(Time now, const JointVector& q, const JointVector& qd) {
    const JointVector tau = Eigen::Map<const Vector6d>(state_.tau.data());
    ports_.publish_measurement(now.ns, seq_++, q, qd, tau, arm_.tip_frame, model_->fk(q));
  }

  // parameters
  ArmParams arm_;
  std::string host_;
  int port_ = link::kDefaultPort, link_timeout_ = 3;
  bool lockstep_ = false;
  double connect_timeout_ = 2, reply_timeout_ = 0.5, dt_ = 1e-3;

  // state
  std::unique_ptr<ArmModel> model_;
  std::unique_ptr<link::LinkClient> link_;
  std::unique_ptr<SafetyGate> gate_;
  std::unique_ptr<SetpointFollower> follower_;
  link::State state_;
  bool started_ = false, link_lost_ = false, link_faulted_ = false;
  int missed_ = 0;
  std::uint64_t seq_ = 0;

  // messages and ports (reused: no allocation per tick)
  msg::WrenchStamped wrench_msg_;
  ArmPorts ports_;
  Input<msg::WrenchStamped> wrench_in_;
};

}  // namespace wysiwyf::robot

WYSIWYF_COMPONENT(wysiwyf::robot::PumaDriver, "puma_driver")
