#include "rtde_link.hpp"

#include <chrono>
#include <stdexcept>

#include "rtde/follow_program.hpp"

namespace wysiwyf::robot::ur {
namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

RtdeLink::RtdeLink(std::string host, std::uint16_t port, double frequency)
    : host_(std::move(host)), address_(host_ + ":" + std::to_string(port)), port_(port), frequency_(frequency) {
  in_.reserve(1 << 16);
  out_.reserve(rtde::kMaxPackageSize);
}

bool RtdeLink::open(double timeout_s) {
  stream_.close();
  framer_.reset();
  reader_.reset();
  last_timestamp_ = -1;
  try {
    stream_ = rtde::TcpStream::connect(host_, port_, timeout_s);
  } catch (const std::exception& e) {
    error_ = std::string("RTDE: ") + e.what();
    return false;
  }
  ++connections_;
  error_.clear();
  session_ =
      std::make_unique<rtde::ClientSession>(frequency_, rtde::follow::output_recipe(), rtde::follow::input_recipe());
  counter_index_ = session_->input_index(rtde::follow::kCounter);
  mode_index_ = session_->input_index(rtde::follow::kMode);
  out_.clear();
  session_->begin(out_);
  if (!stream_.send(out_)) close("RTDE: sending the version request: " + stream_.error());
  out_.clear();
  return connected();
}

bool RtdeLink::handshake(double timeout_s) {
  const auto start = std::chrono::steady_clock::now();
  while (connected() && !session_->streaming()) {
    const double left = timeout_s - seconds_since(start);
    if (left <= 0) {
      close("RTDE: the handshake with " + address_ + " did not finish within " + std::to_string(timeout_s) +
            " s (stuck " + rtde::to_string(session_->state()) + ")");
      break;
    }
    service(left);
  }
  return streaming();
}

void RtdeLink::close(const std::string& why) {
  if (connected() || error_.empty()) error_ = why;
  stream_.close();
}

void RtdeLink::refuse(const std::string& why) {
  ++refused_;
  last_refusal_ = why;
}

int RtdeLink::service(double wait_s) {
  if (!connected()) return 0;
  in_.clear();
  if (wait_s > 0) stream_.wait_readable(wait_s);
  const bool open = stream_.receive(in_);
  framer_.feed(in_.data(), in_.size());
  int fresh = 0;
  out_.clear();
  while (const auto pkg = framer_.next()) {
    const std::uint64_t refused_before = session_->refused();
    const bool data = session_->handle(*pkg, out_);
    if (session_->failed()) {
      close("RTDE handshake with " + address_ + ": " + session_->error());
      return fresh;
    }
    if (session_->refused() != refused_before) {
      // An unknown or out-of-turn package, or a data package of another size or recipe: the
      // stream's framing can no longer be trusted.
      refuse(session_->last_refusal());
      close("RTDE: refused a package from " + address_ + ": " + session_->last_refusal());
      return fresh;
    }
    if (!data) continue;
    if (!reader_) reader_.emplace(*session_);
    if (const std::string why = reader_->read(*session_, last_timestamp_, state_); !why.empty()) {
      refuse("an output package no controller sends: " + why);
      close("RTDE: refused a package from " + address_ + ": " + last_refusal_);
      return fresh;
    }
    last_timestamp_ = state_.timestamp;
    ++outputs_;
    ++fresh;
  }
  if (framer_.failed()) {
    refuse(framer_.error());
    close("RTDE: the stream from " + address_ + " cannot be framed: " + framer_.error());
    return fresh;
  }
  if (!out_.empty() && !stream_.send(out_)) close("RTDE: sending to " + address_ + ": " + stream_.error());
  if (!open) close("RTDE: " + address_ + ": " + stream_.error());
  return fresh;
}

bool RtdeLink::await_output(double timeout_s) {
  const auto start = std::chrono::steady_clock::now();
  for (;;) {
    if (service(std::max(0.0, timeout_s - seconds_since(start))) > 0) return true;
    if (!connected()) return false;
    if (seconds_since(start) >= timeout_s) break;
  }
  if (framer_.pending() > 0) {
    refuse("a package cut short: " + std::to_string(framer_.pending()) + " bytes of it came within " +
           std::to_string(timeout_s) + " s, its header claims more");
    close("RTDE: refused a package from " + address_ + ": " + last_refusal_);
  }
  return false;
}

void RtdeLink::send_inputs(std::int32_t counter, int mode, const JointVector& q, const JointVector& qd,
                           const JointVector& qdd) {
  if (!streaming()) return;
  rtde::RecipeValues& in = session_->inputs();
  in.set_int32(counter_index_, counter);
  in.set_int32(mode_index_, mode);
  for (std::size_t j = 0; j < 6; ++j) {
    const auto k = static_cast<Eigen::Index>(j);
    in.set_double(rtde::follow::kQIndex + j, q[k]);
    in.set_double(rtde::follow::kQdIndex + j, qd[k]);
    in.set_double(rtde::follow::kQddIndex + j, qdd[k]);
  }
  out_.clear();
  session_->encode_inputs(out_);
  if (!stream_.send(out_)) close("RTDE: sending inputs to " + address_ + ": " + stream_.error());
}

}  // namespace wysiwyf::robot::ur
