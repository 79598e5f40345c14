// rdt-emulator: an ATI Net F/T on loopback (RDT over UDP), so pipelines with ft_netft run
// without the sensor. Usage: rdt-emulator [--port 49152] [--rate 1000] [--wrench fx fy fz tx ty tz]
//                                          [--counts-per-force N] [--counts-per-torque N] [--drop-every N]
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <string>
#include <thread>

#include "netft_rdt/rdt_emulator.hpp"

static volatile std::sig_atomic_t g_stop = 0;

int main(int argc, char** argv) {
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
    if (a == "--port")
      o.port = static_cast<std::uint16_t>(std::stoi(next("a port")));
    else if (a == "--rate")
      o.rate_hz = std::stod(next("a rate in Hz"));
    else if (a == "--counts-per-force")
      o.counts_per_force = std::stod(next("a number"));
    else if (a == "--counts-per-torque")
      o.counts_per_torque = std::stod(next("a number"));
    else if (a == "--drop-every")
      o.drop_every = std::stoi(next("a number"));
    else if (a == "--wrench")
      for (auto& w : wrench) w = std::stod(next("six numbers"));
    else {
      std::cerr << "rdt-emulator: unknown option " << a << "\n";
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
}
