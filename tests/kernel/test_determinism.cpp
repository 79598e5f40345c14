// Two runs of the same sim pipeline produce the same outputs, bit for bit.
#include "test_support.hpp"

namespace wysiwyf::test {

std::string loop_pipeline(const std::filesystem::path& dir, int domain) {
  // A feedback loop at three rates: a -> b -> c -> a, each output depending on its inputs.
  return "wysiwyf: 1\ndomain: " + std::to_string(domain) +
         "\ndds: {transport: local}\nclock: {mode: sim, step: 1ms, duration: 2s}\ncomponents:\n"
         "  a: {type: test_probe, rate: 1000, topics: {in: c_out, out: a_out}, params: {gain: 0.7, record: " +
         (dir / "a.txt").string() +
         "}}\n"
         "  b: {type: test_probe, rate: 500, topics: {in: a_out, out: b_out}, params: {gain: -1.3, record: " +
         (dir / "b.txt").string() +
         "}}\n"
         "  c: {type: test_probe, rate: 200, topics: {in: b_out, out: c_out}, params: {gain: 2.1, record: " +
         (dir / "c.txt").string() + "}}\n";
}

TEST(Determinism, TwoSimRunsGiveIdenticalOutputs) {
  const auto root = scratch_dir();
  std::filesystem::create_directories(root / "1");
  std::filesystem::create_directories(root / "2");
  ASSERT_TRUE(run_pipeline(loop_pipeline(root / "1", 47)).ok);
  ASSERT_TRUE(run_pipeline(loop_pipeline(root / "2", 48)).ok);
  for (const char* f : {"a.txt", "b.txt", "c.txt"}) {
    const std::string one = read_file(root / "1" / f), two = read_file(root / "2" / f);
    EXPECT_GT(one.size(), 1000u) << f;
    EXPECT_EQ(one, two) << f << " differs between runs";
  }
  // b ticks at 500 Hz and a publishes at 1 kHz: b sees two samples per tick, all 2000 in total.
  const std::string b = read_file(root / "1" / "b.txt");
  EXPECT_EQ(std::count(b.begin(), b.end(), '\n'), 1999);  // a's last sample comes after b's last tick
}

TEST(Determinism, SimStampsAreSimTime) {
  const auto dir = scratch_dir();
  ASSERT_TRUE(run_pipeline("wysiwyf: 1\ndomain: 49\ndds: {transport: local}\n"
                           "clock: {mode: sim, step: 1ms, duration: 30ms}\ncomponents:\n"
                           "  src: {type: test_probe, rate: 100, topics: {out: x}}\n"
                           "  rec: {type: test_probe, rate: 100, topics: {in: x}, params: {record: " +
                           (dir / "r.txt").string() + "}}\n")
                  .ok);
  std::istringstream lines(read_file(dir / "r.txt"));
  std::vector<long long> seen;
  for (std::string l; std::getline(lines, l);) seen.push_back(std::stoll(l.substr(0, l.find(' '))));
  EXPECT_EQ(seen, (std::vector<long long>{0, 10'000'000, 20'000'000}));
}

}  // namespace wysiwyf::test
