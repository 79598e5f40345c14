// RTDE (libs/robot/rtde) against the protocol as UR's RTDE Guide states it: byte layouts typed in here
// from the guide (not produced by the encoder under test), round trips of every package, recipes
// and their values, the framer on any chunking, and every malformed input refused.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "rtde/framer.hpp"
#include "rtde/packages.hpp"
#include "rtde/variables.hpp"

namespace wysiwyf::robot::rtde {
namespace {

using Bytes = std::vector<std::uint8_t>;

// The payload of the one package in `bytes`, after checking its header.
Bytes payload_of(const Bytes& bytes, PackageType type) {
  EXPECT_GE(bytes.size(), kHeaderSize);
  EXPECT_EQ((bytes[0] << 8) | bytes[1], static_cast<int>(bytes.size())) << "size field";
  EXPECT_EQ(bytes[2], static_cast<std::uint8_t>(type));
  return Bytes(bytes.begin() + kHeaderSize, bytes.end());
}

TEST(Rtde, RequestProtocolVersionIsTheGuidesFiveBytes) {
  Bytes out;
  encode_request_protocol_version(out, 2);
  EXPECT_EQ(out, (Bytes{0x00, 0x05, 'V', 0x00, 0x02}));
  const Bytes p = payload_of(out, PackageType::kRequestProtocolVersion);
  EXPECT_EQ(decode_request_protocol_version(p.data(), p.size()), 2);
  EXPECT_FALSE(decode_request_protocol_version(p.data(), 1));
}

TEST(Rtde, AcceptedRepliesAreOneByteZeroOrOne) {
  for (PackageType t : {PackageType::kRequestProtocolVersion, PackageType::kStart, PackageType::kPause}) {
    Bytes out;
    encode_accepted(out, t, true);
    EXPECT_EQ(out, (Bytes{0x00, 0x04, static_cast<std::uint8_t>(t), 0x01}));
    const Bytes p = payload_of(out, t);
    EXPECT_EQ(decode_accepted(p.data(), p.size()), true);
  }
  const Bytes two{2}, none{}, long_one{1, 0};
  EXPECT_FALSE(decode_accepted(two.data(), two.size()));
  EXPECT_FALSE(decode_accepted(none.data(), none.size()));
  EXPECT_FALSE(decode_accepted(long_one.data(), long_one.size()));
}

TEST(Rtde, ControllerVersionIsFourBigEndianUint32) {
  Bytes out;
  encode_urcontrol_version(out, {5, 11, 3, 108000});
  EXPECT_EQ(out, (Bytes{0x00, 0x13, 'v', 0, 0, 0, 5, 0, 0, 0, 11, 0, 0, 0, 3, 0x00, 0x01, 0xa5, 0xe0}));
  const Bytes p = payload_of(out, PackageType::kGetUrcontrolVersion);
  const auto v = decode_urcontrol_version(p.data(), p.size());
  ASSERT_TRUE(v);
  EXPECT_EQ(v->major, 5u);
  EXPECT_EQ(v->build, 108000u);
  EXPECT_FALSE(decode_urcontrol_version(p.data(), 15));
}

TEST(Rtde, SetupOutputsIsAFrequencyAndCommaSeparatedNames) {
  Bytes out;
  encode_setup_outputs(out, {500.0, {"timestamp", "actual_q"}});
  // 500.0 as IEEE 754 binary64, big-endian: 0x407F400000000000.
  const Bytes expected_start{0x00, 0x1d, 'O', 0x40, 0x7f, 0x40, 0, 0, 0, 0, 0};
  ASSERT_EQ(out.size(), 3u + 8u + 18u);
  EXPECT_TRUE(std::equal(expected_start.begin(), expected_start.end(), out.begin()));
  EXPECT_EQ(std::string(out.begin() + 11, out.end()), "timestamp,actual_q");
  const Bytes p = payload_of(out, PackageType::kSetupOutputs);
  const auto r = decode_setup_outputs(p.data(), p.size());
  ASSERT_TRUE(r);
  EXPECT_EQ(r->frequency, 500.0);
  EXPECT_EQ(r->names, (std::vector<std::string>{"timestamp", "actual_q"}));
}

TEST(Rtde, SetupRequestsWithBadFrequenciesOrNamesAreRefused) {
  for (double f : {0.0, -1.0, 501.0, std::nan(""), static_cast<double>(INFINITY)}) {
    Bytes out;
    encode_setup_outputs(out, {f, {"actual_q"}});
    const Bytes p = payload_of(out, PackageType::kSetupOutputs);
    EXPECT_FALSE(decode_setup_outputs(p.data(), p.size())) << f;
  }
  for (const char* list : {"", "a,,b", "a,", ",a", "actual q", "a;b", "actual_q,actual_q", "\xff"}) {
    EXPECT_FALSE(split_names(list)) << list;
  }
  std::string many;
  for (int i = 0; i <= static_cast<int>(kMaxRecipeFields); ++i) many += (i ? ",n" : "n") + std::to_string(i);
  EXPECT_FALSE(split_names(many));
  EXPECT_FALSE(split_names(std::string(kMaxVariableName + 1, 'a')));
  EXPECT_TRUE(split_names(std::string(kMaxVariableName, 'a')));
}

TEST(Rtde, SetupRepliesCarryTheRecipeIdAndTypes) {
  Bytes out;
  encode_setup_reply(out, PackageType::kSetupInputs, {3, {"DOUBLE", "IN_USE", "NOT_FOUND"}});
  EXPECT_EQ(out[3], 3);
  const Bytes p = payload_of(out, PackageType::kSetupInputs);
  const auto r = decode_setup_reply(p.data(), p.size());
  ASSERT_TRUE(r);
  EXPECT_EQ(r->recipe_id, 3);
  EXPECT_EQ(r->types, (std::vector<std::string>{"DOUBLE", "IN_USE", "NOT_FOUND"}));
  EXPECT_EQ(field_type(r->types[0]), FieldType::kDouble);
  EXPECT_FALSE(field_type(r->types[1]));
  const Bytes empty{};
  EXPECT_FALSE(decode_setup_reply(empty.data(), empty.size()));
}

TEST(Rtde, TextMessagesAreLengthPrefixedWithALevel) {
  Bytes out;
  encode_text_message(out, {"protective stop", "safety", MessageLevel::kError});
  const Bytes p = payload_of(out, PackageType::kTextMessage);
  EXPECT_EQ(p[0], 15);
  const auto m = decode_text_message(p.data(), p.size());
  ASSERT_TRUE(m);
  EXPECT_EQ(m->message, "protective stop");
  EXPECT_EQ(m->source, "safety");
  EXPECT_EQ(m->level, MessageLevel::kError);
  Bytes bad_level = p;
  bad_level.back() = 4;
  EXPECT_FALSE(decode_text_message(bad_level.data(), bad_level.size()));
  const Bytes overlong{200, 'a'};
  EXPECT_FALSE(decode_text_message(overlong.data(), overlong.size()));
}

TEST(Rtde, DataPackagesCarryEveryTypeBigEndianInRecipeOrder) {
  const Recipe recipe(7, {"b", "u8", "u32", "u64", "i32", "d", "v3", "v6", "v6i", "v6u"},
                      {FieldType::kBool, FieldType::kUint8, FieldType::kUint32, FieldType::kUint64, FieldType::kInt32,
                       FieldType::kDouble, FieldType::kVector3d, FieldType::kVector6d, FieldType::kVector6Int32,
                       FieldType::kVector6Uint32});
  EXPECT_EQ(recipe.values_size(), 1u + 1 + 4 + 8 + 4 + 8 + 24 + 48 + 24 + 24);
  RecipeValues values(recipe);
  values.set_bool(0, true);
  values.set_uint8(1, 200);
  values.set_uint32(2, 0xdeadbeef);
  values.set_uint64(3, 0x0123456789abcdefULL);
  values.set_int32(4, -2);
  values.set_double(5, -1.5);
  values.set_vector3d(6, {1, 2, 3});
  values.set_vector6d(7, {0.1, -0.2, 0.3, -0.4, 0.5, -0.6});
  values.set_vector6int32(8, {-1, 2, -3, 4, -5, 6});
  values.set_vector6uint32(9, {1, 2, 3, 4, 5, 0xffffffffu});
  Bytes out;
  encode_data_package(out, values);
  const Bytes p = payload_of(out, PackageType::kDataPackage);
  EXPECT_EQ(p[0], 7);                                                                       // recipe id
  EXPECT_EQ(Bytes(p.begin() + 3, p.begin() + 7), (Bytes{0xde, 0xad, 0xbe, 0xef}));          // u32
  EXPECT_EQ(Bytes(p.begin() + 15, p.begin() + 19), (Bytes{0xff, 0xff, 0xff, 0xfe}));        // i32 -2
  EXPECT_EQ(Bytes(p.begin() + 19, p.begin() + 27), (Bytes{0xbf, 0xf8, 0, 0, 0, 0, 0, 0}));  // -1.5
  RecipeValues back(recipe);
  ASSERT_TRUE(back.read(p.data(), p.size()));
  EXPECT_TRUE(back.get_bool(0));
  EXPECT_EQ(back.get_uint8(1), 200);
  EXPECT_EQ(back.get_uint32(2), 0xdeadbeefu);
  EXPECT_EQ(back.get_uint64(3), 0x0123456789abcdefULL);
  EXPECT_EQ(back.get_int32(4), -2);
  EXPECT_EQ(back.get_double(5), -1.5);
  EXPECT_EQ(back.get_vector3d(6), (std::array<double, 3>{1, 2, 3}));
  EXPECT_EQ(back.get_vector6d(7), (std::array<double, 6>{0.1, -0.2, 0.3, -0.4, 0.5, -0.6}));
  EXPECT_EQ(back.get_vector6int32(8), (std::array<std::int32_t, 6>{-1, 2, -3, 4, -5, 6}));
  EXPECT_EQ(back.get_vector6uint32(9)[5], 0xffffffffu);
  EXPECT_THROW(back.get_double(0), std::invalid_argument);  // a programming error, not input
  EXPECT_THROW(back.get_bool(10), std::invalid_argument);
}

TEST(Rtde, ADataPackageOfAnotherRecipeOrSizeOrABadBoolIsRefusedAndChangesNothing) {
  const Recipe recipe(2, {"flag", "x"}, {FieldType::kBool, FieldType::kDouble});
  RecipeValues values(recipe);
  values.set_double(1, 4.0);
  const Bytes other_id{3, 1, 0, 0, 0, 0, 0, 0, 0, 0}, short_one{2, 1, 0}, bad_bool{2, 2, 0, 0, 0, 0, 0, 0, 0, 0};
  Bytes good{2, 1, 0x40, 0x14, 0, 0, 0, 0, 0, 0};  // true, 5.0
  EXPECT_FALSE(values.read(other_id.data(), other_id.size()));
  EXPECT_FALSE(values.read(short_one.data(), short_one.size()));
  EXPECT_FALSE(values.read(bad_bool.data(), bad_bool.size()));
  EXPECT_EQ(values.get_double(1), 4.0);
  EXPECT_TRUE(values.read(good.data(), good.size()));
  EXPECT_EQ(values.get_double(1), 5.0);
  EXPECT_THROW(Recipe(1, {"a", "a"}, {FieldType::kBool, FieldType::kBool}), std::invalid_argument);
  EXPECT_THROW(Recipe(1, {"a"}, {}), std::invalid_argument);
}

TEST(Rtde, TheFramerCutsAnyChunkingIntoTheSamePackages) {
  Bytes stream;
  encode_request_protocol_version(stream, 2);
  encode_text_message(stream, {"hello", "test", MessageLevel::kInfo});
  encode_setup_inputs(stream, {"input_double_register_24", "input_int_register_24"});
  encode_start(stream);
  std::mt19937 rng(3);
  for (int trial = 0; trial < 200; ++trial) {
    PackageFramer framer;
    std::vector<std::uint8_t> types;
    for (std::size_t at = 0; at < stream.size();) {
      const std::size_t n = std::min<std::size_t>(stream.size() - at, 1 + rng() % 9);
      framer.feed(stream.data() + at, n);
      at += n;
      while (const auto pkg = framer.next()) types.push_back(pkg->type);
    }
    EXPECT_EQ(types, (std::vector<std::uint8_t>{'V', 'M', 'I', 'S'}));
    EXPECT_EQ(framer.pending(), 0u);
    EXPECT_FALSE(framer.failed());
  }
}

TEST(Rtde, AHeaderWithAnImpossibleSizeBreaksTheStreamAndSaysWhy) {
  for (const Bytes& bad : {Bytes{0x00, 0x02, 'U'}, Bytes{0x00, 0x00, 'U'}, Bytes{0xff, 0xff, 'U'}}) {
    PackageFramer framer;
    framer.feed(bad.data(), bad.size());
    EXPECT_FALSE(framer.next());
    EXPECT_TRUE(framer.failed());
    EXPECT_NE(framer.error().find("expected 3 to 4096"), std::string::npos) << framer.error();
    framer.feed(bad.data(), bad.size());  // nothing more is taken
    EXPECT_FALSE(framer.next());
    framer.reset();
    EXPECT_FALSE(framer.failed());
  }
  PackageFramer framer;  // an unknown type is whole: handed on for the caller to refuse
  const Bytes unknown{0x00, 0x04, 'Z', 0};
  framer.feed(unknown.data(), unknown.size());
  const auto pkg = framer.next();
  ASSERT_TRUE(pkg);
  EXPECT_FALSE(package_type(pkg->type));
}

TEST(Rtde, TheControllersVariablesHaveTheGuidesTypes) {
  EXPECT_EQ(output_type("actual_q"), FieldType::kVector6d);
  EXPECT_EQ(output_type("actual_TCP_force"), FieldType::kVector6d);
  EXPECT_EQ(output_type("robot_mode"), FieldType::kInt32);
  EXPECT_EQ(output_type("safety_mode"), FieldType::kInt32);
  EXPECT_EQ(output_type("runtime_state"), FieldType::kUint32);
  EXPECT_EQ(output_type("output_int_register_47"), FieldType::kInt32);
  EXPECT_EQ(output_type("input_double_register_24"), FieldType::kDouble);
  EXPECT_EQ(input_type("input_double_register_24"), FieldType::kDouble);
  EXPECT_EQ(input_type("input_bit_register_64"), FieldType::kBool);
  EXPECT_FALSE(input_type("input_bit_register_63"));
  EXPECT_FALSE(input_type("input_int_register_48"));
  EXPECT_FALSE(input_type("input_int_register_024"));
  EXPECT_FALSE(input_type("actual_q"));  // the robot's state cannot be written
  EXPECT_FALSE(output_type("actual_qq"));
}

}  // namespace
}  // namespace wysiwyf::robot::rtde
