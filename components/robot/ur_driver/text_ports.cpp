#include "text_ports.hpp"

#include <algorithm>
#include <chrono>
#include <stdexcept>
#include <vector>

#include "rtde/tcp.hpp"

namespace wysiwyf::robot::ur {
namespace {

std::string where(const std::string& host, std::uint16_t port) { return host + ":" + std::to_string(port); }

// The next line from `s` (bytes after it stay in `buffer`), within the deadline.
std::string read_line(rtde::TcpStream& s, std::string& buffer, std::chrono::steady_clock::time_point deadline,
                      const std::string& what) {
  for (;;) {
    if (const auto eol = buffer.find('\n'); eol != std::string::npos) {
      std::string line = buffer.substr(0, eol);
      buffer.erase(0, eol + 1);
      if (!line.empty() && line.back() == '\r') line.pop_back();
      return line;
    }
    const double left = std::chrono::duration<double>(deadline - std::chrono::steady_clock::now()).count();
    if (left <= 0) throw std::runtime_error(what + ": no answer line in time");
    s.wait_readable(left);
    std::vector<std::uint8_t> in;
    const bool open = s.receive(in, 4096);
    buffer.append(in.begin(), in.end());
    if (!open && buffer.find('\n') == std::string::npos) throw std::runtime_error(what + ": " + s.error());
    if (buffer.size() > 4096) throw std::runtime_error(what + ": an answer line longer than 4096 bytes");
  }
}

}  // namespace

void send_script(const std::string& host, std::uint16_t port, const std::string& script, double timeout_s) {
  const std::string what = "primary interface " + where(host, port);
  rtde::TcpStream s;
  try {
    s = rtde::TcpStream::connect(host, port, timeout_s);
  } catch (const std::exception& e) {
    throw std::runtime_error(what + ": " + e.what());
  }
  if (!s.send(std::vector<std::uint8_t>(script.begin(), script.end())))
    throw std::runtime_error(what + ": sending the program: " + s.error());
  // Everything queued must leave before the close (the controller runs only a whole program).
  if (!s.drain(timeout_s)) throw std::runtime_error(what + ": sending the program: " + s.error());
}

std::string dashboard_command(const std::string& host, std::uint16_t port, const std::string& command,
                              double timeout_s) {
  const std::string what = "dashboard server " + where(host, port);
  const auto deadline =
      std::chrono::steady_clock::now() +
      std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(timeout_s));
  rtde::TcpStream s;
  try {
    s = rtde::TcpStream::connect(host, port, timeout_s);
  } catch (const std::exception& e) {
    throw std::runtime_error(what + ": " + e.what());
  }
  std::string buffer;
  read_line(s, buffer, deadline, what + " (its greeting)");
  const std::string line = command + "\n";
  if (!s.send(std::vector<std::uint8_t>(line.begin(), line.end())))
    throw std::runtime_error(what + ": sending '" + command + "': " + s.error());
  return read_line(s, buffer, deadline, what + " ('" + command + "')");
}

}  // namespace wysiwyf::robot::ur
