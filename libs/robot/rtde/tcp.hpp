#pragma once
// TCP for the UR's interfaces (RTDE on 30004, the primary interface's script port 30002): a
// connected stream that never blocks the caller's tick (bytes that cannot go out yet wait in a
// bounded queue; reads take what has arrived) and a listener for the emulator. IPv4 only, as the
// controller is. Errors say what failed and where.
#include <cstdint>
#include <string>
#include <vector>

namespace wysiwyf::robot::rtde {

class TcpStream {
 public:
  TcpStream() = default;
  // Takes an accepted or connected socket (made non-blocking, Nagle off: small packages go at once).
  explicit TcpStream(int fd);
  ~TcpStream();
  TcpStream(TcpStream&& other) noexcept;
  TcpStream& operator=(TcpStream&& other) noexcept;
  TcpStream(const TcpStream&) = delete;
  TcpStream& operator=(const TcpStream&) = delete;

  // Connects to host:port (a dotted IPv4 address or a name), waiting at most timeout_s. Throws
  // std::runtime_error naming the address and the reason.
  static TcpStream connect(const std::string& host, std::uint16_t port, double timeout_s);

  bool open() const { return fd_ >= 0; }
  // Queues bytes and sends what the socket takes now. False when the connection is gone or more
  // than max_queued bytes wait (a peer that stopped reading): then closed, with error() saying why.
  bool send(const std::vector<std::uint8_t>& bytes, std::size_t max_queued = 1 << 20);
  // Appends what has arrived (at most max_bytes) to `into`. False when the peer closed or the
  // connection failed: then closed, with error() saying why.
  bool receive(std::vector<std::uint8_t>& into, std::size_t max_bytes = 1 << 16);
  // Waits until bytes arrive or timeout_s passes; true when there are bytes (or an end) to read.
  bool wait_readable(double timeout_s) const;
  // Bytes queued and not yet taken by the socket.
  std::size_t queued() const { return queued_.size(); }
  // Sends the queue, waiting at most timeout_s for the socket to take it (before a close that
  // must not lose it); false when bytes are left or the connection failed (then error() says).
  bool drain(double timeout_s);
  void close();
  const std::string& error() const { return error_; }

 private:
  bool flush();
  int fd_ = -1;
  std::vector<std::uint8_t> queued_;
  std::string error_;
};

class TcpListener {
 public:
  // Listens on address:port (port 0: any free port). Throws std::runtime_error naming the address.
  TcpListener(const std::string& address, std::uint16_t port);
  ~TcpListener();
  TcpListener(const TcpListener&) = delete;
  TcpListener& operator=(const TcpListener&) = delete;

  std::uint16_t port() const { return port_; }
  // A connection waiting to be accepted, within timeout_s, or a closed stream.
  TcpStream accept(double timeout_s);

 private:
  int fd_ = -1;
  std::uint16_t port_ = 0;
};

}  // namespace wysiwyf::robot::rtde
