#pragma once
// Starting the follow program (config/robots/ur_follow.script) on the controller, at activation
// and again when the supervisor asks the arm to recover. Each step waits a bounded time and
// throws std::runtime_error saying which step failed and what the controller answered.
#include <functional>
#include <string>

#include "rtde_link.hpp"

namespace wysiwyf::robot::ur {

// The controller's text ports.
struct Endpoints {
  std::string host;
  int script_port = 30002, dashboard_port = 29999;
};

// Lockstep (the emulator, whose periods stop between input packages, so the program's watchdog
// cannot run out before the stream starts): sends the program, then asks the dashboard until it
// says PLAYING.
void start_program_before_stream(const Endpoints& c, const std::string& program, double timeout_s);

// Real time: the stream runs (`hold` sends one input package holding the arm; the counter
// moves), the program is sent, and its state on the stream says when it runs.
void start_program_on_stream(const Endpoints& c, const std::string& program, double timeout_s, RtdeLink& link,
                             const std::function<void()>& hold);

// Recovery: the dashboard unlocks a protective stop (when `unlock`), then the program goes out
// again (its start shows on the stream). Returns what was done, in words.
std::string restart_program(const Endpoints& c, const std::string& program, double timeout_s, bool unlock);

}  // namespace wysiwyf::robot::ur
