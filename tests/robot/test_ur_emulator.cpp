// The UR e-Series emulator: the controller's behaviour (the follow program's, the watchdog, the
// safety system's protective stop and its unlock) without sockets, then the whole emulator on
// loopback in lockstep as a driver meets it: RTDE handshake, the program through the script
// port, one output package per input package, the dashboard's answers.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <thread>

#include "rtde/client_session.hpp"
#include "rtde/tcp.hpp"
#include "ur_controller_emulator/ur_emulator.hpp"

namespace wysiwyf::robot::ur {
namespace {

using rtde::follow::ProgramState;
namespace follow = rtde::follow;

std::string follow_script() {
  std::ifstream in(std::string(WYSIWYF_CONFIG_DIR) + "/robots/ur_follow.script");
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// The input registers of one period: the counter, the mode, and a reference.
struct Inputs {
  rtde::Recipe recipe;
  rtde::RecipeValues values;
  Inputs() : recipe(make()), values(recipe) {}
  static rtde::Recipe make() {
    std::vector<std::string> names;
    std::vector<rtde::FieldType> types;
    for (const auto& v : follow::input_recipe()) names.push_back(v.name), types.push_back(v.type);
    return rtde::Recipe(1, names, types);
  }
  void set(std::int32_t counter, int mode, const JointVector& q) {
    values.set_int32(follow::kCounterIndex, counter);
    values.set_int32(follow::kModeIndex, mode);
    for (std::size_t j = 0; j < 6; ++j) {
      values.set_double(follow::kQIndex + j, q[static_cast<Eigen::Index>(j)]);
      values.set_double(follow::kQdIndex + j, 0.0);
      values.set_double(follow::kQddIndex + j, 0.0);
    }
  }
};

TEST(UrController, RunsOnlyTheFollowProgramAndFollowsItsRegisters) {
  UrController c({});
  std::string why;
  EXPECT_FALSE(c.load_program("def other():\n  movej([0,0,0,0,0,0])\nend\n", why));
  EXPECT_NE(why.find("only the follow program"), std::string::npos) << why;
  ASSERT_TRUE(c.load_program(follow_script(), why)) << why;
  EXPECT_EQ(c.program_state(), ProgramState::kHolding);
  const JointVector q0 = c.true_q();
  JointVector target = q0;
  target[0] += 0.002;  // within one period at the velocity limit
  Inputs in;
  for (int k = 1; k <= 500; ++k) {
    in.set(k, follow::kFollow, target);
    c.take_inputs(in.values);
    c.step();
  }
  EXPECT_EQ(c.program_state(), ProgramState::kFollowing);
  EXPECT_NEAR(c.true_q()[0], target[0], 2e-4);
  EXPECT_EQ(c.safety_mode(), rtde::SafetyMode::kNormal);
}

TEST(UrController, AStoppedCounterStopsTheProgramAfterItsWatchdogPeriods) {
  UrController c({});
  std::string why;
  ASSERT_TRUE(c.load_program(follow_script(), why));
  Inputs in;
  in.set(7, follow::kFollow, c.true_q());
  c.take_inputs(in.values);
  for (int k = 0; k <= follow::kWatchdogPeriods; ++k) {
    c.step();
    EXPECT_TRUE(c.program_running()) << "period " << k;
  }
  c.step();
  EXPECT_FALSE(c.program_running());
  EXPECT_EQ(c.program_state(), ProgramState::kStoppedHostLost);
}

TEST(UrController, AJumpingTargetIsAProtectiveStopThatOnlyAnUnlockClears) {
  UrController c({});
  std::string why;
  ASSERT_TRUE(c.load_program(follow_script(), why));
  JointVector target = c.true_q();
  target[2] += 0.3;  // far beyond one period at the velocity limit
  Inputs in;
  in.set(1, follow::kFollow, target);
  c.take_inputs(in.values);
  const JointVector before = c.true_q();
  c.step();
  EXPECT_EQ(c.safety_mode(), rtde::SafetyMode::kProtectiveStop);
  EXPECT_FALSE(c.program_running());
  EXPECT_NE(c.stop_reason().find("joint 3 speed limit violation"), std::string::npos) << c.stop_reason();
  for (int k = 0; k < 200; ++k) c.step();
  EXPECT_LT((c.true_q() - before).cwiseAbs().maxCoeff(), 1e-3);  // held where it was
  EXPECT_FALSE(c.load_program(follow_script(), why));            // nothing starts in a stop
  EXPECT_TRUE(c.unlock_protective_stop());
  EXPECT_FALSE(c.unlock_protective_stop());
  EXPECT_TRUE(c.load_program(follow_script(), why)) << why;
}

// Sends `text` to a line-based port and returns its reply line.
std::string ask(rtde::TcpStream& s, const std::string& line) {
  s.send(std::vector<std::uint8_t>(line.begin(), line.end()));
  std::vector<std::uint8_t> in;
  for (int i = 0; i < 100 && std::find(in.begin(), in.end(), '\n') == in.end(); ++i) {
    s.wait_readable(0.05);
    s.receive(in);
  }
  return std::string(in.begin(), in.end());
}

TEST(UrEmulator, InLockstepEveryInputPackageIsOnePeriodAndOneOutputPackage) {
  UrEmulator::Options options;
  options.lockstep = true;
  UrEmulator emulator(options);
  rtde::TcpStream dashboard = rtde::TcpStream::connect("127.0.0.1", emulator.dashboard_port(), 1.0);
  EXPECT_NE(ask(dashboard, "").find("Connected: Universal Robots Dashboard Server"), std::string::npos);

  rtde::TcpStream rtde_stream = rtde::TcpStream::connect("127.0.0.1", emulator.rtde_port(), 1.0);
  rtde::ClientSession client(500, follow::output_recipe(), follow::input_recipe());
  rtde::PackageFramer framer;
  std::vector<std::uint8_t> out;
  client.begin(out);
  int outputs = 0;
  const auto exchange = [&] {
    ASSERT_TRUE(rtde_stream.send(out));
    out.clear();
    rtde_stream.wait_readable(0.2);
    std::vector<std::uint8_t> in;
    rtde_stream.receive(in);
    framer.feed(in.data(), in.size());
    while (const auto pkg = framer.next()) outputs += client.handle(*pkg, out) ? 1 : 0;
  };
  for (int i = 0; i < 50 && !client.streaming() && !client.failed(); ++i) exchange();
  ASSERT_TRUE(client.streaming()) << client.error();
  EXPECT_EQ(outputs, 1) << "the start is answered with the state the stream starts from";
  EXPECT_EQ(emulator.counters().periods, 0u);

  rtde::TcpStream script = rtde::TcpStream::connect("127.0.0.1", emulator.script_port(), 1.0);
  const std::string text = follow_script();
  script.send(std::vector<std::uint8_t>(text.begin(), text.end()));
  for (int i = 0; i < 100 && emulator.counters().scripts_run == 0; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  ASSERT_EQ(emulator.counters().scripts_run, 1u);

  const JointVector q0 = emulator.true_q();
  for (int k = 1; k <= 20; ++k) {
    auto& in = client.inputs();
    in.set_int32(follow::kCounterIndex, k);
    in.set_int32(follow::kModeIndex, follow::kFollow);
    for (std::size_t j = 0; j < 6; ++j)
      in.set_double(follow::kQIndex + j, q0[static_cast<Eigen::Index>(j)] + 0.0005 * k);
    client.encode_inputs(out);
    const int before = outputs;
    for (int i = 0; i < 50 && outputs == before; ++i) exchange();
    ASSERT_EQ(outputs, before + 1) << "input " << k;
  }
  EXPECT_EQ(emulator.counters().periods, 20u);
  const auto& o = client.outputs();
  EXPECT_EQ(o.get_int32(client.output_index(follow::kProgramState)), static_cast<int>(ProgramState::kFollowing));
  EXPECT_NEAR(o.get_double(client.output_index("timestamp")), 20 * 0.002, 1e-12);
  EXPECT_GT(o.get_vector6d(client.output_index("actual_q"))[0], q0[0]);

  emulator.protective_stop("test");
  EXPECT_EQ(ask(dashboard, "safetystatus\n"), "Safetystatus: PROTECTIVE_STOP\n");
  EXPECT_EQ(ask(dashboard, "unlock protective stop\n"), "Protective stop releasing\n");
  EXPECT_EQ(ask(dashboard, "rm -rf /\n"), "could not understand: 'rm -rf /'\n");
  EXPECT_EQ(emulator.counters().packages_refused, 0u);
}

}  // namespace
}  // namespace wysiwyf::robot::ur
