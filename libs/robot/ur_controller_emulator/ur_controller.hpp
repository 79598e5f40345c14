#pragma once
// A Universal Robots e-Series controller as the display meets it, without its sockets: the
// general purpose registers RTDE clients write, the program the primary interface received (only
// the follow program, config/robots/ur_follow.script, is executed: its behaviour is emulated, not
// its text interpreted), the robot's and the safety system's modes, and the arm the program drives.
// servoj toward the registers' reference runs the same JointServo and ArmDynamics as the
// simulated arm (arm_sim with the UR5e's URDF), so the two move alike to the last bit.
// Like the real controller it stops on its own: a target further than one period at the joints'
// velocity limits (a speed violation) or outside the limits is a protective stop, and a program
// whose counter stops for kWatchdogPeriods periods stops the arm and ends.
#include <array>
#include <memory>
#include <string>

#include "arm_joint_sim/arm_dynamics.hpp"
#include "arm_joint_sim/joint_servo.hpp"
#include "rtde/follow_program.hpp"
#include "rtde/recipe.hpp"
#include "rtde/variables.hpp"

namespace wysiwyf::robot::ur {

class UrController {
 public:
  struct Options {
    std::string urdf = "robots/ur5e.urdf";  // found like every config file (cwd, config/, ...)
    std::string drive;                      // a drive file, or empty: ideal drives
    JointVector initial_q;                  // at rest here (default: robots/ur5e-sim.yaml's parked pose)
    JointServoConfig servo;                 // the simulated arm's defaults
    int encoder_counts = 0;                 // per joint revolution (0: no quantisation)
    int substeps = 4;                       // integration steps per period
    double period = 0.002;                  // s: the e-Series' 500 Hz
    Options();
  };

  // Loads the arm; throws std::runtime_error naming what is wrong.
  explicit UrController(Options options);
  ~UrController();

  // A script from the primary interface. The follow program starts (true); anything else is
  // refused with why (this emulator runs no other program).
  bool load_program(const std::string& script, std::string& why);
  // Takes the registers of an input data package (any recipe of input registers).
  void take_inputs(const rtde::RecipeValues& inputs);
  // One controller period.
  void step();
  // Fills every field of an output recipe it knows (the rest stay as they are).
  void fill_outputs(rtde::RecipeValues& out) const;

  // Fault injection and the pendant's (dashboard server's) answers.
  void protective_stop(const std::string& why);
  // Releases a protective stop (the dashboard's "unlock protective stop"); false when none.
  bool unlock_protective_stop();

  bool program_running() const { return running_; }
  rtde::follow::ProgramState program_state() const { return program_state_; }
  rtde::SafetyMode safety_mode() const { return safety_mode_; }
  const std::string& stop_reason() const { return stop_reason_; }
  double time() const { return time_; }
  JointVector true_q() const;
  const ArmModel& model() const;

 private:
  void hold_here();
  void stop_program(rtde::follow::ProgramState state, const std::string& why);
  // Whether the registers' reference is one the arm can take this period (else a protective stop).
  bool acceptable(const JointVector& q, const JointVector& qd, std::string& why) const;

  struct Arm;
  std::unique_ptr<Arm> arm_;
  Options options_;
  std::array<std::int32_t, rtde::kRegisters> int_registers_{};
  std::array<double, rtde::kRegisters> double_registers_{};
  bool running_ = false;
  rtde::follow::ProgramState program_state_ = rtde::follow::ProgramState::kNotRunning;
  rtde::SafetyMode safety_mode_ = rtde::SafetyMode::kNormal;
  std::string stop_reason_;
  std::int32_t last_counter_ = 0;
  int stale_periods_ = 0;
  JointVector ref_q_, ref_qd_, ref_qdd_, tau_;
  double time_ = 0;
};

}  // namespace wysiwyf::robot::ur
