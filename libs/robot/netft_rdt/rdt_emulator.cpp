#include "netft_rdt/rdt_emulator.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>

#include "netft_rdt/rdt_protocol.hpp"

namespace wysiwyf::robot::rdt {

Emulator::Emulator(Options options) : options_(options) {
  socket_ = ::socket(AF_INET, SOCK_DGRAM, 0);
  if (socket_ < 0) throw std::runtime_error(std::string("RDT emulator: socket: ") + std::strerror(errno));
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(options_.port);
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);  // loopback only
  if (::bind(socket_, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0) {
    ::close(socket_);
    throw std::runtime_error("RDT emulator: cannot bind 127.0.0.1:" + std::to_string(options_.port) + ": " +
                             std::strerror(errno));
  }
  socklen_t len = sizeof addr;
  ::getsockname(socket_, reinterpret_cast<sockaddr*>(&addr), &len);
  port_ = ntohs(addr.sin_port);
  thread_ = std::thread([this] { run(); });
}

Emulator::~Emulator() {
  stop_ = true;
  if (thread_.joinable()) thread_.join();
  ::close(socket_);
}

void Emulator::set_wrench(const std::array<double, 6>& wrench) {
  std::lock_guard<std::mutex> lock(mutex_);
  wrench_ = wrench;
}

void Emulator::run() {
  using Clock = std::chrono::steady_clock;
  sockaddr_in client{};
  bool streaming = false;
  std::uint64_t remaining = 0;  // 0: endless
  std::uint32_t rdt_sequence = 0, ft_sequence = 0;
  const auto period = std::chrono::nanoseconds(static_cast<std::int64_t>(1e9 / options_.rate_hz));
  auto next = Clock::now();
  while (!stop_) {
    // Requests: wait up to the next record's time.
    const auto wait_ms =
        streaming
            ? std::max<long>(0, std::chrono::duration_cast<std::chrono::milliseconds>(next - Clock::now()).count())
            : 20;
    pollfd pfd{socket_, POLLIN, 0};
    if (::poll(&pfd, 1, static_cast<int>(wait_ms)) > 0) {
      std::uint8_t buffer[64];
      sockaddr_in from{};
      socklen_t len = sizeof from;
      const ssize_t n = ::recvfrom(socket_, buffer, sizeof buffer, 0, reinterpret_cast<sockaddr*>(&from), &len);
      if (n > 0) {
        ++requests_;
        const RequestResult r = parse_request(buffer, static_cast<std::size_t>(n));
        if (r.error == ParseError::kNone) {
          if (r.request.command == Command::kStartStreaming) {
            client = from;
            streaming = true;
            remaining = r.request.sample_count;
            next = Clock::now();
          } else if (r.request.command == Command::kStop) {
            streaming = false;
          }
        }
      }
    }
    if (!streaming || Clock::now() < next) continue;
    next += period;
    ++ft_sequence;
    ++rdt_sequence;
    if (options_.drop_every > 0 && rdt_sequence % static_cast<std::uint32_t>(options_.drop_every) == 0) continue;
    Record rec;
    rec.rdt_sequence = rdt_sequence;
    rec.ft_sequence = ft_sequence;
    rec.status = options_.bad_status ? 0x80000000u : 0u;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      for (int i = 0; i < 6; ++i)
        rec.counts[i] = static_cast<std::int32_t>(
            std::lround(wrench_[i] * (i < 3 ? options_.counts_per_force : options_.counts_per_torque)));
    }
    const auto bytes = encode(rec);
    ::sendto(socket_, bytes.data(), bytes.size(), 0, reinterpret_cast<sockaddr*>(&client), sizeof client);
    ++sent_;
    if (remaining > 0 && --remaining == 0) streaming = false;
  }
}

}  // namespace wysiwyf::robot::rdt
