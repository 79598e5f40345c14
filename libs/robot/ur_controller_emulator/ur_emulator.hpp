#pragma once
// A Universal Robots e-Series controller on 127.0.0.1 (UrController behind its three ports): RTDE
// (any number of clients, each its own ServerSession; input registers held by one at a time), the
// primary interface's script port (a script is read until the client closes or ends its line
// with the program's call, then loaded), and the dashboard server (line commands: unlock
// protective stop, safetystatus, programState, close safety popup). Two ways to keep time:
//  - real time: one controller period every `period` on the steady clock; outputs to each
//    streaming client at its recipe's frequency;
//  - lockstep: one period per input data package, answered by one output package, so a driver on
//    the simulated clock sees exactly what the simulated arm would; the start of a stream is
//    answered with one output package of the state it starts from (no period passes).
// Faults can be injected for tests: a protective stop, dropped connections, late or malformed
// output packages.
#include <cstdint>
#include <memory>
#include <string>

#include "ur_controller_emulator/ur_controller.hpp"

namespace wysiwyf::robot::ur {

class UrEmulator {
 public:
  struct Options {
    UrController::Options controller;
    bool lockstep = false;
    std::uint16_t rtde_port = 0, script_port = 0, dashboard_port = 0;  // 0: any free port
  };
  struct Counters {
    std::uint64_t rtde_connections = 0, packages_refused = 0, scripts_run = 0, scripts_refused = 0, periods = 0,
                  outputs_sent = 0, dashboard_commands = 0;
  };

  // Loads the arm, binds the three ports and starts; throws std::runtime_error when it cannot.
  explicit UrEmulator(Options options);
  ~UrEmulator();
  UrEmulator(const UrEmulator&) = delete;
  UrEmulator& operator=(const UrEmulator&) = delete;

  std::uint16_t rtde_port() const;
  std::uint16_t script_port() const;
  std::uint16_t dashboard_port() const;
  Counters counters() const;

  // ---- fault injection
  // The safety system stops the arm (as a collision or a speed violation would).
  void protective_stop(const std::string& why);
  // Closes every connection, as a pulled cable would (the clients may connect again).
  void drop_connections();
  // The dashboard server hangs: it takes connections and answers nothing from now on.
  void silence_dashboard();
  // The next output packages go out this many periods late (each held back, then sent at once).
  void delay_outputs(int periods);
  // The next output package to each client is cut short (its header claims the whole package).
  void send_malformed();

  // ---- the truth, for tests
  JointVector true_q() const;
  rtde::SafetyMode safety_mode() const;
  rtde::follow::ProgramState program_state() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace wysiwyf::robot::ur
