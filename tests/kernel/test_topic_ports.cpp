// `topic list` counts every port on a topic, the readers a process serves in-process too (they
// have no DDS endpoint: the process's writer announces them, dds::EndpointPorts), and the
// announcement is read as hostile input: only its exact form, counts in range.
#include <signal.h>

#include <chrono>
#include <sstream>

#include "cli_process.hpp"
#include "test_support.hpp"
#include "wysiwyf/dds.hpp"

namespace wysiwyf::test {

namespace fs = std::filesystem;

namespace {

std::vector<unsigned char> bytes(const std::string& text) { return {text.begin(), text.end()}; }

// The writers and readers `topic list` printed for `topic`, or {-1, -1}.
std::pair<int, int> listed(const std::string& list, const std::string& topic) {
  std::istringstream lines(list);
  for (std::string line; std::getline(lines, line);) {
    std::istringstream f(line);
    std::string name, type;
    int writers = -1, readers = -1;
    if (f >> name >> type >> writers >> readers && name == topic) return {writers, readers};
  }
  return {-1, -1};
}

}  // namespace

TEST(EndpointPorts, TheAnnouncementRoundTripsAndAnythingElseIsNotBelieved) {
  const auto text = dds::endpoint_ports_user_data({2, 5});
  EXPECT_EQ(std::string(text.begin(), text.end()), "wysiwyf-ports 2 5");
  const auto back = dds::endpoint_ports_from_user_data(text);
  ASSERT_TRUE(back);
  EXPECT_EQ(back->writers, 2);
  EXPECT_EQ(back->readers, 5);
  for (const char* bad :
       {"", "wysiwyf-ports", "wysiwyf-ports ", "wysiwyf-ports 1", "wysiwyf-ports 1 ", "wysiwyf-ports 1 2 3",
        "wysiwyf-ports -1 2", "wysiwyf-ports 1 -2", "wysiwyf-ports 1  2", "wysiwyf-ports x 2",
        "wysiwyf-ports 1 99999999999999999999", "wysiwyf-ports 1 100001", "WYSIWYF-ports 1 2", "other 1 2"})
    EXPECT_FALSE(dds::endpoint_ports_from_user_data(bytes(bad))) << "'" << bad << "'";
  std::vector<unsigned char> nul = bytes("wysiwyf-ports 1 2");
  nul.push_back(0);
  EXPECT_FALSE(dds::endpoint_ports_from_user_data(nul));
  EXPECT_FALSE(dds::endpoint_ports_from_user_data(std::vector<unsigned char>(4096, '7')));
  EXPECT_TRUE(dds::endpoint_ports_from_user_data(bytes("wysiwyf-ports 0 100000")));
}

// One process writes `shared` and reads it twice in-process; another process reads it once.
TEST(TopicTools, ListCountsTheReadersOfEveryProcessInProcessOnesToo) {
  const fs::path dir = scratch_dir();
  const fs::path pipeline = dir / "ports.yaml";
  std::ofstream(pipeline) << "wysiwyf: 1\nname: ports\ndomain: 80\ndds: {transport: local}\n"
                             "insecure: true\n"
                             "clock: {mode: sim, step: 1ms, duration: 60s, pace: 1}\n"
                             "components:\n"
                             "  src: {type: test_probe, rate: 50, process: one, topics: {out: shared}}\n"
                             "  near1: {type: test_probe, rate: 50, process: one, topics: {in: shared}}\n"
                             "  near2: {type: test_probe, rate: 50, process: one, topics: {in: shared}}\n"
                             "  far: {type: test_probe, rate: 50, process: two, topics: {in: shared}}\n";
  const pid_t one = spawn_cli({"run", pipeline.string(), "--process", "one", "--no-progress"}, dir / "one.log");
  const pid_t two = spawn_cli({"run", pipeline.string(), "--process", "two", "--no-progress"}, dir / "two.log");
  const std::string list = list_topics_until(80, dir / "list.log", [](const std::string& l) {
    return listed(l, "shared") == std::pair{1, 3};
  });
  EXPECT_EQ(listed(list, "shared"), (std::pair{1, 3})) << list;
  kill(one, SIGTERM);
  kill(two, SIGTERM);
  EXPECT_EQ(wait_exit(one, std::chrono::seconds(30)), 0) << read_file(dir / "one.log");
  EXPECT_EQ(wait_exit(two, std::chrono::seconds(30)), 0) << read_file(dir / "two.log");
}

}  // namespace wysiwyf::test
