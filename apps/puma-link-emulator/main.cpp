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

#include "common/option_numbers.hpp"

#include "puma_controller_emulator/controller_emulator.hpp"

namespace {
volatile std::sig_atomic_t g_stop = 0;

constexpr const char* kUsage =
    "usage: puma-link-emulator [--port 47000] [--lockstep] [--initial-q q1 .. q6] [--encoder-counts N]\n"
    "                          [--servo-bandwidth HZ] [--urdf FILE] [--drive FILE]\n"
    "A PUMA 560 joint controller on 127.0.0.1 (the joint-level link of docs/puma-link.md), running\n"
    "arm_sim's joint servo and arm dynamics, so pipelines with puma_driver run without the arm.\n"
    "--lockstep: one servo period per command (for pipelines on the simulated clock, puma_driver's\n"
    "`lockstep: true`); without it a real-time 1 kHz servo loop. Ctrl-C stops it.\n";
}  // namespace

int main(int argc, char** argv) {
  using wysiwyf::apps::option_number;
  using wysiwyf::apps::option_whole;
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
      if (a == "--help" || a == "-h") {
        std::cout << kUsage;
        return 0;
      }
      if (a == "--port")
        o.port = static_cast<std::uint16_t>(option_whole(a, next("a port"), 0, 65535));
      else if (a == "--lockstep")
        o.lockstep = true;
      else if (a == "--encoder-counts")
        o.encoder_counts = option_whole(a, next("a count"), 0, 1 << 30);
      else if (a == "--servo-bandwidth")
        o.servo.bandwidth_hz = option_number(a, next("a frequency in Hz"), 0.1, 1e4);
      else if (a == "--urdf")
        o.urdf = next("a file");
      else if (a == "--drive")
        o.drive = next("a file");
      else if (a == "--initial-q")
        for (int j = 0; j < 6; ++j) o.initial_q[j] = option_number(a, next("six joint angles, rad"), -10, 10);
      else
        throw std::invalid_argument("unknown option " + a + "\n" + kUsage);
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
