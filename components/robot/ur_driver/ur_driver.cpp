// ur_driver: a Universal Robots e-Series arm over RTDE (Real-Time Data Exchange, protocol 2).
//
// The host half of what arm_sim does, with the same code (setpoint following, safety gate):
// every tick (the rate is RTDE's frequency: 500 Hz, the controller's period) the controller's
// newest output package (actual joints, velocities, commanded torques, TCP force, robot and
// safety modes, the follow program's state) is published on the arm's ports and checked by the
// gate; the gate's bounded joint reference (q, qd, qdd) goes to the input registers with a
// counter and a mode, which config/robots/ur_follow.script, sent over the primary interface,
// follows with servoj (rtde/follow_program.hpp is the contract).
//
// What holds the arm (the gate faults with the reason, the registers say hold, the program stops
// the arm where it is): no output package for stream_timeout_periods ticks, a connection closed
// or broken (a package refused: malformed, cut short, of another recipe or with values no
// controller sends, counted; TCP cannot resynchronise: the driver reconnects), a protective stop
// or another stop of the controller's safety system, the arm not running, the follow program not
// running. The driver reconnects by itself (measurements come back), but only the supervisor's
// ArmRequest CLEAR_INPUT_FAULT lets the arm move again: then the dashboard unlocks a protective
// stop, the program is sent again (real time: on a thread of its own, the tick goes on holding),
// and once it runs the gate restarts from the measured joints.
// With `lockstep` (the simulated clock, against apps/ur-emulator --lockstep) each tick waits for
// the answer to its input package, so the pipeline sees exactly what arm_sim would show.
#include <fstream>
#include <limits>
#include <memory>
#include <sstream>
#include <utility>
#include <stdexcept>

#include "arm_interface/arm_params.hpp"
#include "arm_interface/arm_ports.hpp"
#include "arm_model/arm_model.hpp"
#include "rtde_link.hpp"
#include "safety_gate/safety_gate.hpp"
#include "setpoint_following/setpoint_follower.hpp"
#include "tcp_wrench.hpp"
#include "program_restart.hpp"
#include "wysiwyf/component.hpp"
#include "wysiwyf/config_files.hpp"
#include "wysiwyf/msg_eigen.hpp"

namespace wysiwyf::robot::ur {
namespace {

namespace follow = rtde::follow;
constexpr int kUrJoints = 6;
constexpr int kMaxMissed = 1 << 30;  // missed periods are counted up to here (no overflow)

JointVector joints(const Six& v) { return Eigen::Map<const Eigen::Matrix<double, 6, 1>>(v.data()); }

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

class UrDriver final : public Component {
 public:
  void configure(Context& ctx) override {
    ctx.summary(
        "a Universal Robots e-Series arm over RTDE (servoj toward the safety gate's reference, config/robots/"
        "ur_follow.script), behind the same safety gate and setpoint following as arm_sim");
    controller_.host =
        ctx.param<std::string>("host", "127.0.0.1", "the controller's address (the pendant in Remote Control)");
    rtde_port_ = ctx.param<int>("rtde_port", 30004, "the controller's RTDE port", Range{1, 65535});
    controller_.script_port =
        ctx.param<int>("script_port", 30002, "the primary interface's port (the program)", Range{1, 65535});
    controller_.dashboard_port =
        ctx.param<int>("dashboard_port", 29999, "the dashboard server's port", Range{1, 65535});
    lockstep_ = ctx.param<bool>("lockstep", false,
                                "wait each tick for the answer to the input package (simulated clock, with ur-emulator "
                                "--lockstep); off for a real controller on the real clock");
    connect_timeout_ =
        ctx.param<double>("connect_timeout", 2.0,
                          "s to wait for a connection, the handshake and the program at activation", Range{0.01, 60});
    reply_timeout_ = ctx.param<double>("reply_timeout", 0.5,
                                       "lockstep: s of wall time to wait for each output package before counting it "
                                       "missing",
                                       Range{0.001, 60});
    stream_timeout_ = ctx.param<int>("stream_timeout_periods", 3,
                                     "ticks without an output package before the stream counts as lost (the arm holds)",
                                     Range{1, 1000});
    reconnect_interval_ =
        ctx.param<double>("reconnect_interval", 0.5, "s between attempts to reconnect RTDE", Range{0.002, 60});
    program_timeout_ =
        ctx.param<double>("program_timeout", 2.0,
                          "s a recovery waits for the program sent again to run (then: ask again)", Range{0.01, 60});
    const auto program_path = ctx.param<std::string>("program", "robots/ur_follow.script",
                                                     "the follow program sent to the primary interface");
    tcp_force_ = ctx.param<bool>(
        "tcp_force", false,
        "publish the UR's built-in TCP force sensor on `wrench` (frame sensor_frame, about its origin; the pendant's "
        "TCP must be the flange; the payload's weight added back, as an ATI Net F/T reads the tool; bias: the "
        "controller's zero_ftsensor() at rest); off: `wrench` is an input from an external wrist sensor");
    const auto payload = ctx.param<std::array<double, 4>>(
        "tcp_payload", {0, 0, 0, 0},
        "tcp_force: the tool whose weight the reading carries, as the display's consumers expect (the scene's "
        "tool_mass, kg, and tool_com moved to the flange frame, m); the controller compensates the pendant's whole "
        "payload (set it to this tool and whatever else is on the flange), and this part is added back",
        Range{-100, 100});
    sensor_frame_ = ctx.param<std::string>("sensor_frame", "ft_sensor", "tcp_force: the frame the wrench is given in");
    const auto flange_frame = ctx.param<std::string>("flange_frame", "flange", "tcp_force: the UR's tool flange");
    arm_ = declare_arm_params(ctx);

    ports_.declare(ctx, {[this](const auto& in, const std::string& why) { reject(in, why); },
                         [this](const auto& in, const std::string& why) { reject(in, why); },
                         [this](const std::string& line) { log(line); }});
    if (tcp_force_)
      wrench_out_ = ctx.output<msg::WrenchStamped>("wrench", "the UR's TCP force, sensor frame, tool weight included",
                                                   Qos::sensor(8));
    else
      wrench_in_ = ctx.input<msg::WrenchStamped>(
          "wrench", "the wrist F/T sensor (ft_netft), for the force limit; leave unconnected to go without",
          Qos::sensor(16).optional_input());

    dt_ = arm_.gate.dt;
    try {
      program_ = read_text(find_config_file(program_path));
    } catch (const std::exception& e) {
      ctx.reject("program", e.what());
    }
    if (!program_.empty() && program_.compare(0, follow::kHeader.size(), follow::kHeader) != 0)
      ctx.reject("program", program_path + " does not begin '" + std::string(follow::kHeader) +
                                "': not the follow program whose registers this driver writes");
    model_ = load_arm_model(ctx, arm_);
    if (model_ && model_->dof() != kUrJoints) {
      ctx.reject("urdf", arm_.urdf_path + " has " + std::to_string(model_->dof()) + " joints; a UR arm has 6");
      model_.reset();
    }
    if (model_ && tcp_force_) {
      try {
        tcp_ = std::make_unique<TcpWrench>(*model_, flange_frame, sensor_frame_,
                                           Payload{payload[0], Eigen::Vector3d(payload[1], payload[2], payload[3])});
      } catch (const std::exception& e) {
        ctx.reject("sensor_frame",
                   "frames '" + flange_frame + "' and '" + sensor_frame_ + "' of " + arm_.urdf_path + ": " + e.what());
      }
    }
  }

  void activate() override {
    link_ = std::make_unique<RtdeLink>(controller_.host, static_cast<std::uint16_t>(rtde_port_), 1.0 / dt_);
    const std::string hint = " (is the controller on, in Remote Control, or apps/ur-emulator running?)";
    // Lockstep: the emulator's periods stop between input packages, so the program may start
    // before the stream (its watchdog cannot run out); the dashboard says when it runs.
    if (lockstep_) start_program_before_stream(controller_, program_, connect_timeout_);
    if (!link_->open(connect_timeout_) || !link_->handshake(connect_timeout_))
      throw std::runtime_error(link_->error() + hint);
    if (lockstep_) {
      if (link_->output_packages() == 0 && !link_->await_output(connect_timeout_))
        throw std::runtime_error("RTDE: no output package from " + link_->address() + " after the start" + hint);
    } else {
      start_program_on_stream(controller_, program_, connect_timeout_, *link_, [this] { send_hold(); });
    }
    gate_ = std::make_unique<SafetyGate>(arm_.gate);
    follower_ = std::make_unique<SetpointFollower>(*model_, arm_.tip_frame, *gate_, arm_.tracker_hz, dt_);
    ports_.reset_status();
    started_ = controller_hold_ = restarting_ = false;
    missed_ = 0;
    seq_ = 0;
    next_reconnect_ns_ = 0;
    refused_seen_ = 0;
  }

  void tick(Time now) override {
    // ---- 1. the controller's state (lockstep: the answer to the last input, already here)
    if (!lockstep_) missed_ = link_->service(0) > 0 ? 0 : std::min(missed_ + 1, kMaxMissed);
    if (!started_) {  // the gate starts from the first measurement
      gate_->reset(joints(link_->state().q), now.ns);
      started_ = true;
    }
    if (!link_->streaming()) hold_for(stream_problem());  // (before a reconnection hides it)
    keep_connected(now);
    const bool fresh = link_->streaming() && missed_ < stream_timeout_;
    const UrState& s = link_->state();
    const JointVector q = joints(s.q), qd = joints(s.qd);
    if (fresh) publish(now, s, q, qd);
    // ---- 2. what holds the arm, then the measurements
    if (!fresh)
      hold_for(stream_problem());
    else if (const std::string problem = controller_problem(s);
             !problem.empty() && !restarting_ && !restart_.in_flight())
      hold_for("controller: " + problem);
    if (fresh) {
      gate_->check_measured(q, qd);
      if (tcp_) gate_->check_wrench(force_, torque_);
    }
    if (!tcp_force_)
      while (wrench_in_.take(wrench_msg_))
        gate_->check_wrench(msgs::to_eigen(wrench_msg_.wrench().force()),
                            msgs::to_eigen(wrench_msg_.wrench().torque()));

    // ---- 3. requests (the controller's hold is cleared here), setpoints, the reference
    if (controller_hold_) {
      take_recovery_requests(fresh);
      take_restart_outcome(now);
    } else
      ports_.take_requests(*gate_, now.ns);
    if (restarting_) finish_recovery(now, fresh, q);
    ports_.take_setpoints(arm_, *follower_, now.ns);
    follower_->update(now.ns);
    const JointVector ref_q = gate_->reference().q, ref_qd = gate_->reference().qd;
    const JointReference& ref = gate_->step(now.ns);

    // ---- 4. to the controller: the reference now and the acceleration to the next period (what
    // arm_sim's servo gets); while the controller holds, the program holds where the arm is.
    link_->send_inputs(next_counter(), controller_hold_ ? follow::kHold : follow::kFollow, ref_q, ref_qd, ref.qdd);
    if (lockstep_) missed_ = link_->await_output(reply_timeout_) ? 0 : std::min(missed_ + 1, kMaxMissed);
    if (link_->refused() != refused_seen_) {
      refused_seen_ = link_->refused();
      warn_once("RTDE package refused",
                "refused an RTDE package (" + std::to_string(refused_seen_) + " so far): " + link_->last_refusal());
    }
    ports_.publish_status(now.ns, *gate_, follower_->source());
    report_health(ports_.health(*gate_), controller_hold_ ? hold_reason_ : gate_->reason());
  }

  void deactivate() override {
    if (gate_) ports_.log_bursts(*gate_);
    if (!link_) return;
    send_hold();
    log("stopped: " + std::to_string(link_->output_packages()) + " output packages taken, " +
        std::to_string(link_->refused()) + " refused" +
        (link_->refused() ? " (the last: " + link_->last_refusal() + ")" : std::string()) + ", " +
        std::to_string(link_->connections()) + " RTDE connection(s)");
    link_.reset();
  }

  void hold() noexcept override {
    try {
      if (gate_) gate_->fault("hold: the pipeline stopped on a fault");
      send_hold();
    } catch (...) {
    }
  }

 private:
  static std::int64_t ns(double s) { return static_cast<std::int64_t>(s * 1e9); }

  void send_hold() {
    if (!link_ || !link_->streaming()) return;
    const UrState& s = link_->state();
    const JointVector zero = JointVector::Zero(kUrJoints);
    link_->send_inputs(next_counter(), follow::kHold, joints(s.q), zero, zero);
  }

  // The watchdog's counter: one more every period, never 0 again (int32 wraps to 1).
  std::int32_t next_counter() {
    counter_ = counter_ == std::numeric_limits<std::int32_t>::max() ? 1 : counter_ + 1;
    return counter_;
  }

  // Reopens RTDE every reconnect_interval while it is down (lockstep: the handshake and the first
  // package at once; real time: a short connect, the handshake in the next ticks' service()).
  void keep_connected(Time now) {
    if (link_->connected() && !link_->streaming() && now.ns - opened_ns_ > ns(connect_timeout_))
      link_->close("RTDE: the handshake with " + link_->address() + " did not finish within " +
                   std::to_string(connect_timeout_) + " s");
    if (link_->connected() || now.ns < next_reconnect_ns_) return;
    next_reconnect_ns_ = now.ns + ns(reconnect_interval_);
    const std::string why = link_->error();
    if (!link_->open(lockstep_ ? connect_timeout_ : std::min(connect_timeout_, 0.25 * dt_))) return;
    opened_ns_ = now.ns;
    if (lockstep_) {
      const std::uint64_t before = link_->output_packages();
      if (!link_->handshake(connect_timeout_)) return;
      if (link_->output_packages() == before && !link_->await_output(reply_timeout_)) return;
      missed_ = 0;
    }
    log("RTDE reconnected to " + link_->address() + " after: " + why);
  }

  std::string stream_problem() const {
    if (!link_->connected()) return link_->error();
    return "RTDE: no output package from " + link_->address() + " for " + std::to_string(missed_) + " periods";
  }

  // The controller (or the link to it) holds the arm: the gate faults, the program holds.
  void hold_for(const std::string& why) {
    if (restarting_ || (restart_.in_flight() && !restart_abandoned_)) {
      restarting_ = false, restart_abandoned_ = restart_.in_flight();
      log("recovery abandoned: " + why);
    }
    if (controller_hold_) return;  // the first reason stands
    controller_hold_ = true;
    prior_arm_fault_ = gate_->state() == SafetyState::kFault && !gate_->input_fault() ? gate_->reason() : "";
    hold_reason_ = "UR " + why;
    gate_->fault(hold_reason_);
    log("holding: " + hold_reason_);
  }

  // The supervisor's clear: unlock a protective stop, send the program again (off the tick).
  void take_recovery_requests(bool fresh) {
    while (ports_.request.take(request_msg_)) {
      if (request_msg_.request() != msg::ARM_CLEAR_INPUT_FAULT) {
        reject(ports_.request, "unknown request " + std::to_string(static_cast<int>(request_msg_.request())));
        continue;
      }
      if (restarting_ || restart_.in_flight()) continue;  // (a request in flight)
      if (!prior_arm_fault_.empty()) {
        reject(ports_.request, "the arm's own fault came first, only a restart clears it: " + prior_arm_fault_);
        continue;
      }
      if (!fresh) {
        reject(ports_.request, "cannot recover while " + stream_problem() + "; ask again once the stream is back");
        continue;
      }
      restart_.start(controller_, program_, connect_timeout_,
                     link_->state().safety_mode == rtde::SafetyMode::kProtectiveStop);
      restart_asked_ = request_msg_.reason().c_str();
      if (lockstep_) restart_.wait();
    }
  }

  // The restart's outcome, when it has one: then the program's start is awaited on the stream.
  void take_restart_outcome(Time now) {
    const auto outcome = restart_.poll();
    if (!outcome || std::exchange(restart_abandoned_, false)) return;
    if (!outcome->done) return reject(ports_.request, "cannot recover: " + outcome->what);
    restarting_ = true;
    restart_deadline_ns_ = now.ns + ns(program_timeout_);
    log("recovering as asked (" + restart_asked_ + "): " + outcome->what + "; holding until it runs");
  }

  void finish_recovery(Time now, bool fresh, const JointVector& q) {
    if (fresh && program_running(link_->state())) {
      restarting_ = controller_hold_ = false;
      gate_->reset(q, now.ns);  // holding at the measured joints until a setpoint near them
      log("recovered from '" + hold_reason_ + "': the follow program runs; holding at the measured joints");
      hold_reason_.clear();
    } else if (now.ns > restart_deadline_ns_) {
      restarting_ = false;
      log("the follow program did not run within " + std::to_string(program_timeout_) +
          " s: " + controller_problem(link_->state()) + "; still holding, ask again");
    }
  }

  void publish(Time now, const UrState& s, const JointVector& q, const JointVector& qd) {
    ports_.publish_measurement(now.ns, seq_, q, qd, joints(s.moment), arm_.tip_frame, model_->fk(q));
    if (tcp_) {
      tcp_->to_sensor(q, s.tcp_force, force_, torque_);
      fill_header(wrench_msg_.header(), now.ns, seq_, sensor_frame_.c_str());
      msgs::to_msg(force_, torque_, wrench_msg_.wrench());
      wrench_out_.write(wrench_msg_);
    }
    ++seq_;
  }

  // parameters
  ArmParams arm_;
  Endpoints controller_;
  std::string program_, sensor_frame_;
  int rtde_port_ = 30004, stream_timeout_ = 3;
  bool lockstep_ = false, tcp_force_ = false;
  double connect_timeout_ = 2, reply_timeout_ = 0.5, reconnect_interval_ = 0.5, program_timeout_ = 2, dt_ = 0.002;

  // state
  std::unique_ptr<ArmModel> model_;
  std::unique_ptr<TcpWrench> tcp_;
  std::unique_ptr<RtdeLink> link_;
  std::unique_ptr<SafetyGate> gate_;
  std::unique_ptr<SetpointFollower> follower_;
  bool started_ = false, controller_hold_ = false, restarting_ = false, restart_abandoned_ = false;
  ProgramRestart restart_;
  std::string hold_reason_, prior_arm_fault_, restart_asked_;
  int missed_ = 0;
  std::int32_t counter_ = 0;
  std::uint64_t seq_ = 0, refused_seen_ = 0;
  std::int64_t next_reconnect_ns_ = 0, opened_ns_ = 0, restart_deadline_ns_ = 0;
  Eigen::Vector3d force_ = Eigen::Vector3d::Zero(), torque_ = Eigen::Vector3d::Zero();

  // messages and ports (reused: no allocation per tick)
  msg::WrenchStamped wrench_msg_;
  msg::ArmRequest request_msg_;
  ArmPorts ports_;
  Input<msg::WrenchStamped> wrench_in_;
  Output<msg::WrenchStamped> wrench_out_;
};

}  // namespace wysiwyf::robot::ur

WYSIWYF_COMPONENT(wysiwyf::robot::ur::UrDriver, "ur_driver")
