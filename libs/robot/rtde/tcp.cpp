#include "rtde/tcp.hpp"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netdb.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <stdexcept>

namespace wysiwyf::robot::rtde {
namespace {

int timeout_ms(double s) { return s <= 0 ? 0 : static_cast<int>(s * 1000.0 + 0.5); }

void set_nonblocking(int fd) { ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL, 0) | O_NONBLOCK); }

std::string where(const std::string& host, std::uint16_t port) { return host + ":" + std::to_string(port); }

}  // namespace

TcpStream::TcpStream(int fd) : fd_(fd) {
  if (fd_ < 0) return;
  set_nonblocking(fd_);
  const int one = 1;
  ::setsockopt(fd_, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
}

TcpStream::~TcpStream() { close(); }

TcpStream::TcpStream(TcpStream&& other) noexcept
    : fd_(other.fd_), queued_(std::move(other.queued_)), error_(std::move(other.error_)) {
  other.fd_ = -1;
}

TcpStream& TcpStream::operator=(TcpStream&& other) noexcept {
  if (this != &other) {
    close();
    fd_ = other.fd_;
    queued_ = std::move(other.queued_);
    error_ = std::move(other.error_);
    other.fd_ = -1;
  }
  return *this;
}

TcpStream TcpStream::connect(const std::string& host, std::uint16_t port, double timeout_s) {
  addrinfo hints{};
  hints.ai_family = AF_INET;
  hints.ai_socktype = SOCK_STREAM;
  addrinfo* found = nullptr;
  if (const int rc = ::getaddrinfo(host.c_str(), nullptr, &hints, &found); rc != 0 || !found)
    throw std::runtime_error("cannot resolve " + where(host, port) + ": " + ::gai_strerror(rc));
  sockaddr_in addr = *reinterpret_cast<const sockaddr_in*>(found->ai_addr);
  ::freeaddrinfo(found);
  addr.sin_port = htons(port);
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  if (fd < 0) throw std::runtime_error("socket for " + where(host, port) + ": " + std::strerror(errno));
  set_nonblocking(fd);
  if (::connect(fd, reinterpret_cast<const sockaddr*>(&addr), sizeof addr) != 0 && errno != EINPROGRESS) {
    const std::string why = std::strerror(errno);
    ::close(fd);
    throw std::runtime_error("cannot connect to " + where(host, port) + ": " + why);
  }
  pollfd p{fd, POLLOUT, 0};
  if (::poll(&p, 1, timeout_ms(timeout_s)) <= 0) {
    ::close(fd);
    throw std::runtime_error("no answer from " + where(host, port) + " within " + std::to_string(timeout_s) + " s");
  }
  int err = 0;
  socklen_t len = sizeof err;
  ::getsockopt(fd, SOL_SOCKET, SO_ERROR, &err, &len);
  if (err != 0) {
    ::close(fd);
    throw std::runtime_error("cannot connect to " + where(host, port) + ": " + std::strerror(err));
  }
  return TcpStream(fd);
}

bool TcpStream::flush() {
  while (!queued_.empty()) {
    const ssize_t n = ::send(fd_, queued_.data(), queued_.size(), MSG_NOSIGNAL);
    if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) return true;
    if (n < 0) {
      error_ = std::string("send: ") + std::strerror(errno);
      close();
      return false;
    }
    queued_.erase(queued_.begin(), queued_.begin() + n);
  }
  return true;
}

bool TcpStream::send(const std::vector<std::uint8_t>& bytes, std::size_t max_queued) {
  if (!open()) return false;
  queued_.insert(queued_.end(), bytes.begin(), bytes.end());
  if (!flush()) return false;
  if (queued_.size() > max_queued) {
    error_ = std::to_string(queued_.size()) + " bytes wait to be sent (the peer stopped reading)";
    close();
    return false;
  }
  return true;
}

bool TcpStream::receive(std::vector<std::uint8_t>& into, std::size_t max_bytes) {
  if (!open()) return false;
  if (!flush()) return false;
  std::uint8_t buffer[4096];
  while (max_bytes > 0) {
    const ssize_t n = ::recv(fd_, buffer, std::min(sizeof buffer, max_bytes), 0);
    if (n > 0) {
      into.insert(into.end(), buffer, buffer + n);
      max_bytes -= static_cast<std::size_t>(n);
      continue;
    }
    if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) return true;
    error_ = n == 0 ? "the peer closed the connection" : std::string("recv: ") + std::strerror(errno);
    close();
    return false;
  }
  return true;
}

bool TcpStream::wait_readable(double timeout_s) const {
  if (!open()) return false;
  pollfd p{fd_, POLLIN, 0};
  return ::poll(&p, 1, timeout_ms(timeout_s)) > 0;
}

bool TcpStream::drain(double timeout_s) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (open() && flush() && !queued_.empty()) {
    const double left = std::chrono::duration<double>(deadline - std::chrono::steady_clock::now()).count();
    if (left <= 0) {
      error_ = std::to_string(queued_.size()) + " bytes not taken within " + std::to_string(timeout_s) + " s";
      return false;
    }
    pollfd p{fd_, POLLOUT, 0};
    ::poll(&p, 1, std::max(1, timeout_ms(left)));
  }
  return open() && queued_.empty();
}

void TcpStream::close() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  queued_.clear();
}

TcpListener::TcpListener(const std::string& address, std::uint16_t port) {
  fd_ = ::socket(AF_INET, SOCK_STREAM, 0);
  if (fd_ < 0) throw std::runtime_error("socket for " + where(address, port) + ": " + std::strerror(errno));
  const int one = 1;
  ::setsockopt(fd_, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(port);
  if (::inet_pton(AF_INET, address.c_str(), &addr.sin_addr) != 1 ||
      ::bind(fd_, reinterpret_cast<const sockaddr*>(&addr), sizeof addr) != 0 || ::listen(fd_, 4) != 0) {
    const std::string why = std::strerror(errno);
    ::close(fd_);
    throw std::runtime_error("cannot listen on " + where(address, port) + ": " + why);
  }
  socklen_t len = sizeof addr;
  ::getsockname(fd_, reinterpret_cast<sockaddr*>(&addr), &len);
  port_ = ntohs(addr.sin_port);
  set_nonblocking(fd_);
}

TcpListener::~TcpListener() {
  if (fd_ >= 0) ::close(fd_);
}

TcpStream TcpListener::accept(double timeout_s) {
  pollfd p{fd_, POLLIN, 0};
  if (::poll(&p, 1, timeout_ms(timeout_s)) <= 0) return TcpStream();
  const int fd = ::accept(fd_, nullptr, nullptr);
  return TcpStream(fd);
}

}  // namespace wysiwyf::robot::rtde
