#pragma once
// ur_driver's RTDE connection to the controller (TCP port 30004): the stream, the framer and the
// client's handshake with the follow program's recipes (rtde/follow_program.hpp), then input
// packages out and output packages in, each output package checked (UrStateReader) before it is
// believed. Whatever breaks the stream closes the connection and says why: the peer closed it, a
// header the framer cannot cut, a package refused (unknown, out of turn, of another size or
// recipe), a package no controller sends (bad values), a package cut short. TCP cannot be
// resynchronised, only reopened (open() again). Refused packages are counted.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "arm_model/arm_types.hpp"
#include "rtde/client_session.hpp"
#include "rtde/framer.hpp"
#include "rtde/tcp.hpp"
#include "ur_state.hpp"

namespace wysiwyf::robot::ur {

class RtdeLink {
 public:
  RtdeLink(std::string host, std::uint16_t port, double frequency);

  // Connects (waiting at most timeout_s) and sends the handshake's first request; the handshake
  // goes on in service(). False, with error(), when the connection cannot be made.
  bool open(double timeout_s);
  // Waits (at most timeout_s) until the stream runs; false, closed, with error(), when it fails.
  bool handshake(double timeout_s);
  // Sends what waits, reads what has arrived (waiting at most wait_s for the first bytes) and
  // handles every whole package. Returns how many believable output packages came (the newest
  // in state()); a broken stream closes the connection.
  int service(double wait_s);
  // service() until an output package comes or timeout_s passes; true when one came. A package
  // begun and not finished by then was cut short: refused, and the connection closed.
  bool await_output(double timeout_s);
  // One input package: the counter, the mode and the reference (only while streaming).
  void send_inputs(std::int32_t counter, int mode, const JointVector& q, const JointVector& qd, const JointVector& qdd);
  void close(const std::string& why);

  bool connected() const { return stream_.open(); }
  bool streaming() const { return connected() && session_ && session_->streaming(); }
  // Why the connection closed or could not be opened (empty while up).
  const std::string& error() const { return error_; }
  const UrState& state() const { return state_; }
  const std::string& address() const { return address_; }
  std::uint64_t output_packages() const { return outputs_; }
  std::uint64_t refused() const { return refused_; }
  const std::string& last_refusal() const { return last_refusal_; }
  std::uint64_t connections() const { return connections_; }

 private:
  void refuse(const std::string& why);

  std::string host_, address_;
  std::uint16_t port_;
  double frequency_;
  rtde::TcpStream stream_;
  rtde::PackageFramer framer_;
  std::unique_ptr<rtde::ClientSession> session_;
  std::optional<UrStateReader> reader_;
  std::vector<std::uint8_t> in_, out_;
  UrState state_;
  double last_timestamp_ = -1;
  std::string error_, last_refusal_;
  std::uint64_t outputs_ = 0, refused_ = 0, connections_ = 0;
  std::size_t counter_index_ = 0, mode_index_ = 0;
};

}  // namespace wysiwyf::robot::ur
