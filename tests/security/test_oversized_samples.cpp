// Samples over a topic's bound from a participant outside the pipeline: an intruder writes 8 MB
// JointStates (a type bounded to a few hundred bytes) on the topic a robot-side process reads
// with a deadline, over UDP as from another host. The reader refuses each as it comes (Fast DDS:
// the history of a bounded type holds no larger sample; CheckedTypeSupport refuses any that got
// past it), says so once and then counts, none reaches the component, and its stream from the
// pipeline's own writer never stalls for its deadline (20 ms, five periods). (Real clock:
// deadlines are in wall time. Waits are hang guards.)
#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <fstream>
#include <sstream>
#include <thread>

#include "../kernel/cli_process.hpp"
#include "../kernel/test_support.hpp"
#include "intruder_participant.hpp"
#include "wysiwyf/msgs.hpp"

#include <fastcdr/Cdr.h>
#include <fastcdr/FastBuffer.h>

namespace wysiwyf::test {
namespace {

namespace fs = std::filesystem;

constexpr int kDomain = 96;
constexpr std::uint32_t kIntruderSeq = 777000;

TEST(OversizedSamples, EightMegabyteSamplesFromOutsideAreDroppedAndTheRobotsStreamKeepsItsDeadline) {
  const fs::path dir = scratch_dir();
  const fs::path pipeline = dir / "robot.yaml";
  // The display's stream to the robot's process at 250 Hz with a 20 ms deadline (5 periods).
  std::ofstream(pipeline) << "wysiwyf: 1\nname: oversized\ndomain: " << kDomain
                          << "\ndds: {transport: loopback}\ninsecure: true\nclock: {mode: real, duration: 14s}\n"
                             "components:\n"
                             "  src: {type: test_probe, rate: 250, process: display, topics: {out: crossing},\n"
                             "        qos: {out: {deadline: 20ms}}}\n"
                             "  sink: {type: test_probe, rate: 250, process: robot, topics: {in: crossing},\n"
                             "         params: {record: "
                          << (dir / "received.txt").string() << "}, qos: {in: {deadline: 20ms}}}\n";
  const pid_t robot = spawn_cli({"run", pipeline.string(), "--process", "robot", "--no-progress"}, dir / "robot.log");
  const pid_t display =
      spawn_cli({"run", pipeline.string(), "--process", "display", "--no-progress"}, dir / "display.log");
  {
    Participant intruder(kDomain, std::nullopt);
    ASSERT_TRUE(intruder.ok());
    // A JointState of a million positions as CDR (8 MB; the type's bound is 8 joints), sent as
    // bytes: a participant whose type has no bound (another vendor's, or its own) may send it.
    msg::JointState big;
    big.header().frame_id("base");
    big.position().assign(1'000'000, 12345.0);
    auto* writer = intruder.raw_writer("crossing", "wysiwyf::msg::JointState", 20'000'000);
    ASSERT_NE(writer, nullptr);
    const auto cdr_of = [&big] {
      std::vector<std::uint8_t> bytes(9'000'000);
      eprosima::fastcdr::FastBuffer buffer(reinterpret_cast<char*>(bytes.data()), bytes.size());
      eprosima::fastcdr::Cdr cdr(buffer, eprosima::fastcdr::Cdr::DEFAULT_ENDIAN, eprosima::fastcdr::Cdr::DDS_CDR);
      cdr.serialize_encapsulation();
      big.serialize(cdr);
      bytes.resize(cdr.getSerializedDataLength());
      return bytes;
    };
    eprosima::fastdds::dds::PublicationMatchedStatus matched;
    for (int i = 0; i < 160 && matched.current_count < 1; ++i) {  // discovery (a hang guard)
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
      writer->get_publication_matched_status(matched);
    }
    ASSERT_EQ(matched.current_count, 1) << "the robot's reader matched the intruder's writer";
    std::this_thread::sleep_for(std::chrono::milliseconds(500));  // the display's stream under way
    int written = 0;
    for (std::uint32_t i = 0; i < 20; ++i) {  // 160 MB over 4 s
      big.header().seq(kIntruderSeq + i);
      cli::RawCdr sample{cdr_of()};
      written += writer->write(&sample);
      std::this_thread::sleep_for(std::chrono::milliseconds(200));
    }
    EXPECT_EQ(written, 20);
  }
  EXPECT_EQ(wait_exit(display, std::chrono::seconds(60)), 0) << read_file(dir / "display.log");
  EXPECT_EQ(wait_exit(robot, std::chrono::seconds(60)), 0) << read_file(dir / "robot.log");
  // The robot's reader refused them as they came (Fast DDS: a bounded type's history holds no
  // larger sample), said once and then counted, not once a sample.
  const std::string log = read_file(dir / "robot.log");
  std::istringstream log_lines(log);
  int said = 0;
  for (std::string line; std::getline(log_lines, line);)
    said += line.find("larger than the history") != std::string::npos;
  EXPECT_GE(said, 1) << "the intruder's samples reached the reader: " << log;
  EXPECT_LE(said, 2) << "said at the 1st and the 10th, not for each of 20: " << log;

  // Every sample the robot's component took is the display's, and none was long in coming.
  std::istringstream lines(read_file(dir / "received.txt"));
  long long last_ns = 0, longest_gap_ns = 0;
  int samples = 0, intruders = 0;
  for (std::string line; std::getline(lines, line);) {
    std::istringstream f(line);
    long long now = 0;
    unsigned long long seq = 0;
    f >> now >> seq;
    intruders += seq >= kIntruderSeq && seq < kIntruderSeq + 20;
    if (last_ns > 0) longest_gap_ns = std::max(longest_gap_ns, now - last_ns);
    last_ns = now;
    ++samples;
  }
  std::printf("[measured] %d samples taken, longest gap between two %.1f ms, %d from the intruder\n", samples,
              static_cast<double>(longest_gap_ns) * 1e-6, intruders);
  EXPECT_GT(samples, 1000);
  EXPECT_EQ(intruders, 0);
  // (Not the deadline's own report: it may fire once as the display's process starts writing.)
  EXPECT_LT(longest_gap_ns, 20'000'000) << "the robot's stream stalled while the intruder wrote";
}

}  // namespace
}  // namespace wysiwyf::test
