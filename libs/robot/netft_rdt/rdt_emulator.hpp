#pragma once
// An ATI Net F/T on loopback: answers RDT requests on a UDP port and streams records of a
// configurable wrench, for tests and for running pipelines without the sensor
// (apps/rdt-emulator). Faults can be injected: dropped records, a bad status word.
#include <array>
#include <atomic>
#include <cstdint>
#include <mutex>
#include <thread>

namespace wysiwyf::robot::rdt {

class Emulator {
 public:
  struct Options {
    std::uint16_t port = 0;  // 0: any free port (see port())
    double rate_hz = 1000;   // records per second while streaming
    double counts_per_force = 1e6;
    double counts_per_torque = 1e6;
    int drop_every = 0;       // skip every n-th record (0: none)
    bool bad_status = false;  // report a sensor error in every record
  };
  explicit Emulator(Options options);
  ~Emulator();
  Emulator(const Emulator&) = delete;
  Emulator& operator=(const Emulator&) = delete;

  std::uint16_t port() const { return port_; }
  // The wrench it reports from now on: Fx Fy Fz (N), Tx Ty Tz (N.m).
  void set_wrench(const std::array<double, 6>& wrench);
  std::uint64_t records_sent() const { return sent_.load(); }
  std::uint64_t requests_received() const { return requests_.load(); }

 private:
  void run();

  Options options_;
  int socket_ = -1;
  std::uint16_t port_ = 0;
  std::thread thread_;
  std::atomic<bool> stop_{false};
  std::atomic<std::uint64_t> sent_{0}, requests_{0};
  std::mutex mutex_;
  std::array<double, 6> wrench_{};
};

}  // namespace wysiwyf::robot::rdt
