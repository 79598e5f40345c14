#pragma once
// The UR controller's two text ports the driver uses besides RTDE, each for one short exchange
// with a bounded wait: the primary interface (30002), which runs the URScript program sent to it
// (the pendant in Remote Control), and the dashboard server (29999), one command line answered
// by one line. Errors (std::runtime_error) name the port, the address and what failed.
#include <cstdint>
#include <string>

namespace wysiwyf::robot::ur {

// Sends `script` to the primary interface and closes the connection (the controller starts a
// program it receives whole).
void send_script(const std::string& host, std::uint16_t port, const std::string& script, double timeout_s);

// Sends one dashboard command and returns its answer line (without the line end), after the
// server's greeting line.
std::string dashboard_command(const std::string& host, std::uint16_t port, const std::string& command,
                              double timeout_s);

}  // namespace wysiwyf::robot::ur
