// rdt-emulator: an ATI Net F/T on loopback (RDT over UDP), so pipelines with ft_netft run
// without the sensor. Usage: rdt-emulator [--port 49152] [--rate 1000] [--wrench fx fy fz tx ty tz]
//                                          [--counts-per-force N] [--counts-per-torque N] [--drop-every N]
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <string>
#include <thread>

#include "common/option_numbers.hpp"

#include "netft_rdt/rdt_emulator.hpp"

static volatile std::sig_atomic_t g_stop = 0;

static constexpr const char* kUsage =
    "usage: rdt-emulator [--port 49152] [--rate 1000] [--wrench fx fy fz tx ty tz]\n"
    "                    [--counts-per-force N] [--counts-per-torque N] [--drop-every N]\n"
    "An ATI Net F/T sensor on loopback (RDT over UDP) streaming a constant wrench (N, N m) at the\n"
    "rate asked, so pipelines with ft_netft run without the sensor. --drop-every N leaves out every\n"
    "Nth record (a lossy network). Ctrl-C stops it.\n";

int main(int argc, char** argv) try {
  using wysiwyf::apps::option_number;
  using wysiwyf::apps::option_whole;
  wysiwyf::robot::rdt::Emulator::Options o;
  o.port = 49152;
  std::array<double, 6> wrench{};
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&](const char* what) {
      if (i + 1 >= argc) {
        std::cerr << "rdt-emulator: " << a << " needs " << what << "\n";
        std::exit(2);
      }
      return std::string(argv[++i]);
    };
    if (a == "--help" || a == "-h") {
      std::cout << kUsage;
      return 0;
    }
    if (a == "--port")
      o.port = static_cast<std::uint16_t>(option_whole(a, next("a port"), 0, 65535));
    else if (a == "--rate")
      o.rate_hz = option_number(a, next("a rate in Hz"), 1, 1e5);
    else if (a == "--counts-per-force")
      o.counts_per_force = option_number(a, next("a number"), 1e-6, 1e12);
    else if (a == "--counts-per-torque")
      o.counts_per_torque = option_number(a, next("a number"), 1e-6, 1e12);
    else if (a == "--drop-every")
      o.drop_every = option_whole(a, next("a number"), 0, 1 << 30);
    else if (a == "--wrench")
      for (auto& w : wrench) w = option_number(a, next("six numbers"), -1e6, 1e6);
    else {
      std::cerr << "rdt-emulator: unknown option " << a << "\n" << kUsage;
      return 2;
    }
  }
  std::signal(SIGINT, [](int) { g_stop = 1; });
  std::signal(SIGTERM, [](int) { g_stop = 1; });
  wysiwyf::robot::rdt::Emulator emulator(o);
  emulator.set_wrench(wrench);
  std::cout << "RDT emulator on 127.0.0.1:" << emulator.port() << " at " << o.rate_hz << " Hz\n" << std::flush;
  while (!g_stop) std::this_thread::sleep_for(std::chrono::milliseconds(100));
  std::cout << "sent " << emulator.records_sent() << " records\n";
  return 0;
} catch (const std::exception& e) {  // an option refused, a port in use, ...
  std::cerr << "rdt-emulator: " << e.what() << "\n" << kUsage;
  return 2;
}
