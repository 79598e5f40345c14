#pragma once
// The controller end of puma-link on 127.0.0.1: the PUMA's 1 kHz joint servo and arm dynamics
// (the ones arm_sim runs, from arm_sim), answering a puma_driver. Two ways to keep time:
//  - real time: a 1 kHz loop on the steady clock; each period it applies the newest command,
//    advances the arm and sends its state to the host; with no valid command for
//    timeout_periods it holds the arm where it is (status holding, fault "command timeout");
//  - lockstep: the arm advances one servo period per command and the state answers it, so a
//    driver on the simulated clock (its `lockstep` parameter) sees exactly what arm_sim would.
// Like a real controller it checks every command: outside the joint limits, a step beyond
// the velocity limit, or an overspeed reference latch a fault (the arm holds) until a command
// with the reset flag. Damaged or stale datagrams are dropped and counted.
#include <atomic>
#include <cstdint>
#include <memory>
#include <string>
#include <thread>

#include "arm_joint_sim/joint_servo.hpp"
#include "puma_link/puma_link.hpp"

namespace wysiwyf::robot::link {

class ControllerEmulator {
 public:
  struct Options {
    std::uint16_t port = 0;  // 0: any free port (see port())
    bool lockstep = false;
    double period = 1e-3;                             // servo period, s
    int timeout_periods = 3;                          // real time: periods without a command before holding
    std::string urdf = "robots/puma560.urdf";         // found like every config file (cwd, config/, ...)
    std::string drive = "robots/puma560_drive.yaml";  // empty: ideal drives
    Vector6d initial_q;                               // at rest here at start (default: arm_sim's ready pose)
    JointServoConfig servo;                           // arm_sim's defaults
    int encoder_counts = 1000;
    int substeps = 4;
    Options();
  };
  struct Counters {
    std::uint64_t commands_applied = 0, queries = 0, states_sent = 0, dropped_damaged = 0, dropped_stale = 0,
                  timeouts = 0, rejected = 0;
  };

  // Loads the model, binds the port and starts the loop; throws std::runtime_error when it cannot.
  explicit ControllerEmulator(Options options);
  ~ControllerEmulator();
  ControllerEmulator(const ControllerEmulator&) = delete;
  ControllerEmulator& operator=(const ControllerEmulator&) = delete;

  std::uint16_t port() const;
  Counters counters() const;
  // Test hook: while silent it reads and drops everything and sends nothing (a pulled cable).
  void set_silent(bool silent);
  // The arm's true joint angles (for tests), read between periods.
  Vector6d true_q() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace wysiwyf::robot::link
