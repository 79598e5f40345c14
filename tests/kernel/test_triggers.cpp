// Data-triggered ticks: a component with `trigger: <input>` ticks when a sample lands there. On
// the sim clock the whole chain runs in its producer's step, in dependency order, repeatably; on
// the real clock each sample ticks it once.
#include "test_support.hpp"

namespace wysiwyf::test {
namespace {

struct Seen {
  long long now = 0;
  unsigned long long seq = 0;
  long long stamp = 0;
};

// test_probe's record: "now seq value stamp" per sample taken.
std::vector<Seen> read_record(const std::filesystem::path& file) {
  std::vector<Seen> seen;
  std::istringstream lines(read_file(file));
  for (std::string l; std::getline(lines, l);) {
    std::istringstream f(l);
    Seen s;
    std::string value, stamp;
    f >> s.now >> s.seq >> value >> stamp;
    s.stamp = static_cast<long long>(std::strtod(stamp.c_str(), nullptr));
    seen.push_back(s);
  }
  return seen;
}

// src (periodic, 100 Hz) -> a -> b, a and b triggered, listed in `order`.
std::string chain(const std::filesystem::path& dir, int domain, const std::string& clock,
                  const std::vector<std::string>& order) {
  std::map<std::string, std::string> line = {
      {"src", "  src: {type: test_probe, rate: 100, topics: {out: x}}\n"},
      {"a", "  a: {type: test_probe, rate: 100, trigger: in, topics: {in: x, out: y}, params: {record: " +
                (dir / "a.txt").string() + "}}\n"},
      {"b", "  b: {type: test_probe, rate: 100, trigger: [in], topics: {in: y}, params: {record: " +
                (dir / "b.txt").string() + "}}\n"}};
  std::string yaml = "wysiwyf: 1\ndomain: " + std::to_string(domain) + "\ndds: {transport: local}\nclock: " + clock +
                     "\ncomponents:\n";
  for (const auto& name : order) yaml += line.at(name);
  return yaml;
}

TEST(Triggers, OnTheSimClockAChainRunsInItsProducersStepWhateverTheFileOrder) {
  for (const auto& order : std::vector<std::vector<std::string>>{{"src", "a", "b"}, {"b", "a", "src"}}) {
    const auto dir = scratch_dir();
    const RunResult r = run_pipeline(chain(dir, 61, "{mode: sim, step: 1ms, duration: 50ms}", order));
    ASSERT_TRUE(r.ok) << r.error;
    const auto a = read_record(dir / "a.txt"), b = read_record(dir / "b.txt");
    ASSERT_EQ(a.size(), 5u) << "one tick of a per sample of src (0, 10, ..., 40 ms)";
    ASSERT_EQ(b.size(), 5u);
    for (std::size_t i = 0; i < a.size(); ++i) {
      EXPECT_EQ(a[i].now, static_cast<long long>(i) * 10'000'000) << "a ticks in src's step";
      EXPECT_EQ(a[i].stamp, a[i].now) << "the sample a takes was made in the same step";
      EXPECT_EQ(b[i].now, a[i].now) << "b ticks in the same step, after a";
      EXPECT_EQ(b[i].seq, i) << "b takes a's i-th output";
    }
    // Triggered components tick only on samples: as many ticks as samples, reported.
    for (const auto& c : r.components) {
      if (c.name != "src") {
        EXPECT_EQ(c.ticks, 5u) << c.name;
      }
    }
  }
}

TEST(Triggers, TwoSimRunsOfATriggeredChainAreIdentical) {
  const auto one = scratch_dir() / "1", two = scratch_dir() / "2";
  std::filesystem::create_directories(one);
  std::filesystem::create_directories(two);
  ASSERT_TRUE(run_pipeline(chain(one, 62, "{mode: sim, step: 1ms, duration: 200ms}", {"b", "src", "a"})).ok);
  ASSERT_TRUE(run_pipeline(chain(two, 63, "{mode: sim, step: 1ms, duration: 200ms}", {"b", "src", "a"})).ok);
  EXPECT_EQ(read_file(one / "b.txt"), read_file(two / "b.txt"));
  EXPECT_FALSE(read_file(one / "b.txt").empty());
}

TEST(Triggers, OnTheRealClockEverySampleTicksTheChainOnce) {
  const auto dir = scratch_dir();
  const RunResult r = run_pipeline(chain(dir, 64, "{mode: real, duration: 400ms}", {"src", "a", "b"}));
  ASSERT_TRUE(r.ok) << r.error;
  const auto a = read_record(dir / "a.txt"), b = read_record(dir / "b.txt");
  ASSERT_GE(a.size(), 10u);
  // Each of a's outputs reached b, in order; the last may have been in flight at the stop.
  ASSERT_GE(b.size() + 1, a.size());
  for (std::size_t i = 0; i < b.size(); ++i) EXPECT_EQ(b[i].seq, i);
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_EQ(a[i].seq, i) << "a missed none of src's samples";
  for (const auto& c : r.components) {
    if (c.name == "a") {
      EXPECT_EQ(c.ticks, a.size()) << "one tick per sample";
    }
  }
}

TEST(Triggers, ATriggerLoopIsAFaultNotAHang) {
  std::string log;
  const RunResult r = run_pipeline(
      "wysiwyf: 1\ndomain: 94\ndds: {transport: local}\nclock: {mode: sim, step: 1ms, duration: 20ms}\n"
      "components:\n"
      "  kick: {type: test_probe, rate: 100, topics: {out: x}}\n"
      "  loop: {type: test_probe, rate: 100, trigger: in, topics: {in: x, out: x}}\n",
      {}, &log);
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.error.find("component 'loop'"), std::string::npos) << r.error;
  EXPECT_NE(r.error.find("without a loop among their triggers"), std::string::npos) << r.error;
}

TEST(Triggers, ATriggerThatIsNotAnInputIsRejectedWithItsPlace) {
  Loader loader(test_search_dirs());
  const PipelineSpec spec = load_pipeline_from_string(
      "wysiwyf: 1\ncomponents:\n  a: {type: test_probe, rate: 100, trigger: [in, out, inn]}\n", "t.yaml");
  const ValidationResult v = validate_pipeline(spec, loader);
  ASSERT_EQ(v.errors.size(), 2u);
  EXPECT_NE(v.errors[0].str().find("t.yaml:3:"), std::string::npos) << v.errors[0].str();
  EXPECT_NE(v.errors[0].str().find("trigger 'out' of component 'a' (test_probe) is not one of its input ports; "
                                   "expected one of in"),
            std::string::npos)
      << v.errors[0].str();
  EXPECT_NE(v.errors[1].str().find("did you mean 'in'"), std::string::npos) << v.errors[1].str();
  try {
    load_pipeline_from_string("wysiwyf: 1\ncomponents:\n  a: {type: test_probe, rate: 100, trigger: {in: 1}}\n",
                              "t.yaml");
    ADD_FAILURE() << "a map as trigger was accepted";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("expected an input port name, or a list of them"), std::string::npos)
        << e.what();
  }
}

// trigger_timeout: a triggered component also ticks after that much silence (a watchdog tick):
// src every 100 ms, sink on its samples and 30 ms after its last tick.
std::string watched(int domain, const std::string& clock) {
  return "wysiwyf: 1\ndomain: " + std::to_string(domain) + "\ndds: {transport: local}\nclock: " + clock +
         "\ncomponents:\n"
         "  sink: {type: test_probe, rate: 100, trigger: in, trigger_timeout: 30ms, topics: {in: x}}\n"
         "  src: {type: test_probe, rate: 10, topics: {out: x}}\n";
}

TEST(Triggers, OnTheSimClockATriggerTimeoutTicksAfterThatMuchSilence) {
  const RunResult r = run_pipeline(watched(66, "{mode: sim, step: 1ms, duration: 250ms}"));
  ASSERT_TRUE(r.ok) << r.error;
  for (const auto& c : r.components) {
    if (c.name == "sink") {
      EXPECT_EQ(c.ticks, 10u) << "samples at 0, 100, 200 ms; silence ticks at 30, 60, 90, 130, 160, 190, 230 ms";
    }
  }
}

TEST(Triggers, OnTheRealClockATriggerTimeoutTicksAfterThatMuchSilence) {
  const RunResult r = run_pipeline(watched(67, "{mode: real, duration: 400ms}"));
  ASSERT_TRUE(r.ok) << r.error;
  std::uint64_t src = 0, sink = 0;
  for (const auto& c : r.components) (c.name == "src" ? src : sink) = c.ticks;
  ASSERT_GE(src, 3u);
  EXPECT_GE(sink, src + 3) << "at least one silence tick in each 100 ms gap";
  EXPECT_LE(sink, src + 400 / 30 + 1) << "no more than one every 30 ms of silence";
}

TEST(Triggers, ATriggerTimeoutWithoutATriggerIsRejectedAtItsLine) {
  try {
    load_pipeline_from_string(
        "wysiwyf: 1\ncomponents:\n  a: {type: test_probe, rate: 100,\n      trigger_timeout: 5ms}\n", "t.yaml");
    ADD_FAILURE() << "accepted";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("t.yaml:4:"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("trigger_timeout: found one without a trigger"), std::string::npos)
        << e.what();
  }
  try {
    load_pipeline_from_string(
        "wysiwyf: 1\ncomponents:\n  a: {type: test_probe, rate: 100, trigger: in, trigger_timeout: 0ms}\n", "t.yaml");
    ADD_FAILURE() << "a zero timeout was accepted";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("trigger_timeout: found '0ms'; expected a positive duration"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace wysiwyf::test
