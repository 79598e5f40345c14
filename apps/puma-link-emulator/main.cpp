// puma-link-emulator: a PUMA 560 joint controller on 127.0.0.1 (docs/puma-link.md), running the
// same joint servo and arm dynamics as arm_sim, so pipelines with puma_driver run without the arm.
//   puma-link-emulator [--port 47000] [--lockstep] [--initial-q q1 .. q6] [--encoder-counts N]
//                      [--servo-bandwidth HZ] [--urdf FILE] [--drive FILE]
// --lockstep: one servo period per command (for pipelines on the simulated clock, with
// puma_driver's `lockstep: true`); without it, a real-time 1 kHz servo loop.
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <iostream>
#include <string>
#include <thread>

#include "puma_controller_emulator/controller_emulator.hpp"

namespace {
volatile std::sig_atomic_t g_stop = 0;
}

int main(int argc, char** argv) {
  using wysiwyf::robot::link::ControllerEmulator;
  ControllerEmulator::Options o;
  o.port = wysiwyf::robot::link::kDefaultPort;
  try {
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      auto next = [&](const char* what) {
        if (i + 1 >= argc) throw std::invalid_argument(a + " needs " + what);
        return std::string(argv[++i]);
      };
      if (a == "--port")
        o.port = static_cast<std::uint16_t>(std::stoi(next("a port")));
      else if (a == "--lockstep")
        o.lockstep = true;
      else if (a == "--encoder-counts")
        o.encoder_counts = std::stoi(next("a count"));
      else if (a == "--servo-bandwidth")
        o.servo.bandwidth_hz = std::stod(next("a frequency in Hz"));
      else if (a == "--urdf")
        o.urdf = next("a file");
      else if (a == "--drive")
        o.drive = next("a file");
      else if (a == "--initial-q")
        for (int j = 0; j < 6; ++j) o.initial_q[j] = std::stod(next("six joint angles, rad"));
      else
        throw std::invalid_argument("unknown option " + a +
                                    " (see the comment at the top of apps/puma-link-emulator/main.cpp)");
    }
  } catch (const std::exception& e) {
    std::cerr << "puma-link-emulator: " << e.what() << "\n";
    return 2;
  }
  std::signal(SIGINT, [](int) { g_stop = 1; });
  std::signal(SIGTERM, [](int) { g_stop = 1; });
  try {
    ControllerEmulator emulator(o);
    std::cout << "puma-link emulator on 127.0.0.1:" << emulator.port() << (o.lockstep ? " (lockstep)" : " (1 kHz)")
              << "\n"
              << std::flush;
    while (!g_stop) std::this_thread::sleep_for(std::chrono::milliseconds(100));
    const auto c = emulator.counters();
    std::cout << "applied " << c.commands_applied << " commands, answered " << c.queries << " queries, sent "
              << c.states_sent << " states; dropped " << c.dropped_damaged << " damaged, " << c.dropped_stale
              << " out-of-order; " << c.timeouts << " command timeouts, " << c.rejected << " commands refused\n";
  } catch (const std::exception& e) {
    std::cerr << "puma-link-emulator: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
