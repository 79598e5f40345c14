// ur-emulator: a Universal Robots e-Series controller on 127.0.0.1 (libs/robot/ur_controller_emulator):
// RTDE, the primary interface's script port and the dashboard server, running the follow
// program's behaviour (config/robots/ur_follow.script) on the same joint servo and arm dynamics
// as arm_sim with the UR5e's URDF, so pipelines with ur_driver run without the arm.
//   ur-emulator [--rtde-port 30004] [--script-port 30002] [--dashboard-port 29999] [--lockstep]
//               [--urdf FILE] [--drive FILE] [--initial-q q1 .. q6] [--encoder-counts N]
//               [--servo-bandwidth HZ]
// A port of 0 takes any free one (the line printed at the start names them). --lockstep: one
// controller period per input data package (for pipelines on the simulated clock, with
// ur_driver's `lockstep: true`); without it, a real-time 500 Hz controller.
#include <chrono>
#include <csignal>
#include <iostream>
#include <string>
#include <thread>

#include "common/option_numbers.hpp"

#include "ur_controller_emulator/ur_emulator.hpp"

namespace {
volatile std::sig_atomic_t g_stop = 0;

constexpr const char* kUsage =
    "usage: ur-emulator [--rtde-port 30004] [--script-port 30002] [--dashboard-port 29999] [--lockstep]\n"
    "                   [--urdf FILE] [--drive FILE] [--initial-q q1 .. q6] [--encoder-counts N]\n"
    "                   [--servo-bandwidth HZ]\n"
    "A Universal Robots e-Series controller on 127.0.0.1: RTDE, the script port and the dashboard\n"
    "server, running the follow program on arm_sim's joint servo and dynamics (the UR5e's URDF by\n"
    "default), so pipelines with ur_driver run without the arm. A port of 0 takes any free one (the\n"
    "first line printed names them). --lockstep: one controller period per input data package (for\n"
    "pipelines on the simulated clock, ur_driver's `lockstep: true`); without it a real-time 500 Hz\n"
    "controller. Ctrl-C stops it and prints what it did.\n";

}  // namespace

int main(int argc, char** argv) {
  using wysiwyf::apps::option_number;
  using wysiwyf::apps::option_whole;
  using wysiwyf::robot::ur::UrEmulator;
  UrEmulator::Options o;
  o.rtde_port = 30004, o.script_port = 30002, o.dashboard_port = 29999;
  try {
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      auto next = [&](const char* what) {
        if (i + 1 >= argc) throw std::invalid_argument(a + " needs " + what);
        return std::string(argv[++i]);
      };
      if (a == "--help" || a == "-h") {
        std::cout << kUsage;
        return 0;
      }
      if (a == "--rtde-port")
        o.rtde_port = static_cast<std::uint16_t>(option_whole(a, next("a port"), 0, 65535));
      else if (a == "--script-port")
        o.script_port = static_cast<std::uint16_t>(option_whole(a, next("a port"), 0, 65535));
      else if (a == "--dashboard-port")
        o.dashboard_port = static_cast<std::uint16_t>(option_whole(a, next("a port"), 0, 65535));
      else if (a == "--lockstep")
        o.lockstep = true;
      else if (a == "--urdf")
        o.controller.urdf = next("a file");
      else if (a == "--drive")
        o.controller.drive = next("a file");
      else if (a == "--encoder-counts")
        o.controller.encoder_counts = option_whole(a, next("a count"), 0, 1 << 30);
      else if (a == "--servo-bandwidth")
        o.controller.servo.bandwidth_hz = option_number(a, next("a frequency in Hz"), 0.1, 1e4);
      else if (a == "--initial-q")
        for (int j = 0; j < 6; ++j)
          o.controller.initial_q[j] = option_number(a, next("six joint angles, rad"), -10, 10);
      else
        throw std::invalid_argument("unknown option " + a + "\n" + kUsage);
    }
  } catch (const std::exception& e) {
    std::cerr << "ur-emulator: " << e.what() << "\n";
    return 2;
  }
  std::signal(SIGINT, [](int) { g_stop = 1; });
  std::signal(SIGTERM, [](int) { g_stop = 1; });
  try {
    UrEmulator emulator(o);
    std::cout << "UR emulator on 127.0.0.1: rtde " << emulator.rtde_port() << ", script " << emulator.script_port()
              << ", dashboard " << emulator.dashboard_port() << (o.lockstep ? " (lockstep)" : " (500 Hz)") << "\n"
              << std::flush;
    while (!g_stop) std::this_thread::sleep_for(std::chrono::milliseconds(100));
    const auto c = emulator.counters();
    std::cout << "ran " << c.periods << " periods, sent " << c.outputs_sent << " output packages to "
              << c.rtde_connections << " RTDE connection(s); " << c.packages_refused << " packages refused; "
              << c.scripts_run << " programs run, " << c.scripts_refused << " refused; " << c.dashboard_commands
              << " dashboard commands\n";
  } catch (const std::exception& e) {
    std::cerr << "ur-emulator: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
