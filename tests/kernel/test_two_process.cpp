// Two process groups of one pipeline, run as two `wysiwyf run --process` processes, exchange data
// over DDS (shared memory / loopback only); `wysiwyf topic` tools see the running pipeline.
#include <signal.h>

#include <chrono>
#include <sstream>
#include <thread>

#include "cli_process.hpp"
#include "test_support.hpp"

namespace wysiwyf::test {

namespace fs = std::filesystem;

TEST(TwoProcesses, ProcessGroupsExchangeDataOverDds) {
  const fs::path dir = scratch_dir();
  const fs::path pipeline = dir / "split.yaml";
  std::ofstream(pipeline) << "wysiwyf: 1\nname: split\ndomain: 50\ndds: {transport: local}\n"
                             "clock: {mode: sim, step: 1ms, duration: 60s, pace: 1}\n"
                             "components:\n"
                             "  src: {type: test_probe, rate: 100, process: producer, topics: {out: crossing}}\n"
                             "  sink: {type: test_probe, rate: 100, process: consumer, topics: {in: crossing},\n"
                             "         params: {stop_after_received: 20, record: "
                          << (dir / "received.txt").string() << "}}\n";
  const pid_t producer =
      spawn_cli({"run", pipeline.string(), "--process", "producer", "--no-progress"}, dir / "producer.log");
  const pid_t consumer =
      spawn_cli({"run", pipeline.string(), "--process", "consumer", "--no-progress"}, dir / "consumer.log");

  EXPECT_EQ(wait_exit(consumer, std::chrono::seconds(60)), 0) << read_file(dir / "consumer.log");
  EXPECT_NE(read_file(dir / "consumer.log").find("stopped: stopped by sink: received 20"), std::string::npos)
      << read_file(dir / "consumer.log");

  // The command line tools see the running producer.
  const std::string topics = list_topics_until(
      50, dir / "list.log", [](const std::string& l) { return l.find("wysiwyf/diagnostics") != std::string::npos; });
  EXPECT_NE(topics.find("crossing"), std::string::npos) << topics;
  EXPECT_NE(topics.find("wysiwyf::msg::JointState"), std::string::npos) << topics;
  EXPECT_NE(topics.find("wysiwyf/diagnostics"), std::string::npos) << topics;
  const pid_t echo = spawn_cli({"topic", "echo", "crossing", "--domain", "50", "--transport", "local", "--count", "2"},
                               dir / "echo.log");
  EXPECT_EQ(wait_exit(echo, std::chrono::seconds(30)), 0) << read_file(dir / "echo.log");
  const std::string echoed = read_file(dir / "echo.log");
  // Two samples: two "---" separator lines. (Lines, not dashes: a tool may say what it did first,
  // such as removing what a killed process left in /dev/shm.)
  std::istringstream echoed_lines(echoed);
  int separators = 0;
  for (std::string line; std::getline(echoed_lines, line);) separators += line == "---";
  EXPECT_EQ(separators, 2) << echoed;
  EXPECT_NE(echoed.find("position: ["), std::string::npos) << echoed;

  // Its diagnostics are on the domain too (transient local: the latest state of each component).
  const pid_t diag =
      spawn_cli({"topic", "echo", "wysiwyf/diagnostics", "--domain", "50", "--transport", "local", "--count", "1"},
                dir / "diag.log");
  EXPECT_EQ(wait_exit(diag, std::chrono::seconds(30)), 0) << read_file(dir / "diag.log");
  const std::string diagnostics = read_file(dir / "diag.log");
  EXPECT_NE(diagnostics.find("instance: \"src\""), std::string::npos) << diagnostics;
  EXPECT_NE(diagnostics.find("state: STATE_ACTIVE"), std::string::npos) << diagnostics;
  EXPECT_NE(diagnostics.find("rate_hz: 100"), std::string::npos) << diagnostics;

  // SIGTERM stops the producer cleanly.
  kill(producer, SIGTERM);
  EXPECT_EQ(wait_exit(producer, std::chrono::seconds(30)), 0) << read_file(dir / "producer.log");
  EXPECT_NE(read_file(dir / "producer.log").find("stopped: signal"), std::string::npos)
      << read_file(dir / "producer.log");

  // 20 samples, consecutive, intact: the source writes position[0] = its stamp in seconds.
  std::istringstream lines(read_file(dir / "received.txt"));
  std::vector<unsigned long long> seqs;
  for (std::string line; std::getline(lines, line);) {
    std::istringstream f(line);
    long long now = 0;
    unsigned long long seq = 0;
    std::string pos_hex, stamp_hex;
    f >> now >> seq >> pos_hex >> stamp_hex;
    const double position = std::strtod(pos_hex.c_str(), nullptr);
    const double stamp_ns = std::strtod(stamp_hex.c_str(), nullptr);
    EXPECT_DOUBLE_EQ(position, stamp_ns * 1e-9) << line;
    seqs.push_back(seq);
  }
  ASSERT_EQ(seqs.size(), 20u);
  for (std::size_t i = 1; i < seqs.size(); ++i) EXPECT_EQ(seqs[i], seqs[i - 1] + 1);
}

// A one-writer topic without a deadline (the arm's requests): when its writer's process is killed,
// the same group's restarted process owns it once the killed writer's liveliness lapses
// (dds::kOneWriterLiveliness, 0.5 s), not after the killed participant's 5 s lease.
TEST(TwoProcesses, ARestartedWriterOwnsAOneWriterTopicOnceTheKilledOnesLivelinessLapses) {
  const fs::path dir = scratch_dir();
  const fs::path pipeline = dir / "one_writer.yaml";
  std::ofstream(pipeline) << "wysiwyf: 1\nname: handover\ndomain: 127\ndds: {transport: local}\ninsecure: true\n"
                             "clock: {mode: real}\n"
                             "components:\n"
                             "  src: {type: test_probe, rate: 50, process: producer, topics: {out: requests},\n"
                             "        params: {one_writer: true}}\n"
                             "  sink: {type: test_probe, rate: 50, process: consumer, topics: {in: requests},\n"
                             "         params: {one_writer: true, name_writers: true}}\n";
  const auto run = [&](const std::string& group, const std::string& log) {
    return spawn_cli({"run", pipeline.string(), "--process", group, "--no-progress"}, dir / log);
  };
  // How many processes the consumer has followed so far, waiting up to `limit` for `count`.
  const auto followed = [&](int count, std::chrono::milliseconds limit) {
    const auto until = std::chrono::steady_clock::now() + limit;
    int seen = 0;
    while (true) {
      const std::string log = read_file(dir / "consumer.log");
      seen = 0;
      for (std::size_t at = log.find("samples from process 'handover/producer/"); at != std::string::npos;
           at = log.find("samples from process 'handover/producer/", at + 1))
        ++seen;
      if (seen >= count || std::chrono::steady_clock::now() > until) return seen;
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
  };
  const pid_t consumer = run("consumer", "consumer.log");
  const pid_t first = run("producer", "producer.log");
  ASSERT_EQ(followed(1, std::chrono::seconds(30)), 1) << read_file(dir / "consumer.log");
  kill(first, SIGKILL);
  wait_exit(first, std::chrono::seconds(10));
  const pid_t second = run("producer", "producer2.log");
  EXPECT_EQ(followed(2, std::chrono::seconds(30)), 2) << read_file(dir / "consumer.log");
  // The killed writer let go by its liveliness, before its participant's lease (5 s) ended, and
  // the restarted one followed as soon as it was heard, never ignored as a second writer (which
  // it would be until the lease, however soon it started).
  const std::string log = read_file(dir / "consumer.log");
  const std::string killed = "'handover/producer/" + std::to_string(first) + "'";
  const auto lapsed = log.find("topic 'requests': its writer " + killed);
  ASSERT_NE(lapsed, std::string::npos) << log;
  EXPECT_NE(log.find("lost its liveliness (nothing from its process for 500 ms)", lapsed), std::string::npos) << log;
  EXPECT_LT(lapsed, log.find("process " + killed + " is lost")) << log;
  EXPECT_EQ(log.find("samples of a second writer"), std::string::npos) << log;
  for (const pid_t pid : {second, consumer}) {
    kill(pid, SIGTERM);
    EXPECT_EQ(wait_exit(pid, std::chrono::seconds(30)), 0);
  }
}

// `topic echo` with no count ends when the topic's writer leaves (it used to wait forever), and
// --count takes a whole number of samples, not seconds.
TEST(TopicTools, EchoEndsWhenTheWriterLeaves) {
  const fs::path dir = scratch_dir();
  const fs::path pipeline = dir / "source.yaml";
  std::ofstream(pipeline) << "wysiwyf: 1\nname: source\ndomain: 57\ndds: {transport: local}\n"
                             "clock: {mode: sim, step: 1ms, duration: 4s, pace: 1}\n"
                             "components:\n  src: {type: test_probe, rate: 50, topics: {out: leaving}}\n";
  const pid_t source = spawn_cli({"run", pipeline.string(), "--no-progress"}, dir / "source.log");
  const pid_t echo = spawn_cli(
      {"topic", "echo", "leaving", "--domain", "57", "--transport", "local", "--timeout", "30"}, dir / "echo.log");
  EXPECT_EQ(wait_exit(source, std::chrono::seconds(60)), 0) << read_file(dir / "source.log");
  EXPECT_EQ(wait_exit(echo, std::chrono::seconds(60)), 0) << read_file(dir / "echo.log");  // -1: still waiting
  const std::string echoed = read_file(dir / "echo.log");
  EXPECT_NE(echoed.find("every writer of topic 'leaving' has gone"), std::string::npos) << echoed;
  EXPECT_NE(echoed.find("position: ["), std::string::npos) << echoed;

  const pid_t bad = spawn_cli({"topic", "echo", "leaving", "--domain", "57", "--count", "2.5"}, dir / "bad.log");
  EXPECT_EQ(wait_exit(bad, std::chrono::seconds(30)), 2) << read_file(dir / "bad.log");
  EXPECT_NE(read_file(dir / "bad.log").find("--count: found '2.5'; expected a whole number of samples"),
            std::string::npos)
      << read_file(dir / "bad.log");
}

}  // namespace wysiwyf::test
