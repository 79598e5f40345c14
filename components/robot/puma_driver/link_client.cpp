#include "link_client.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace wysiwyf::robot::link {

LinkClient::LinkClient(const std::string& host, std::uint16_t port) : address_(host + ":" + std::to_string(port)) {
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(port);
  if (::inet_pton(AF_INET, host.c_str(), &addr.sin_addr) != 1)
    throw std::invalid_argument("host: found '" + host + "'; expected an IPv4 address like 192.168.1.20");
  socket_ = ::socket(AF_INET, SOCK_DGRAM, 0);
  if (socket_ < 0) throw std::runtime_error(std::string("puma-link: socket: ") + std::strerror(errno));
  // connect(): only the controller's datagrams are received, and sends go to it.
  if (::connect(socket_, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0) {
    const std::string why = std::strerror(errno);
    ::close(socket_);
    throw std::runtime_error("puma-link: cannot address " + address_ + ": " + why);
  }
}

LinkClient::~LinkClient() { ::close(socket_); }

std::uint32_t LinkClient::send(Command c) {
  c.sequence = next_sequence_++;
  const auto bytes = encode(c);
  // A refused send (nobody listening yet: ICMP port unreachable) is the same as a lost datagram.
  if (::send(socket_, bytes.data(), bytes.size(), MSG_DONTWAIT) == static_cast<ssize_t>(bytes.size())) ++counters_.sent;
  return c.sequence;
}

bool LinkClient::read_one(State& out) {
  std::uint8_t buffer[512];
  for (;;) {
    const ssize_t n = ::recv(socket_, buffer, sizeof buffer, MSG_DONTWAIT);
    if (n < 0) {
      if (errno == ECONNREFUSED) continue;  // a port-unreachable report from an earlier send: not data
      return false;
    }
    State s;
    if (decode(buffer, static_cast<std::size_t>(n), s) != DecodeError::kNone) {
      ++counters_.dropped_damaged;
      continue;
    }
    // A controller restart begins its states at 0 again: a big step back is a new session.
    if (have_state_ && !newer(s.sequence, last_state_) && last_state_ - s.sequence < 1000) {
      ++counters_.dropped_stale;
      continue;
    }
    have_state_ = true;
    last_state_ = s.sequence;
    ++counters_.received;
    out = s;
    return true;
  }
}

bool LinkClient::poll_newest(State& out) {
  bool got = false;
  State s;
  while (read_one(s)) {
    out = s;
    got = true;
  }
  return got;
}

bool LinkClient::wait_for_ack(std::uint32_t sequence, std::chrono::nanoseconds timeout, State& out) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::nanoseconds>(deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) return false;
    pollfd pfd{socket_, POLLIN, 0};
    const timespec ts{static_cast<time_t>(left.count() / 1'000'000'000),
                      static_cast<long>(left.count() % 1'000'000'000)};
    if (::ppoll(&pfd, 1, &ts, nullptr) <= 0) continue;
    State s;
    if (!read_one(s)) continue;
    if (s.ack == sequence) {
      out = s;
      return true;
    }
  }
}

}  // namespace wysiwyf::robot::link
