// The two ends of an RTDE connection (ClientSession, the driver's; ServerSession, the
// controller's) joined in memory through framers: the handshake, the stream both ways, and every
// refusal: a variable the controller lacks, one another connection writes, a refused version or
// start, packages out of turn, malformed or of unknown type.
#include <gtest/gtest.h>

#include "rtde/client_session.hpp"
#include "rtde/server_session.hpp"

namespace wysiwyf::robot::rtde {
namespace {

using Bytes = std::vector<std::uint8_t>;

const std::vector<Variable> kOutputs = {{"timestamp", FieldType::kDouble},
                                        {"actual_q", FieldType::kVector6d},
                                        {"robot_mode", FieldType::kInt32},
                                        {"safety_mode", FieldType::kInt32}};
const std::vector<Variable> kInputs = {{"input_double_register_24", FieldType::kDouble},
                                       {"input_int_register_24", FieldType::kInt32}};

// A client and a server session joined by two byte streams.
struct Link {
  ClientSession client;
  ServerSession server;
  PackageFramer to_server, to_client;
  Bytes up, down;  // bytes in flight

  Link(InputOwners& owners, std::vector<Variable> outputs = kOutputs, std::vector<Variable> inputs = kInputs)
      : client(500, std::move(outputs), std::move(inputs)), server({5, 11, 3, 0}, owners) {}

  // Delivers every byte in flight, both ways, until none is left; returns the output data
  // packages the client took.
  int pump() {
    int data = 0;
    while (!up.empty() || !down.empty()) {
      to_server.feed(up.data(), up.size());
      up.clear();
      while (const auto pkg = to_server.next()) server.handle(*pkg, down);
      to_client.feed(down.data(), down.size());
      down.clear();
      while (const auto pkg = to_client.next()) data += client.handle(*pkg, up) ? 1 : 0;
    }
    return data;
  }
  void connect() {
    client.begin(up);
    pump();
  }
};

TEST(RtdeSessions, TheHandshakeEndsStreamingAndCarriesDataBothWays) {
  InputOwners owners;
  Link link(owners);
  link.connect();
  ASSERT_TRUE(link.client.streaming()) << link.client.error();
  EXPECT_TRUE(link.server.streaming());
  EXPECT_EQ(link.client.controller_version().major, 5u);
  EXPECT_EQ(link.server.output_frequency(), 500);
  ASSERT_NE(link.server.output_recipe(), nullptr);
  EXPECT_EQ(link.server.output_recipe()->size(), 4u);

  RecipeValues& out = *link.server.outputs();
  out.set_double(0, 12.5);
  out.set_vector6d(1, {0.1, -1.5, 1.2, -0.4, 1.57, 0});
  out.set_int32(2, static_cast<std::int32_t>(RobotMode::kRunning));
  out.set_int32(3, static_cast<std::int32_t>(SafetyMode::kNormal));
  link.server.encode_outputs(link.down);
  EXPECT_EQ(link.pump(), 1);
  EXPECT_EQ(link.client.outputs().get_double(link.client.output_index("timestamp")), 12.5);
  EXPECT_EQ(link.client.outputs().get_vector6d(1)[1], -1.5);
  EXPECT_EQ(link.client.outputs().get_int32(2), 7);

  link.client.inputs().set_double(link.client.input_index("input_double_register_24"), 0.25);
  link.client.inputs().set_int32(1, 42);
  link.client.encode_inputs(link.up);
  link.pump();
  EXPECT_EQ(link.server.input_packages(), 1u);
  const RecipeValues* in = link.server.inputs(link.client.inputs().recipe().id());
  ASSERT_NE(in, nullptr);
  EXPECT_EQ(in->get_double(0), 0.25);
  EXPECT_EQ(in->get_int32(1), 42);
  EXPECT_EQ(link.client.refused() + link.server.refused(), 0u);
}

TEST(RtdeSessions, AVariableTheControllerLacksFailsTheHandshakeByName) {
  InputOwners owners;
  Link link(owners, {{"actual_q", FieldType::kVector6d}, {"actual_joint_torques", FieldType::kVector6d}});
  link.connect();
  EXPECT_TRUE(link.client.failed());
  EXPECT_NE(link.client.error().find("'actual_joint_torques': the controller says NOT_FOUND"), std::string::npos)
      << link.client.error();
  EXPECT_FALSE(link.server.streaming());
}

TEST(RtdeSessions, AnAskedTypeTheControllerDoesNotHaveFailsTheHandshake) {
  InputOwners owners;
  Link link(owners, {{"robot_mode", FieldType::kDouble}});
  link.connect();
  EXPECT_TRUE(link.client.failed());
  EXPECT_NE(link.client.error().find("says INT32, expected DOUBLE"), std::string::npos) << link.client.error();
}

TEST(RtdeSessions, InputsAnotherConnectionWritesAreInUseUntilItCloses) {
  InputOwners owners;
  auto first = std::make_unique<Link>(owners);
  first->connect();
  ASSERT_TRUE(first->client.streaming());
  Link second(owners);
  second.connect();
  EXPECT_TRUE(second.client.failed());
  EXPECT_NE(second.client.error().find("IN_USE"), std::string::npos) << second.client.error();
  first.reset();  // the first connection closes: its registers are free
  Link third(owners);
  third.connect();
  EXPECT_TRUE(third.client.streaming()) << third.client.error();
}

TEST(RtdeSessions, ARefusedProtocolVersionFailsTheHandshake) {
  InputOwners owners;
  Link link(owners);
  encode_request_protocol_version(link.up, 1);  // the server answers 0 to anything but 2
  link.to_server.feed(link.up.data(), link.up.size());
  link.up.clear();
  link.server.handle(*link.to_server.next(), link.down);
  link.client.begin(link.up);  // the client now asks for 2, but reads the refusal first
  link.up.clear();
  link.pump();
  EXPECT_TRUE(link.client.failed());
  EXPECT_NE(link.client.error().find("refused RTDE protocol version 2"), std::string::npos);
}

TEST(RtdeSessions, TheServerRefusesAndCountsWhatItCannotTakeAndStaysUp) {
  InputOwners owners;
  Link link(owners);
  link.connect();
  ASSERT_TRUE(link.server.streaming());
  const std::vector<Bytes> bad = {
      {0x00, 0x04, 'Z', 0},                                   // unknown type
      {0x00, 0x05, 'U', 99, 0},                               // data of no input recipe
      {0x00, 0x04, 'U', link.client.inputs().recipe().id()},  // data of a recipe, too short
      {0x00, 0x03, 'U'},                                      // data without a recipe id
      {0x00, 0x04, 'S', 1},                                   // start with a payload
      {0x00, 0x05, 'I', 'a', ','},                            // setup (malformed, and while streaming)
  };
  for (const Bytes& b : bad) link.up.insert(link.up.end(), b.begin(), b.end());
  link.pump();
  EXPECT_EQ(link.server.refused(), bad.size());
  EXPECT_EQ(link.client.messages(), bad.size());  // each refusal told as an error text message
  EXPECT_EQ(link.client.last_message().level, MessageLevel::kError);
  EXPECT_NE(link.server.last_refusal().find("while streaming"), std::string::npos) << link.server.last_refusal();
  EXPECT_TRUE(link.server.streaming());
  // Paused, the same connection may set up again.
  encode_pause(link.up);
  link.pump();
  EXPECT_FALSE(link.server.streaming());
  encode_setup_inputs(link.up, {"input_double_register_30"});
  link.pump();
  EXPECT_EQ(link.server.refused(), bad.size());
}

TEST(RtdeSessions, TheClientRefusesAndCountsPackagesOutOfTurnOrMalformed) {
  InputOwners owners;
  Link link(owners);
  link.connect();
  ASSERT_TRUE(link.client.streaming());
  const std::vector<Bytes> bad = {
      {0x00, 0x04, 'V', 1},     // a version reply while streaming
      {0x00, 0x05, 'U', 1, 0},  // a data package of the wrong size
      {0x00, 0x04, 'M', 9},     // a malformed text message
      {0x00, 0x03, 'q'},        // unknown type
  };
  for (const Bytes& b : bad) link.down.insert(link.down.end(), b.begin(), b.end());
  EXPECT_EQ(link.pump(), 0);
  EXPECT_EQ(link.client.refused(), bad.size());
  EXPECT_TRUE(link.client.streaming());
  link.server.encode_outputs(link.down);
  EXPECT_EQ(link.pump(), 1);
  EXPECT_EQ(link.client.data_packages(), 1u);
}

}  // namespace
}  // namespace wysiwyf::robot::rtde
