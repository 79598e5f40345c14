// Two processes whose QoS cannot match say so, each on its own side, with the topic and the
// policy: before, a reliable reader on a best-effort writer silently received nothing.
#include <gtest/gtest.h>

#include <csignal>
#include <fstream>
#include <thread>

#include "../kernel/cli_process.hpp"
#include "../kernel/test_support.hpp"

namespace wysiwyf::test {

namespace fs = std::filesystem;

// Two pipelines on one domain (validation sees each alone; within one pipeline it refuses such a
// reader at its line: tests/kernel/broken/qos_refused_across_processes.yaml).
TEST(QosMismatch, AReliableReaderOnABestEffortWriterIsReportedOnBothSides) {
  const fs::path dir = scratch_dir();
  const auto write = [&](const std::string& name, const std::string& component) {
    std::ofstream(dir / (name + ".yaml")) << "wysiwyf: 1\nname: " << name
                                          << "\ndomain: 64\ndds: {transport: local}\n"
                                             "clock: {mode: sim, step: 1ms, duration: 3s, pace: 1}\n"
                                             "components:\n"
                                          << component;
    return (dir / (name + ".yaml")).string();
  };
  const std::string producing = write("producer",
                                      "  src: {type: test_probe, rate: 100, topics: {out: crossing},\n"
                                      "        qos: {out: {reliability: best_effort}}}\n");
  const std::string consuming = write("consumer",
                                      "  sink: {type: test_probe, rate: 100, topics: {in: crossing},\n"
                                      "         qos: {in: {reliability: reliable}}}\n");
  const pid_t producer = spawn_cli({"run", producing, "--no-progress"}, dir / "producer.log");
  const pid_t consumer = spawn_cli({"run", consuming, "--no-progress"}, dir / "consumer.log");
  EXPECT_EQ(wait_exit(producer, std::chrono::seconds(60)), 0) << read_file(dir / "producer.log");
  EXPECT_EQ(wait_exit(consumer, std::chrono::seconds(60)), 0) << read_file(dir / "consumer.log");
  const std::string produced = read_file(dir / "producer.log"), consumed = read_file(dir / "consumer.log");
  // As it happens, in the log...
  EXPECT_NE(produced.find("[dds] topic 'crossing': a reader in another process was refused: RELIABILITY: a reader "
                          "wants reliable, this writer offers best effort; no samples flow to it"),
            std::string::npos)
      << produced;
  EXPECT_NE(consumed.find("[dds] topic 'crossing': a writer in another process was refused: RELIABILITY: this "
                          "reader wants reliable, the writer offers best effort; no samples come from it"),
            std::string::npos)
      << consumed;
  // ...and in the run's summary.
  EXPECT_NE(produced.find("dds: topic 'crossing': 1 endpoint(s) of other processes refused (RELIABILITY)"),
            std::string::npos)
      << produced;
  EXPECT_NE(consumed.find("dds: topic 'crossing': 1 endpoint(s) of other processes refused (RELIABILITY)"),
            std::string::npos)
      << consumed;
}

namespace {

// Two process groups of test_probe on the real clock for `seconds`: the producer's out on topic
// 'crossing', the consumer's in, both with a 50 ms deadline, `params` on both.
fs::path producer_and_consumer(const fs::path& dir, const std::string& name, int domain, int seconds,
                               const std::string& params) {
  const fs::path pipeline = dir / (name + ".yaml");
  std::ofstream(pipeline) << "wysiwyf: 1\nname: " << name << "\ndomain: " << domain
                          << "\ndds: {transport: local}\ninsecure: true\nclock: {mode: real, duration: " << seconds
                          << "s}\ncomponents:\n"
                             "  src: {type: test_probe, rate: 100, process: producer, topics: {out: crossing},\n"
                             "        params: "
                          << params
                          << ", qos: {out: {deadline: 50ms}}}\n"
                             "  sink: {type: test_probe, rate: 100, process: consumer, topics: {in: crossing},\n"
                             "         params: "
                          << params << ", qos: {in: {deadline: 50ms}}}\n";
  return pipeline;
}

}  // namespace

// A stream with a DDS deadline (the pipeline's qos): when its writer's process freezes, the
// reading process names it as soon as a deadline passes, says when samples come again, and
// counts the misses in the run's summary. (Real clock: the freeze is in wall time.)
TEST(Deadline, AWriterWhoseProcessFreezesIsNamedByItsReader) {
  const fs::path dir = scratch_dir();
  const fs::path pipeline = producer_and_consumer(dir, "deadline", 120, 5, "{}");
  const pid_t consumer =
      spawn_cli({"run", pipeline.string(), "--process", "consumer", "--no-progress"}, dir / "consumer.log");
  const pid_t producer =
      spawn_cli({"run", pipeline.string(), "--process", "producer", "--no-progress"}, dir / "producer.log");
  std::this_thread::sleep_for(std::chrono::seconds(2));
  kill(producer, SIGSTOP);
  std::this_thread::sleep_for(std::chrono::seconds(1));
  kill(producer, SIGCONT);
  EXPECT_EQ(wait_exit(producer, std::chrono::seconds(60)), 0) << read_file(dir / "producer.log");
  wait_exit(consumer, std::chrono::seconds(60));  // (its summary has the misses: not a clean exit)
  const std::string consumed = read_file(dir / "consumer.log");
  EXPECT_NE(consumed.find("[dds] topic 'crossing': no sample for its deadline (50 ms) from 'deadline/producer/"),
            std::string::npos)
      << consumed;
  EXPECT_NE(consumed.find("[dds] topic 'crossing': samples again from 'deadline/producer/"), std::string::npos)
      << consumed;
  EXPECT_NE(consumed.find("dds: topic 'crossing': its deadline missed"), std::string::npos) << consumed;
}

// A one-writer stream with a deadline (the robot's setpoint): when its writer's process is killed,
// its restarted successor owns the topic once the deadline passes (or the killed writer's
// liveliness lapses), not after the dead process's DDS lease (5 s), which is when its writer is
// unmatched. (Real clock: the kill is in wall time.)
TEST(Deadline, ARestartedOneWriterOwnsTheTopicOnceTheKilledOneMissedItsDeadline) {
  const fs::path dir = scratch_dir();
  const fs::path pipeline = producer_and_consumer(dir, "owner", 121, 10, "{one_writer: true, name_writers: true}");
  const pid_t consumer =
      spawn_cli({"run", pipeline.string(), "--process", "consumer", "--no-progress"}, dir / "consumer.log");
  const pid_t first =
      spawn_cli({"run", pipeline.string(), "--process", "producer", "--no-progress"}, dir / "first.log");
  std::this_thread::sleep_for(std::chrono::seconds(2));
  kill(first, SIGKILL);
  wait_exit(first, std::chrono::seconds(10));
  const pid_t second =
      spawn_cli({"run", pipeline.string(), "--process", "producer", "--no-progress"}, dir / "second.log");
  wait_exit(second, std::chrono::seconds(60));
  wait_exit(consumer, std::chrono::seconds(60));
  const std::string consumed = read_file(dir / "consumer.log");
  const std::string first_name = "'owner/producer/" + std::to_string(first) + "'";
  const std::string second_name = "'owner/producer/" + std::to_string(second) + "'";
  const auto handed = consumed.find("[dds] topic 'crossing': its writer " + first_name);
  ASSERT_NE(handed, std::string::npos) << consumed;
  const std::string line = consumed.substr(handed, consumed.find('\n', handed) - handed);
  // (Its liveliness lapses 0.5 s after the kill: whichever of the two comes first frees the topic.)
  const bool by_deadline = line.find("missed its deadline; " + second_name) != std::string::npos &&
                           line.find("owns it now") != std::string::npos;
  const bool by_liveliness = line.find("lost its liveliness") != std::string::npos;
  EXPECT_TRUE(by_deadline || by_liveliness) << line;
  EXPECT_EQ(consumed.find("samples of a second writer"), std::string::npos) << "the successor was ignored:\n"
                                                                            << consumed;
  const auto lost = consumed.find("process " + first_name + " is lost");
  EXPECT_TRUE(lost == std::string::npos || lost > handed) << "handed over only after the lease:\n" << consumed;
  // The consumer's input says which process each sample came from (Input::writer()).
  const auto from_first = consumed.find("[sink] samples from process " + first_name);
  const auto from_second = consumed.find("[sink] samples from process " + second_name);
  EXPECT_NE(from_first, std::string::npos) << consumed;
  EXPECT_NE(from_second, std::string::npos) << consumed;
  EXPECT_LT(from_first, from_second) << consumed;
}

}  // namespace wysiwyf::test
