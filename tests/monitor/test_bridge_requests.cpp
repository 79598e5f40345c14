// The bridge's checks on what a network client sends: every request is validated before use (a
// bad one is a problem to tell the client, never a throw), and an HTTP target reaches only the
// regular files of the web root. The running bridge is tested with these frames and paths by
// tests/monitor/hostile_clients.sh.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "bridge/client_requests.hpp"
#include "bridge/connection_graph.hpp"
#include "bridge/web_files.hpp"

namespace wysiwyf::bridge {
namespace {

namespace fs = std::filesystem;
using Fox = FoxgloveRequest::Op;

TEST(BridgeRequests, FoxgloveSubscribeAndUnsubscribeAreRead) {
  const auto sub = parse_foxglove_request(
      R"({"op":"subscribe","subscriptions":[{"id":0,"channelId":7},{"id":4294967295,"channelId":1}]})");
  ASSERT_EQ(sub.op, Fox::kSubscribe) << sub.problem;
  ASSERT_EQ(sub.subscriptions.size(), 2u);
  EXPECT_EQ(sub.subscriptions[0].channel, 7u);
  EXPECT_EQ(sub.subscriptions[1].id, 4294967295u);
  const auto unsub = parse_foxglove_request(R"({"op":"unsubscribe","subscriptionIds":[3, 12345]})");
  ASSERT_EQ(unsub.op, Fox::kUnsubscribe) << unsub.problem;
  EXPECT_EQ(unsub.unsubscribe, (std::vector<std::uint32_t>{3, 12345}));
}

TEST(BridgeRequests, TheConnectionGraphIsSubscribedAndUnsubscribed) {
  EXPECT_EQ(parse_foxglove_request(R"({"op":"subscribeConnectionGraph"})").op, Fox::kSubscribeGraph);
  EXPECT_EQ(parse_foxglove_request(R"({"op":"unsubscribeConnectionGraph"})").op, Fox::kUnsubscribeGraph);
}

// The whole graph from nothing, then only what changed; a topic nobody publishes or reads any
// more is removed.
TEST(BridgeRequests, AConnectionGraphUpdateCarriesWhatChanged) {
  ConnectionGraph a;
  a.published = {{"robot/setpoint", {"demo/display/1"}}, {"robot/wrench", {"demo/robot/2"}}};
  a.subscribed = {{"robot/setpoint", {"demo/robot/2"}}, {"robot/wrench", {}}};
  const auto full = nlohmann::json::parse(connection_graph_update({}, a));
  EXPECT_EQ(full["op"], "connectionGraphUpdate");
  EXPECT_EQ(full["publishedTopics"].size(), 2u);
  EXPECT_EQ(full["subscribedTopics"][0]["subscriberIds"][0], "demo/robot/2");
  EXPECT_TRUE(full["removedTopics"].empty());
  EXPECT_EQ(connection_graph_update(a, a), "");
  ConnectionGraph b = a;
  b.published.erase("robot/wrench");
  b.subscribed.erase("robot/wrench");
  b.subscribed["robot/setpoint"].insert("wysiwyf-cli");
  const auto diff = nlohmann::json::parse(connection_graph_update(a, b));
  EXPECT_TRUE(diff["publishedTopics"].empty());
  ASSERT_EQ(diff["subscribedTopics"].size(), 1u);
  EXPECT_EQ(diff["subscribedTopics"][0]["subscriberIds"].size(), 2u);
  EXPECT_EQ(diff["removedTopics"], nlohmann::json::array({"robot/wrench"}));
}

// The frames that killed the bridge (an unchecked conversion threw on the I/O thread), each
// refused with a problem that names what was wrong.
TEST(BridgeRequests, EveryMalformedFoxgloveFrameIsAProblemNamingWhatWasWrong) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {R"({"op":1})", "\"op\" to be a string; got a number"},
      {R"({"op":null})", "\"op\" to be a string; got null"},
      {R"({"op":["subscribe"]})", "\"op\" to be a string; got an array"},
      {R"({"op":"subscribe","subscriptions":"x"})", "\"subscriptions\" to be an array; got a string"},
      {R"({"op":"subscribe"})", "\"subscriptions\" to be an array; got none"},
      {R"({"op":"subscribe","subscriptions":[1]})", "subscriptions[0]: expected an object"},
      {R"({"op":"subscribe","subscriptions":[{"id":"a","channelId":1}]})",
       "subscriptions[0].id: expected a whole number"},
      {R"({"op":"subscribe","subscriptions":[{"id":1}]})",
       "subscriptions[0].channelId: expected a whole number from 0 to 4294967295; got none"},
      {R"({"op":"subscribe","subscriptions":[{"id":-1,"channelId":1}]})", "got a negative number"},
      {R"({"op":"subscribe","subscriptions":[{"id":4294967296,"channelId":1}]})", "got a number over 4294967295"},
      {R"({"op":"subscribe","subscriptions":[{"id":1.5,"channelId":1}]})", "got a fraction"},
      {R"({"op":"unsubscribe","subscriptionIds":[12345,"a",null]})", "subscriptionIds[1]: expected a whole number"},
      {R"({"op":"unsubscribe","subscriptionIds":{}})", "\"subscriptionIds\" to be an array; got an object"},
      {R"([1,2])", "expected a JSON object"},
      {R"({"op":"subscribe",)", "expected a JSON object"},
      {"\xff\xfe{\"op\":\"x\"}", "expected a JSON object"},
      {"", "expected a JSON object"},
  };
  for (const auto& [frame, expected] : cases) {
    const auto r = parse_foxglove_request(frame);
    EXPECT_EQ(r.op, Fox::kInvalid) << frame;
    EXPECT_NE(r.problem.find(expected), std::string::npos) << frame << " -> " << r.problem;
    EXPECT_TRUE(r.subscriptions.empty() && r.unsubscribe.empty()) << frame;
  }
  EXPECT_EQ(parse_foxglove_request(R"({"op":1})").problem, "expected \"op\" to be a string; got a number");
  const auto other = parse_foxglove_request(R"({"op":"advertise","channels":[]})");
  EXPECT_EQ(other.op, Fox::kUnsupported);
  EXPECT_NE(other.problem.find("'advertise' is not supported"), std::string::npos) << other.problem;
}

// 200,000 nested arrays crashed the bridge (a stack overflow); depth and size are bounded before
// the JSON parser sees the text.
TEST(BridgeRequests, DeepNestingAndHugeRequestsAreRefusedBeforeParsing) {
  const auto nested = [](int depth) {
    return R"({"op":"subscribe","subscriptions":)" + std::string(depth, '[') + std::string(depth, ']') + "}";
  };
  const auto r = parse_foxglove_request(nested(200000));
  EXPECT_EQ(r.op, Fox::kInvalid);
  EXPECT_NE(r.problem.find("a request of 400035 bytes; at most 65536"), std::string::npos) << r.problem;
  const auto deep = parse_foxglove_request(nested(30000));
  EXPECT_EQ(deep.op, Fox::kInvalid);
  EXPECT_NE(deep.problem.find("nested deeper than 8"), std::string::npos) << deep.problem;
  EXPECT_EQ(parse_foxglove_request(nested(7)).problem,
            "subscribe: subscriptions[0]: expected an object {\"id\", \"channelId\"}; got an array");
  // Brackets inside strings are not nesting.
  const auto in_string = parse_foxglove_request(R"({"op":"[[[[[[[[[[[[[[[[\"]]]]"})");
  EXPECT_EQ(in_string.op, Fox::kUnsupported) << in_string.problem;
  const auto huge = parse_foxglove_request(std::string(kMaxRequestBytes + 1, ' '));
  EXPECT_NE(huge.problem.find("at most 65536"), std::string::npos) << huge.problem;
  std::string many = R"({"op":"subscribe","subscriptions":[)";
  for (int i = 0; i < 5000; ++i) many += std::string(i ? "," : "") + "{}";
  EXPECT_NE(parse_foxglove_request(many + "]}").problem.find("5000 subscriptions in one request; at most 4096"),
            std::string::npos);
}

TEST(BridgeRequests, DashboardRequestsAreValidated) {
  const auto plot = parse_dashboard_request(R"({"op":"plot","topic":"robot/wrench","field":"wrench.force.z"})");
  ASSERT_EQ(plot.op, DashboardRequest::Op::kPlot) << plot.problem;
  EXPECT_EQ(plot.topic, "robot/wrench");
  EXPECT_EQ(plot.field, "wrench.force.z");
  EXPECT_EQ(parse_dashboard_request(R"({"op":"unplot","topic":"a","field":"b"})").op, DashboardRequest::Op::kUnplot);
  const std::vector<std::pair<std::string, std::string>> cases = {
      {R"({"op":"plot","topic":1,"field":2})", "\"topic\" to be a string; got a number"},
      {R"({"op":"plot","topic":"a"})", "\"field\" to be a string; got none"},
      {R"({"op":"plot","topic":"","field":"x"})", "1 to 256 printable ASCII characters"},
      {R"({"op":"plot","topic":"a\u0000b","field":"x"})", "printable ASCII"},
      {R"({"op":"plot","topic":")" + std::string(300, 'a') + R"(","field":"x"})", "1 to 256"},
      {R"({"op":"subscribe"})", "'subscribe' is not a dashboard request"},
      {R"({"op":1})", "\"op\" to be a string"},
      {"not json", "expected a JSON object"},
  };
  for (const auto& [frame, expected] : cases) {
    const auto r = parse_dashboard_request(frame);
    EXPECT_EQ(r.op, DashboardRequest::Op::kInvalid) << frame;
    EXPECT_NE(r.problem.find(expected), std::string::npos) << frame << " -> " << r.problem;
  }
}

TEST(BridgeRequests, TheBudgetRefusesAFloodAndSaysSoOncePerBurst) {
  RequestBudget budget(10, 5);
  const auto t0 = RequestBudget::Clock::time_point{} + std::chrono::hours(1);
  int served = 0;
  for (int i = 0; i < 100; ++i) served += budget.take(t0);
  EXPECT_EQ(served, 5);
  EXPECT_TRUE(budget.refusal_to_report());
  EXPECT_FALSE(budget.refusal_to_report());
  EXPECT_TRUE(budget.take(t0 + std::chrono::milliseconds(100)));  // one earned back
  EXPECT_FALSE(budget.take(t0 + std::chrono::milliseconds(100)));
  EXPECT_TRUE(budget.refusal_to_report());  // a new burst of refusals is told again
}

class WebFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    // A folder of this test's own (ctest runs the cases in parallel, each in its own process).
    base_ = fs::path(WYSIWYF_TEST_SCRATCH_DIR) / "web_files" /
            ::testing::UnitTest::GetInstance()->current_test_info()->name();
    fs::remove_all(base_);
    root_ = base_ / "dashboard";
    fs::create_directories(root_ / "vendor" / "uplot");
    std::ofstream(root_ / "index.html") << "<html>";
    std::ofstream(root_ / "vendor" / "uplot" / "uPlot.min.css") << "css";
    std::ofstream(root_ / ".hidden") << "secret";
    std::ofstream(base_ / "outside.txt") << "secret";
    fs::create_symlink(base_ / "outside.txt", root_ / "link.txt");
    fs::create_symlink("/etc/passwd", root_ / "passwd");
    fs::create_directories(root_ / "folder");
    ::mkfifo((root_ / "fifo").c_str(), 0600);
    std::ofstream(root_ / "big.bin").seekp(static_cast<std::streamoff>(kMaxWebFileBytes)) << 'x';
  }
  std::optional<WebFile> resolve(const std::string& target) {
    problem_.clear();
    return resolve_web_file(root_, target, problem_);
  }
  fs::path base_, root_;
  std::string problem_;
};

TEST_F(WebFiles, TheDashboardsFilesAreServed) {
  auto index = resolve("/");
  ASSERT_TRUE(index) << problem_;
  EXPECT_EQ(*read_web_file(*index), "<html>");
  EXPECT_STREQ(web_content_type(index->path), "text/html; charset=utf-8");
  auto css = resolve("/vendor/uplot/uPlot.min.css?v=1#x");
  ASSERT_TRUE(css) << problem_;
  EXPECT_EQ(*read_web_file(*css), "css");
}

// `//etc/passwd` was served: an absolute path joined to the web root discards the root.
TEST_F(WebFiles, NothingOutsideTheWebRootAndNothingButRegularFilesIsServed) {
  for (const std::string target : std::vector<std::string>{"//etc/passwd",
                                                           "//proc/self/environ",
                                                           "//root/.bashrc",
                                                           "//dev/zero",
                                                           "/../outside.txt",
                                                           "/vendor/../../outside.txt",
                                                           "/%2e%2e/outside.txt",
                                                           "/..%2foutside.txt",
                                                           "/./index.html",
                                                           "/.hidden",
                                                           "/link.txt",
                                                           "/passwd",
                                                           "/folder",
                                                           "/fifo",
                                                           "/big.bin",
                                                           "/index.html/",
                                                           "/no_such_file",
                                                           "index.html",
                                                           "",
                                                           "/a\\..\\outside.txt",
                                                           std::string("/index.html\0x", 13),
                                                           "/" + std::string(2000, 'a')}) {
    const auto file = resolve(target);
    EXPECT_FALSE(file) << "'" << target << "' was resolved to " << file->path;
    EXPECT_FALSE(problem_.empty()) << target;
  }
  EXPECT_FALSE(resolve_web_file({}, "/index.html", problem_));
  EXPECT_NE(problem_.find("serves no dashboard"), std::string::npos);
}

TEST_F(WebFiles, AFileIsReadNoFurtherThanItsBound) {
  const auto index = resolve("/index.html");
  ASSERT_TRUE(index);
  EXPECT_EQ(*read_web_file(*index, 3), "<ht");
}

}  // namespace
}  // namespace wysiwyf::bridge
