// The ATI Net F/T RDT protocol and the ft_netft component against the loopback emulator.
#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "netft_rdt/rdt_emulator.hpp"
#include "netft_rdt/rdt_protocol.hpp"
#include "wysiwyf/harness.hpp"
#include "wysiwyf/msgs.hpp"

namespace wysiwyf::robot::rdt {

TEST(RdtProtocol, AGoodRecordRoundTrips) {
  Record r;
  r.rdt_sequence = 0xdeadbeef;
  r.ft_sequence = 7;
  r.counts = {1000000, -2000000, 3, -4, 2147483647, -2147483647};
  const auto bytes = encode(r);
  EXPECT_EQ(bytes[0], 0xde);  // big-endian on the wire
  const RecordResult p = parse_record(bytes.data(), bytes.size(), 2147483647);
  ASSERT_EQ(p.error, ParseError::kNone);
  EXPECT_EQ(p.record.rdt_sequence, 0xdeadbeefu);
  EXPECT_EQ(p.record.counts, r.counts);
}

TEST(RdtProtocol, ShortLongAndOutOfRangeRecordsAreRejected) {
  Record r;
  r.counts = {10, 20, 30, 40, 50, 60};
  const auto bytes = encode(r);
  EXPECT_EQ(parse_record(bytes.data(), 35, 1000).error, ParseError::kShort);
  EXPECT_EQ(parse_record(bytes.data(), 0, 1000).error, ParseError::kShort);
  std::array<std::uint8_t, 37> longer{};
  EXPECT_EQ(parse_record(longer.data(), longer.size(), 1000).error, ParseError::kLong);
  EXPECT_EQ(parse_record(bytes.data(), bytes.size(), 59).error, ParseError::kOutOfRange);
  EXPECT_EQ(parse_record(bytes.data(), bytes.size(), 60).error, ParseError::kNone);
  r.counts[2] = -61;
  const auto negative = encode(r);
  EXPECT_EQ(parse_record(negative.data(), negative.size(), 60).error, ParseError::kOutOfRange);
  r.counts[2] = 0;
  r.status = 0x80000000u;
  const auto faulty = encode(r);
  EXPECT_EQ(parse_record(faulty.data(), faulty.size(), 1000).error, ParseError::kStatusError);
}

TEST(RdtProtocol, RequestsWithAWrongHeaderOrCommandAreRejected) {
  const auto start = encode(Request{Command::kStartStreaming, 0});
  EXPECT_EQ(start, (std::array<std::uint8_t, 8>{0x12, 0x34, 0x00, 0x02, 0, 0, 0, 0}));
  EXPECT_EQ(parse_request(start.data(), start.size()).error, ParseError::kNone);
  auto wrong = start;
  wrong[0] = 0x43;
  EXPECT_EQ(parse_request(wrong.data(), wrong.size()).error, ParseError::kWrongHeader);
  auto unknown = start;
  unknown[3] = 0x07;
  EXPECT_EQ(parse_request(unknown.data(), unknown.size()).error, ParseError::kUnknownCommand);
  EXPECT_EQ(parse_request(start.data(), 7).error, ParseError::kShort);
}

TEST(RdtProtocol, DroppedSamplesCountAcrossTheWrap) {
  EXPECT_EQ(dropped_between(5, 6), 0u);
  EXPECT_EQ(dropped_between(5, 9), 3u);
  EXPECT_EQ(dropped_between(0xffffffffu, 1), 1u);
}

// Ticks the component (on its own time line) until `count` wrenches arrived or the guard expires.
std::vector<msg::WrenchStamped> collect(Harness& h, Input<msg::WrenchStamped>& out, std::size_t count) {
  std::vector<msg::WrenchStamped> got;
  msg::WrenchStamped w;
  const auto guard = std::chrono::steady_clock::now() + std::chrono::seconds(5);  // a hang guard only
  for (std::int64_t t = 0; got.size() < count && std::chrono::steady_clock::now() < guard; t += 1'000'000) {
    h.tick(Time{t});
    while (out.take(w)) got.push_back(w);
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return got;
}

std::string params(std::uint16_t port, const std::string& extra = "") {
  return "{host: 127.0.0.1, port: " + std::to_string(port) + ", counts_per_force: 1000000, counts_per_torque: 1000000" +
         extra + "}";
}

TEST(FtNetFt, StreamsTheSensorsWrenchInNewtons) {
  Emulator emulator(Emulator::Options{});
  emulator.set_wrench({1.5, -2.0, 30.0, 0.25, -0.5, 0.125});
  Harness h("ft_netft", params(emulator.port()));
  auto out = h.watch<msg::WrenchStamped>("wrench");
  h.activate();
  const auto got = collect(h, out, 20);
  ASSERT_GE(got.size(), 20u);
  const auto& w = got.back().wrench();
  EXPECT_DOUBLE_EQ(w.force().x(), 1.5);
  EXPECT_DOUBLE_EQ(w.force().y(), -2.0);
  EXPECT_DOUBLE_EQ(w.force().z(), 30.0);
  EXPECT_DOUBLE_EQ(w.torque().z(), 0.125);
  EXPECT_EQ(std::string(got.back().header().frame_id().c_str()), "ft_sensor");
  h.deactivate();
}

TEST(FtNetFt, TaresOnTheFirstSamples) {
  Emulator emulator(Emulator::Options{});
  emulator.set_wrench({0.0, 0.0, -3.4, 0.0, 0.1, 0.0});  // the tool's weight
  Harness h("ft_netft", params(emulator.port(), ", tare_samples: 10"));
  auto out = h.watch<msg::WrenchStamped>("wrench");
  h.activate();
  auto got = collect(h, out, 5);
  ASSERT_GE(got.size(), 5u);
  EXPECT_NEAR(got.back().wrench().force().z(), 0.0, 1e-9);
  emulator.set_wrench({0.0, 2.0, -3.4, 0.0, 0.1, 0.0});  // a 2 N push appears
  bool seen = false;
  for (int i = 0; i < 50 && !seen; ++i) {
    got = collect(h, out, 1);
    seen = !got.empty() && std::abs(got.back().wrench().force().y() - 2.0) < 1e-9;
  }
  EXPECT_TRUE(seen);
  EXPECT_NEAR(got.back().wrench().force().z(), 0.0, 1e-9);
}

TEST(FtNetFt, DroppedRecordsShowAsSequenceGaps) {
  Emulator::Options o;
  o.drop_every = 5;
  Emulator emulator(o);
  Harness h("ft_netft", params(emulator.port()));
  auto out = h.watch<msg::WrenchStamped>("wrench");
  h.activate();
  const auto got = collect(h, out, 40);
  ASSERT_GE(got.size(), 40u);
  int gaps = 0;
  for (std::size_t i = 1; i < got.size(); ++i) {
    const auto step = got[i].header().seq() - got[i - 1].header().seq();
    EXPECT_TRUE(step == 1 || step == 2) << step;
    gaps += step == 2;
    if (step == 2) {
      EXPECT_EQ((got[i].header().seq() - 1) % 5, 0u);  // the dropped one was a multiple of 5
    }
  }
  EXPECT_GE(gaps, 7);
}

TEST(FtNetFt, RecordsWithASensorErrorAreNotPublished) {
  Emulator::Options o;
  o.bad_status = true;
  Emulator emulator(o);
  Harness h("ft_netft", params(emulator.port()));
  auto out = h.watch<msg::WrenchStamped>("wrench");
  h.activate();
  for (std::int64_t t = 0; t < 5'000'000'000 && emulator.records_sent() < 20; t += 1'000'000) {  // hang guard
    h.tick(Time{t});
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  h.tick(Time{6'000'000'000});  // take whatever else arrived
  EXPECT_GE(emulator.records_sent(), 20u);
  EXPECT_EQ(out.received(), 0u);
}

TEST(FtNetFt, ABadHostIsAConfigurationError) {
  try {
    Harness h("ft_netft", "{host: sensor.local}");
    FAIL() << "accepted";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("expected an IPv4 address"), std::string::npos) << e.what();
  }
}

}  // namespace wysiwyf::robot::rdt
