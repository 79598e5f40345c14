// ft_netft: the ATI Net F/T wrist force/torque sensor over UDP (RDT). Streams in activate(),
// publishes every record as a WrenchStamped in the sensor frame (header.seq = the record's
// rdt_sequence, so consumers see gaps too), counts dropped and rejected records, optionally
// tares on its first tare_samples records after activation (the sensor alone: with the display's
// tool mounted, leave it at 0, since the supervisor and admittance_sim take the tool's weight out
// themselves), and asks the sensor to stream again when it falls silent.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstring>

#include "netft_rdt/rdt_protocol.hpp"
#include "wysiwyf/component.hpp"
#include "wysiwyf/msg_eigen.hpp"

namespace wysiwyf::robot {

class FtNetFt final : public Component {
 public:
  void configure(Context& ctx) override {
    ctx.summary("ATI Net F/T force/torque sensor over UDP (RDT streaming)");
    host_ = ctx.param<std::string>("host", "192.168.1.1", "the sensor's IPv4 address");
    port_ = ctx.param<int>("port", rdt::kDefaultPort, "the sensor's RDT UDP port", Range{1, 65535});
    counts_per_force_ =
        ctx.param<double>("counts_per_force", 1e6, "counts per N (the sensor's calibration)", Range{1, 1e9});
    counts_per_torque_ =
        ctx.param<double>("counts_per_torque", 1e6, "counts per N.m (the sensor's calibration)", Range{1, 1e9});
    max_counts_ = static_cast<std::int64_t>(ctx.param<double>(
        "max_counts", 2147483647.0, "readings beyond this many counts are rejected (the calibrated range)",
        Range{1, 2147483647.0}));
    tare_samples_ =
        ctx.param<int>("tare_samples", 0, "average this many first samples as the bias (0: no tare)", Range{0, 100000});
    silence_ms_ = ctx.param<int>(
        "silence_ms", 100, "no record for this long: report it and ask the sensor to stream again", Range{1, 60000});
    frame_id_ = ctx.param<std::string>("frame_id", "ft_sensor", "frame of the published wrench");
    wrench_ =
        ctx.output<msg::WrenchStamped>("wrench", "every record, in the sensor frame, bias removed", Qos::sensor(16));
    sockaddr_in probe{};
    if (::inet_pton(AF_INET, host_.c_str(), &probe.sin_addr) != 1)
      ctx.reject("host", "found '" + host_ + "'; expected an IPv4 address like 192.168.1.1");
  }

  void activate() override {
    socket_ = ::socket(AF_INET, SOCK_DGRAM, 0);
    if (socket_ < 0) throw std::runtime_error(std::string("socket: ") + std::strerror(errno));
    sockaddr_in addr{};
    addr.sin_family = AF_INET;
    addr.sin_port = htons(static_cast<std::uint16_t>(port_));
    ::inet_pton(AF_INET, host_.c_str(), &addr.sin_addr);
    // connect(): only the sensor's datagrams are received, and sends go to it.
    if (::connect(socket_, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0)
      throw std::runtime_error("cannot reach the F/T sensor at " + host_ + ":" + std::to_string(port_) + ": " +
                               std::strerror(errno));
    send(rdt::Command::kStartStreaming);
  }

  void tick(Time now) override {
    std::uint8_t buffer[64];
    bool got = false;
    for (int i = 0; i < 256; ++i) {  // drain what arrived since the last tick
      const ssize_t n = ::recv(socket_, buffer, sizeof buffer, MSG_DONTWAIT);
      if (n < 0) break;
      got = true;
      const rdt::RecordResult r = rdt::parse_record(buffer, static_cast<std::size_t>(n), max_counts_);
      if (r.error != rdt::ParseError::kNone) {
        ++rejected_;
        warn_once("rejected a record: " + rdt::to_string(r.error) + " (further ones are counted in the diagnostics)");
        continue;
      }
      if (received_ > 0) {
        const std::uint32_t gap = rdt::dropped_between(last_sequence_, r.record.rdt_sequence);
        if (gap < 1'000'000u) dropped_ += gap;  // larger: reordered, or the sensor restarted its count
      }
      last_sequence_ = r.record.rdt_sequence;
      ++received_;
      publish(r.record, now);
    }
    if (got) {
      last_data_ns_ = now.ns;
      if (silent_) log("the sensor streams again");
      silent_ = false;
    } else if (last_data_ns_ >= 0 ? now.ns - last_data_ns_ > silence_ms_ * 1'000'000LL : false) {
      if (!silent_) log("no record for " + std::to_string(silence_ms_) + " ms: asking the sensor to stream again");
      silent_ = true;
      last_data_ns_ = now.ns;  // ask again after another silence period
      send(rdt::Command::kStartStreaming);
    } else if (last_data_ns_ < 0) {
      last_data_ns_ = now.ns;
    }
  }

  void deactivate() override {
    if (socket_ >= 0) {
      send(rdt::Command::kStop);
      ::close(socket_);
      socket_ = -1;
    }
    log("received " + std::to_string(received_) + " records, " + std::to_string(dropped_) + " dropped, " +
        std::to_string(rejected_) + " rejected");
  }

 private:
  void send(rdt::Command c) {
    const auto bytes = rdt::encode(rdt::Request{c, 0});
    ::send(socket_, bytes.data(), bytes.size(), MSG_DONTWAIT);
  }

  void publish(const rdt::Record& rec, Time now) {
    msgs::Vector6d w;
    for (int i = 0; i < 6; ++i) w[i] = rec.counts[i] / (i < 3 ? counts_per_force_ : counts_per_torque_);
    if (tared_ < tare_samples_) {  // still measuring the bias
      for (int i = 0; i < 6; ++i) bias_[i] += w[i] / tare_samples_;
      ++tared_;
      return;
    }
    for (int i = 0; i < 6; ++i) w[i] -= bias_[i];
    fill_header(msg_.header(), now.ns, rec.rdt_sequence, frame_id_.c_str());
    msgs::to_msg(w, msg_.wrench());
    wrench_.write(msg_);
  }

  std::string host_, frame_id_;
  int port_ = rdt::kDefaultPort, tare_samples_ = 0, tared_ = 0, silence_ms_ = 100;
  double counts_per_force_ = 1e6, counts_per_torque_ = 1e6;
  std::int64_t max_counts_ = 0, last_data_ns_ = -1;
  int socket_ = -1;
  bool silent_ = false;
  std::uint32_t last_sequence_ = 0;
  std::uint64_t received_ = 0, dropped_ = 0, rejected_ = 0;
  msgs::Vector6d bias_ = msgs::Vector6d::Zero();
  msg::WrenchStamped msg_;
  Output<msg::WrenchStamped> wrench_;
};

}  // namespace wysiwyf::robot

WYSIWYF_COMPONENT(wysiwyf::robot::FtNetFt, "ft_netft")
