// Every component's inputs fuzzed through the Harness (component_fuzzer.hpp): seeded sequences of
// plausible and hostile samples of each declared input type; no tick throws, no output carries a
// non-finite number, no setpoint leaves the arm's reach or its unit quaternion. The sequence count
// per component is the CI's; WYSIWYF_FUZZ_SEQUENCES sets another (scripts/fuzz components).
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <string>

#include "component_fuzzer.hpp"
#include "wysiwyf/loader.hpp"

namespace wysiwyf::safety {
namespace {

struct Subject {
  const char* type;
  const char* params;
  double rate_hz;
  std::uint64_t sequences;  // in CI
};

std::ostream& operator<<(std::ostream& out, const Subject& s) { return out << s.type; }

class ComponentInputs : public ::testing::TestWithParam<Subject> {};

TEST_P(ComponentInputs, SurviveRandomAndHostileSamplesWithFiniteOutputs) {
  const Subject& subject = GetParam();
  FuzzOptions o;
  o.type = subject.type;
  o.params = subject.params;
  o.rate_hz = subject.rate_hz;
  o.sequences = subject.sequences;
  if (const char* n = std::getenv("WYSIWYF_FUZZ_SEQUENCES")) o.sequences = std::strtoull(n, nullptr, 10);
  if (const char* seed = std::getenv("WYSIWYF_FUZZ_SEED")) o.seed = std::strtoull(seed, nullptr, 10);
  Loader loader({WYSIWYF_COMPONENT_DIR});
  const FuzzResult r = fuzz_component(o, loader);
  std::string inputs;
  for (const auto& i : r.inputs) inputs += (inputs.empty() ? "" : ", ") + i;
  std::printf(
      "[measured] %s (seed %llu): %llu sequences, %llu ticks; inputs %s: %llu samples fed, %llu refused by "
      "deserialisation, %llu rejected by the component; %llu outputs checked; slowest tick %.1f ms\n",
      subject.type, static_cast<unsigned long long>(o.seed), static_cast<unsigned long long>(r.sequences),
      static_cast<unsigned long long>(r.ticks), inputs.c_str(), static_cast<unsigned long long>(r.fed),
      static_cast<unsigned long long>(r.refused_by_dds), static_cast<unsigned long long>(r.rejected),
      static_cast<unsigned long long>(r.outputs), r.slowest_tick_s * 1e3);
  for (const auto& u : r.unwatched) std::printf("[measured] %s: output %s not checked\n", subject.type, u.c_str());
  EXPECT_EQ(r.sequences, o.sequences);
  EXPECT_GT(r.fed, 0u) << "nothing reached the component";
  EXPECT_EQ(r.finding_count, 0u) << [&] {
    std::string s;
    for (const auto& f : r.findings) s += "\n  " + f;
    return s;
  }();
}

// Sequences in CI: 20,000 for every component whose tick costs microseconds; fewer for those that
// render (llvmpipe: milliseconds a tick). `scripts/fuzz components` runs 100,000 of each.
constexpr std::uint64_t kCi = 20000;
INSTANTIATE_TEST_SUITE_P(
    Components, ComponentInputs,
    ::testing::Values(Subject{"supervisor", "{}", 1000, kCi}, Subject{"surface_planner", "{}", 250, kCi},
                      Subject{"admittance_sim", "{}", 1000, kCi}, Subject{"arm_sim", "{}", 1000, kCi},
                      Subject{"user_sim", "{}", 1000, kCi}, Subject{"setpoint_script", "{}", 250, kCi},
                      Subject{"wrench_lowpass", "{}", 1000, kCi}, Subject{"hand_tracker_sim", "{}", 100, kCi},
                      Subject{"marker_tracker", "{}", 25, kCi},
                      Subject{"camera_fixed", "{extrinsics: calibration/sim_camera.yaml}", 25, kCi},
                      Subject{"chroma_keyer", "{}", 25, kCi}, Subject{"stereo_depth", "{}", 25, kCi},
                      Subject{"fingertip_tracker", "{}", 25, kCi}, Subject{"frame_latency", "{}", 100, kCi},
                      Subject{"overlay", "{}", 25, kCi}, Subject{"ros2_mirror", "{}", 100, kCi},
                      Subject{"display_metrics", "{}", 1000, 5000}, Subject{"compositor", "{}", 25, 5000},
                      Subject{"video_sink", "{path: " WYSIWYF_TEST_SCRATCH_DIR "/fuzz_video.mp4}", 25, 5000},
                      Subject{"renderer", "{}", 25, 2000}, Subject{"device_mask", "{}", 25, 1000},
                      Subject{"camera_sim", "{}", 25, 30}),
    [](const ::testing::TestParamInfo<Subject>& info) { return std::string(info.param.type); });

}  // namespace
}  // namespace wysiwyf::safety
