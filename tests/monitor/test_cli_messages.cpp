// The monitoring commands say what is wrong and where they looked: --help on every command, the
// domain searched and the closest topic names when a topic has no writer, and `topic hz` with
// the rate on the pipeline's own clock next to the wall clock's.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <set>
#include <sstream>

#include "../kernel/cli_process.hpp"
#include "../kernel/test_support.hpp"

namespace wysiwyf::test {

namespace fs = std::filesystem;

TEST(CommandLine, HelpWorksOnEveryCommand) {
  const fs::path dir = scratch_dir();
  for (const std::string command :
       {"run", "validate", "components", "topic", "monitor", "bridge", "record", "play", "new"}) {
    const fs::path log = dir / (command + ".log");
    EXPECT_EQ(wait_exit(spawn_cli({command, "--help"}, log), std::chrono::seconds(30)), 0) << command;
    const std::string text = read_file(log);
    EXPECT_EQ(text.rfind("usage:\n  " + command, 0), 0u) << command << ": " << text;
  }
  // `wysiwyf --help` is a page: a line a command. A command's own help says each thing once
  // (the options shared by the commands that join a domain are their own paragraph).
  EXPECT_EQ(wait_exit(spawn_cli({"--help"}, dir / "all.log"), std::chrono::seconds(30)), 0);
  const std::string all = read_file(dir / "all.log");
  EXPECT_LE(std::count(all.begin(), all.end(), '\n'), 24) << all;
  for (const std::string command : {"run", "validate", "topic", "monitor", "bridge", "record", "play", "new"})
    EXPECT_NE(all.find("\n  " + command + " "), std::string::npos) << command << " is not listed:\n" << all;
  for (const std::string command : {"topic", "monitor", "bridge", "record", "play"}) {
    std::istringstream lines(read_file(dir / (command + ".log")));
    std::set<std::string> seen;
    for (std::string line; std::getline(lines, line);)
      EXPECT_TRUE(line.size() < 20 || seen.insert(line).second) << command << " --help repeats: " << line;
  }
  // A sub-command's --help is its command's.
  EXPECT_EQ(wait_exit(spawn_cli({"topic", "echo", "--help"}, dir / "echo.log"), std::chrono::seconds(30)), 0);
  EXPECT_NE(read_file(dir / "echo.log").find("topic echo TOPIC"), std::string::npos);
}

// Every number option is read by one check: trailing text, non-finite values and values out of
// range are refused with the option, what was found and what was expected (exit 2, before any
// DDS participant or pipeline is made).
TEST(CommandLine, BadNumberOptionsAreRefusedWithWhatWasExpected) {
  const fs::path dir = scratch_dir();
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"record", "--all", "-o", (dir / "x.mcap").string(), "--duration", "5s"}, "--duration: found '5s'"},
      {{"play", (dir / "x.mcap").string(), "--rate", "-1"}, "--rate: found '-1'"},
      {{"bridge", "--port", "70000"}, "--port: found '70000'; expected a TCP port"},
      {{"monitor", "--interval", "0"}, "--interval: found '0'"},
      {{"topic", "echo", "x", "--count", "2.5"}, "--count: found '2.5'; expected a whole number"},
      {{"topic", "echo", "x", "--domain", "300"}, "--domain: found '300'; expected a domain id from 0 to 232"},
      {{"discovery-server", "--id", "x"}, "--id: found 'x'"},
      {{"run", "pipelines/demo-sim.yaml", "--start-after", "nan"}, "--start-after: found 'nan'"},
  };
  int i = 0;
  for (const auto& [args, message] : cases) {
    const fs::path log = dir / ("case" + std::to_string(i++) + ".log");
    EXPECT_EQ(wait_exit(spawn_cli(args, log), std::chrono::seconds(30)), 2) << args.front() << ": " << read_file(log);
    EXPECT_NE(read_file(log).find(message), std::string::npos) << read_file(log);
  }
}

TEST(CommandLine, ATopicWithoutWriterNamesTheDomainAndTheClosestTopics) {
  const fs::path dir = scratch_dir();
  const fs::path pipeline = dir / "source.yaml";
  // pace 0.5: the sim clock runs at half the wall clock's speed.
  std::ofstream(pipeline) << "wysiwyf: 1\nname: source\ndomain: 69\ndds: {transport: local}\n"
                             "clock: {mode: sim, step: 1ms, duration: 6s, pace: 0.5}\n"
                             "components:\n"
                             "  src: {type: test_probe, rate: 100, topics: {out: robot/joint_state}}\n";
  const pid_t run = spawn_cli({"run", pipeline.string(), "--no-progress"}, dir / "run.log");
  const pid_t typo =
      spawn_cli({"topic", "echo", "robot/joint_stat", "--domain", "69", "--transport", "local", "--timeout", "3"},
                dir / "typo.log");
  const pid_t hz = spawn_cli({"topic", "hz", "robot/joint_state", "--domain", "69", "--transport", "local", "--window",
                              "2", "--duration", "5"},
                             dir / "hz.log");
  EXPECT_EQ(wait_exit(typo, std::chrono::seconds(30)), 1);
  EXPECT_EQ(wait_exit(hz, std::chrono::seconds(30)), 0) << read_file(dir / "hz.log");
  EXPECT_EQ(wait_exit(run, std::chrono::seconds(60)), 0) << read_file(dir / "run.log");
  EXPECT_NE(read_file(dir / "typo.log")
                .find("no writer on topic 'robot/joint_stat' in DDS domain 69 (transport local) within 3 s; did you "
                      "mean 'robot/joint_state'?"),
            std::string::npos)
      << read_file(dir / "typo.log");
  // 100 samples a second of sim time, whatever the wall clock's pace: the stamps say so.
  const std::string rates = read_file(dir / "hz.log");
  EXPECT_NE(rates.find("stamps 100.000 Hz"), std::string::npos) << rates;
}

}  // namespace wysiwyf::test
