// round_trip_text: the shortest text of at least 6 significant digits that reads back as the
// same double, as printf's %g writes it (what the tools print in YAML).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <iomanip>
#include <limits>
#include <random>
#include <sstream>

#include "wysiwyf/number_text.hpp"

namespace wysiwyf::test {

namespace {

// The definition itself, slowly: %g at 6, 7, ... 17 digits until strtod gives v back.
std::string by_definition(double v) {
  for (int p = 6; p <= 17; ++p) {
    std::ostringstream t;
    t << std::setprecision(p) << v;
    if (std::strtod(t.str().c_str(), nullptr) == v) return t.str();
  }
  std::ostringstream s;
  s << std::setprecision(std::numeric_limits<double>::max_digits10) << v;
  return s.str();
}

}  // namespace

TEST(RoundTripText, WritesTheShortestTextOfAtLeastSixDigitsThatReadsBack) {
  EXPECT_EQ(round_trip_text(0.1), "0.1");
  EXPECT_EQ(round_trip_text(100000), "100000");
  EXPECT_EQ(round_trip_text(1e6), "1e+06");
  EXPECT_EQ(round_trip_text(1e-7), "1e-07");
  EXPECT_EQ(round_trip_text(1234567), "1234567");
  EXPECT_EQ(round_trip_text(0.1 + 0.2), "0.30000000000000004");
  EXPECT_EQ(round_trip_text(-0.0), "-0");
  EXPECT_EQ(round_trip_text(std::numeric_limits<double>::denorm_min()), "4.94066e-324");
  EXPECT_EQ(round_trip_text(std::numeric_limits<double>::max()), "1.7976931348623157e+308");
  EXPECT_EQ(round_trip_text(std::numeric_limits<double>::infinity()), "inf");
  EXPECT_EQ(round_trip_text(-std::numeric_limits<double>::infinity()), "-inf");
  EXPECT_EQ(round_trip_text(std::nan("")), "nan");
}

TEST(RoundTripText, AgreesWithItsDefinitionOnAnyDouble) {
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> sensor(-10.0, 10.0);
  for (int i = 0; i < 100000; ++i) {
    const std::uint64_t bits = random();
    double any;
    std::memcpy(&any, &bits, sizeof any);  // every exponent, denormals and NaNs among them
    if (!std::isnan(any)) ASSERT_EQ(round_trip_text(any), by_definition(any)) << std::hexfloat << any;
    const double measured = sensor(random);  // what samples hold
    ASSERT_EQ(round_trip_text(measured), by_definition(measured)) << std::hexfloat << measured;
    const float single = static_cast<float>(measured);  // float fields are printed through double
    ASSERT_EQ(round_trip_text(single), by_definition(single)) << std::hexfloat << single;
  }
}

}  // namespace wysiwyf::test
