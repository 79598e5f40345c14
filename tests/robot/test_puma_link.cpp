// The puma-link codec: round trips, and every kind of damaged datagram refused.
#include <gtest/gtest.h>

#include <zlib.h>

#include <cmath>

#include "puma_link/puma_link.hpp"

namespace wysiwyf::robot::link {

TEST(PumaLink, CommandsAndStatesRoundTrip) {
  Command c;
  c.sequence = 0xfffffffeu;
  c.hold = true;
  c.q = {0.1, -0.2, 0.3, -1e-12, 2.5, -3.14159};
  c.qd = {1, 2, 3, 4, 5, -6};
  c.qdd = {-0.5, 0, 0, 0, 0, 7.25};
  const auto bytes = encode(c);
  ASSERT_EQ(bytes.size(), 168u);
  Command back;
  ASSERT_EQ(decode(bytes.data(), bytes.size(), back), DecodeError::kNone);
  EXPECT_EQ(back.sequence, c.sequence);
  EXPECT_TRUE(back.hold);
  EXPECT_FALSE(back.reset_fault);
  EXPECT_FALSE(back.query);
  EXPECT_EQ(back.q, c.q);
  EXPECT_EQ(back.qd, c.qd);
  EXPECT_EQ(back.qdd, c.qdd);
  State s;
  s.sequence = 7;
  s.ack = 6;
  s.status = Status::kFault;
  s.fault = Fault::kCommandTimeout;
  s.q = {1, 2, 3, 4, 5, 6};
  s.qd = {-1, -2, -3, -4, -5, -6};
  s.tau = {0.5, 0, 0, 0, 0, 9};
  const auto sb = encode(s);
  State sback;
  ASSERT_EQ(decode(sb.data(), sb.size(), sback), DecodeError::kNone);
  EXPECT_EQ(sback.ack, 6u);
  EXPECT_EQ(sback.status, Status::kFault);
  EXPECT_EQ(sback.fault, Fault::kCommandTimeout);
  EXPECT_EQ(sback.q, s.q);
  EXPECT_EQ(sback.tau, s.tau);
}

TEST(PumaLink, DamagedDatagramsAreRefused) {
  Command c;
  c.q = {0.1, 0.2, 0.3, 0.4, 0.5, 0.6};
  const auto good = encode(c);
  Command out;
  EXPECT_EQ(decode(good.data(), good.size() - 1, out), DecodeError::kSize);
  auto bad = good;
  bad[0] ^= 0xff;
  EXPECT_EQ(decode(bad.data(), bad.size(), out), DecodeError::kMagic);
  bad = good;
  bad[4] = 2;
  EXPECT_EQ(decode(bad.data(), bad.size(), out), DecodeError::kVersion);
  bad = good;
  bad[20] ^= 0x01;  // one bit of q flipped in transit
  EXPECT_EQ(decode(bad.data(), bad.size(), out), DecodeError::kChecksum);
  State s;
  EXPECT_EQ(decode(good.data(), good.size(), s), DecodeError::kSize);  // a command is not a state
  bad = good;
  bad[12] = 0x08;  // a flag this version does not know, with a valid CRC: refused, not ignored
  const auto crc = static_cast<std::uint32_t>(crc32(crc32(0L, Z_NULL, 0), bad.data(), 164));
  for (int i = 0; i < 4; ++i) bad[164 + i] = static_cast<std::uint8_t>(crc >> (8 * i));
  EXPECT_EQ(decode(bad.data(), bad.size(), out), DecodeError::kFlags);
  c.qdd[3] = std::nan("");
  const auto nan = encode(c);
  EXPECT_EQ(decode(nan.data(), nan.size(), out), DecodeError::kNotFinite);
}

TEST(PumaLink, SequencesCompareAcrossTheWrap) {
  EXPECT_TRUE(newer(1, 0));
  EXPECT_FALSE(newer(0, 0));
  EXPECT_FALSE(newer(0, 1));
  EXPECT_TRUE(newer(2, 0xffffffffu));
  EXPECT_FALSE(newer(0xffffffffu, 2));
}

}  // namespace wysiwyf::robot::link
