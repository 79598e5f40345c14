#include "ur_controller_emulator/ur_controller.hpp"

#include <charconv>
#include <cmath>
#include <stdexcept>

#include "wysiwyf/config_files.hpp"

namespace wysiwyf::robot::ur {

using rtde::FieldType;
using rtde::RuntimeState;
using rtde::SafetyMode;
using rtde::follow::ProgramState;

UrController::Options::Options() : initial_q(6) {
  // robots/ur5e-sim.yaml's parked pose: the plate at (0.55, 0, 0.4) facing +x, elbow up.
  initial_q << 2.802180, -1.581828, 1.807510, -0.225596, 1.231347, 1.570657;
}

struct UrController::Arm {
  ArmModel model;
  DriveParams drive;
  JointServo servo;
  ArmDynamics dynamics;

  static ArmModel load(const Options& o, const DriveParams& drive) {
    ArmModel m(find_config_file(o.urdf), "flange");
    if (!drive.is_ideal()) m.set_rotor_inertia(drive.reflected_inertia());
    return m;
  }
  static DriveParams drive_of(const Options& o) {
    if (o.drive.empty()) return DriveParams::ideal(static_cast<int>(o.initial_q.size()));
    return load_drive_params(find_config_file(o.drive));
  }
  explicit Arm(const Options& o)
      : model(load(o, drive_of(o))),
        drive(drive_of(o)),
        servo(model, drive, o.servo, o.initial_q),
        dynamics(model, drive, o.encoder_counts, o.servo.coulomb_smoothing) {}
};

UrController::UrController(Options options) : options_(std::move(options)) {
  arm_ = std::make_unique<Arm>(options_);
  const ArmModel& m = arm_->model;
  if (m.dof() != 6 || options_.initial_q.size() != 6)
    throw std::runtime_error("UR emulator: " + options_.urdf + " has " + std::to_string(m.dof()) +
                             " joints and initial_q " + std::to_string(options_.initial_q.size()) + "; a UR arm has 6");
  if (!m.limits().within(options_.initial_q))
    throw std::runtime_error("UR emulator: the initial joint angles are outside the limits of " + options_.urdf);
  if (!(options_.period > 0.0) || options_.substeps < 1)
    throw std::runtime_error("UR emulator: period and substeps must be positive");
  arm_->dynamics.reset(options_.initial_q);
  hold_here();
  tau_ = m.gravity_torques(options_.initial_q);
}

UrController::~UrController() = default;

const ArmModel& UrController::model() const { return arm_->model; }
JointVector UrController::true_q() const { return arm_->dynamics.q(); }

void UrController::hold_here() {
  ref_q_ = arm_->dynamics.measured_q();
  ref_qd_ = ref_qdd_ = JointVector::Zero(ref_q_.size());
}

bool UrController::load_program(const std::string& script, std::string& why) {
  if (script.compare(0, rtde::follow::kHeader.size(), rtde::follow::kHeader) != 0) {
    why =
        "this emulator runs only the follow program (a script beginning '" + std::string(rtde::follow::kHeader) + "')";
    return false;
  }
  if (safety_mode_ != SafetyMode::kNormal) {
    why = "the safety system is in " + std::string(rtde::to_string(safety_mode_)) + ": no program starts";
    return false;
  }
  running_ = true;
  program_state_ = ProgramState::kHolding;
  stop_reason_.clear();
  last_counter_ = int_registers_[24];
  stale_periods_ = 0;
  hold_here();
  return true;
}

namespace {
// N of "<prefix>N", or -1.
int register_number(const std::string& name, std::string_view prefix) {
  if (name.compare(0, prefix.size(), prefix) != 0) return -1;
  int n = -1;
  const char* first = name.data() + prefix.size();
  const auto [end, ec] = std::from_chars(first, name.data() + name.size(), n);
  return ec == std::errc() && end == name.data() + name.size() && n >= 0 && n < rtde::kRegisters ? n : -1;
}
}  // namespace

void UrController::take_inputs(const rtde::RecipeValues& inputs) {
  const rtde::Recipe& r = inputs.recipe();
  for (std::size_t i = 0; i < r.size(); ++i) {
    if (const int n = register_number(r.name(i), "input_int_register_"); n >= 0 && r.type(i) == FieldType::kInt32)
      int_registers_[static_cast<std::size_t>(n)] = inputs.get_int32(i);
    else if (const int d = register_number(r.name(i), "input_double_register_");
             d >= 0 && r.type(i) == FieldType::kDouble)
      double_registers_[static_cast<std::size_t>(d)] = inputs.get_double(i);
  }
}

void UrController::stop_program(ProgramState state, const std::string& why) {
  running_ = false;
  program_state_ = state;
  stop_reason_ = why;
  hold_here();
}

void UrController::protective_stop(const std::string& why) {
  safety_mode_ = SafetyMode::kProtectiveStop;
  stop_program(ProgramState::kNotRunning, "protective stop: " + why);
}

bool UrController::unlock_protective_stop() {
  if (safety_mode_ != SafetyMode::kProtectiveStop) return false;
  safety_mode_ = SafetyMode::kNormal;
  return true;
}

bool UrController::acceptable(const JointVector& q, const JointVector& qd, std::string& why) const {
  const ArmLimits& lim = arm_->model.limits();
  for (int j = 0; j < 6; ++j) {
    if (!std::isfinite(q[j]) || !std::isfinite(qd[j]) || q[j] < lim.lower[j] || q[j] > lim.upper[j]) {
      why = "joint " + std::to_string(j + 1) + " target outside its limits";
      return false;
    }
    // One period at the velocity limit, with slack for a reference restarting from a hold.
    if (std::abs(q[j] - ref_q_[j]) > lim.velocity[j] * options_.period * 1.5 + 5e-3 ||
        std::abs(qd[j]) > lim.velocity[j]) {
      why = "joint " + std::to_string(j + 1) + " speed limit violation";
      return false;
    }
  }
  return true;
}

void UrController::step() {
  if (running_) {
    const std::int32_t counter = int_registers_[24];
    stale_periods_ = counter == last_counter_ ? stale_periods_ + 1 : 0;
    last_counter_ = counter;
    if (stale_periods_ > rtde::follow::kWatchdogPeriods) {
      stop_program(ProgramState::kStoppedHostLost,
                   "no reference for " + std::to_string(rtde::follow::kWatchdogPeriods) + " periods; stopped");
    } else if (int_registers_[25] == rtde::follow::kFollow) {
      JointVector q(6), qd(6), qdd(6);
      const std::size_t r = rtde::follow::kFirstReferenceRegister;
      for (std::size_t j = 0; j < 6; ++j)
        q[j] = double_registers_[r + j], qd[j] = double_registers_[r + 6 + j], qdd[j] = double_registers_[r + 12 + j];
      std::string why;
      if (!acceptable(q, qd, why)) {
        protective_stop(why);
      } else {
        ref_q_ = q, ref_qd_ = qd, ref_qdd_ = qdd;
        program_state_ = ProgramState::kFollowing;
      }
    } else if (program_state_ != ProgramState::kHolding) {
      program_state_ = ProgramState::kHolding;
      hold_here();
    }
  }
  ArmDynamics& arm = arm_->dynamics;
  tau_ = arm_->servo.torque(arm.measured_q(), arm.qd(), ref_q_, ref_qd_, ref_qdd_);
  const double h = options_.period / options_.substeps;
  const JointVector none = JointVector::Zero(6);
  for (int s = 0; s < options_.substeps; ++s) arm.step(h, tau_, none);
  if (!running_ || program_state_ != ProgramState::kFollowing) ref_qdd_.setZero();
  time_ += options_.period;
}

void UrController::fill_outputs(rtde::RecipeValues& out) const {
  const rtde::Recipe& r = out.recipe();
  const auto six = [](const JointVector& v) { return std::array<double, 6>{v[0], v[1], v[2], v[3], v[4], v[5]}; };
  const ArmDynamics& arm = arm_->dynamics;
  for (std::size_t i = 0; i < r.size(); ++i) {
    const std::string& n = r.name(i);
    if (n == "timestamp")
      out.set_double(i, time_);
    else if (n == "actual_q")
      out.set_vector6d(i, six(arm.measured_q()));
    else if (n == "actual_qd")
      out.set_vector6d(i, six(arm.qd()));
    else if (n == "target_q")
      out.set_vector6d(i, six(ref_q_));
    else if (n == "target_qd")
      out.set_vector6d(i, six(ref_qd_));
    // The joint torques the servo commands, N m (the emulator has no motor currents: its
    // actual_current reports the same torques, a torque constant of 1 N m/A).
    else if (n == "target_moment" || n == "actual_current")
      out.set_vector6d(i, six(tau_));
    // No wrench acts on the emulated flange: the built-in sensor reads zero (payload compensated).
    else if (n == "actual_TCP_force")
      out.set_vector6d(i, {0, 0, 0, 0, 0, 0});
    else if (n == "robot_mode")
      out.set_int32(i, static_cast<std::int32_t>(rtde::RobotMode::kRunning));
    else if (n == "safety_mode")
      out.set_int32(i, static_cast<std::int32_t>(safety_mode_));
    else if (n == "runtime_state")
      out.set_uint32(i, static_cast<std::uint32_t>(running_ ? RuntimeState::kPlaying : RuntimeState::kStopped));
    // Bits: 0 power on, 1 program running.
    else if (n == "robot_status_bits")
      out.set_uint32(i, 1u | (running_ ? 2u : 0u));
    // Bits: 0 normal mode, 2 protective stopped.
    else if (n == "safety_status_bits")
      out.set_uint32(i, safety_mode_ == SafetyMode::kNormal           ? 1u
                        : safety_mode_ == SafetyMode::kProtectiveStop ? 4u
                                                                      : 0u);
    else if (n == rtde::follow::kProgramState)
      out.set_int32(i, static_cast<std::int32_t>(program_state_));
    else if (const int k = register_number(n, "input_int_register_"); k >= 0 && r.type(i) == FieldType::kInt32)
      out.set_int32(i, int_registers_[static_cast<std::size_t>(k)]);
    else if (const int d = register_number(n, "input_double_register_"); d >= 0 && r.type(i) == FieldType::kDouble)
      out.set_double(i, double_registers_[static_cast<std::size_t>(d)]);
  }
}

}  // namespace wysiwyf::robot::ur
