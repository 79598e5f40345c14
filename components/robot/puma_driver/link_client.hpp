#pragma once
// The host end of puma-link: one UDP socket connected to the controller, commands out, states in
// (damaged and out-of-order ones dropped and counted). Blocking only where asked to (lockstep).
#include <chrono>
#include <cstdint>
#include <string>

#include "puma_link/puma_link.hpp"

namespace wysiwyf::robot::link {

class LinkClient {
 public:
  struct Counters {
    std::uint64_t sent = 0, received = 0, dropped_damaged = 0, dropped_stale = 0;
  };
  // Throws std::invalid_argument for a host that is not an IPv4 address, std::runtime_error when
  // the socket cannot be opened.
  LinkClient(const std::string& host, std::uint16_t port);
  ~LinkClient();
  LinkClient(const LinkClient&) = delete;
  LinkClient& operator=(const LinkClient&) = delete;

  // Sends with the next sequence number (set in c); returns that sequence.
  std::uint32_t send(Command c);
  // The newest valid state that arrived since the last call, without waiting; false if none.
  bool poll_newest(State& out);
  // Waits up to `timeout` for a state acknowledging command `sequence` (older ones are consumed);
  // false on timeout.
  bool wait_for_ack(std::uint32_t sequence, std::chrono::nanoseconds timeout, State& out);

  const Counters& counters() const { return counters_; }
  const std::string& address() const { return address_; }

 private:
  bool read_one(State& out);  // the next valid, newer state already received, without waiting

  int socket_ = -1;
  std::string address_;
  std::uint32_t next_sequence_ = 0;
  bool have_state_ = false;
  std::uint32_t last_state_ = 0;
  Counters counters_;
};

}  // namespace wysiwyf::robot::link
