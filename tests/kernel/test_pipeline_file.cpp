// include:, --set, durations and the merged view of a pipeline.
#include "test_support.hpp"

namespace wysiwyf::test {

TEST(PipelineFile, DurationsTakeUnits) {
  EXPECT_EQ(parse_duration("1ms"), 1'000'000);
  EXPECT_EQ(parse_duration("20 ms"), 20'000'000);
  EXPECT_EQ(parse_duration("12s"), 12'000'000'000);
  EXPECT_EQ(parse_duration("500us"), 500'000);
  EXPECT_EQ(parse_duration("2min"), 120'000'000'000);
  EXPECT_EQ(parse_duration("0.5s"), 500'000'000);
  EXPECT_EQ(parse_duration("0"), 0);
  EXPECT_FALSE(parse_duration("12"));
  EXPECT_FALSE(parse_duration("fast"));
  EXPECT_FALSE(parse_duration("-1s"));
}

TEST(PipelineFile, IncludeThenOverrideThenSet) {
  const auto dir = scratch_dir();
  std::ofstream(dir / "base.yaml") << "wysiwyf: 1\nname: base\ndomain: 3\nclock: {mode: sim, step: 1ms, duration: 1s}\n"
                                      "components:\n"
                                      "  a: {type: test_probe, rate: 100, params: {gain: 1, record: x.txt}}\n"
                                      "  b: {type: test_probe, rate: 50}\n";
  std::ofstream(dir / "top.yaml") << "wysiwyf: 1\ninclude: base.yaml\nname: top\n"
                                     "components:\n"
                                     "  a: {params: {gain: 2}}\n"
                                     "  b: {enabled: false}\n"
                                     "  c: {type: test_probe, rate: 10}\n";
  const PipelineSpec spec = load_pipeline((dir / "top.yaml").string(), {"a.params.gain=3", "clock.duration=250ms", "domain=9"});
  EXPECT_EQ(spec.name.value, "top");
  EXPECT_EQ(spec.domain_id(), 9);
  EXPECT_EQ(spec.duration_ns(), 250'000'000);
  EXPECT_EQ(spec.step_ns(), 1'000'000);
  ASSERT_EQ(spec.components.size(), 3u);
  const ComponentSpec* a = spec.find("a");
  EXPECT_EQ(a->params.at("gain").value.as<double>(), 3.0);
  EXPECT_EQ(a->params.at("gain").where.file, "--set a.params.gain=3");
  EXPECT_EQ(a->params.at("record").value.as<std::string>(), "x.txt");
  EXPECT_EQ(a->params.at("record").where.line, 6);
  EXPECT_TRUE(a->params.at("record").where.file.find("base.yaml") != std::string::npos);
  EXPECT_FALSE(spec.find("b")->is_enabled());
  EXPECT_EQ(spec.processes(), (std::vector<std::string>{"main"}));
}

TEST(PipelineFile, AllErrorsAreReportedNotJustTheFirst) {
  try {
    load_pipeline_from_string("wysiwyf: 1\ndomain: -1\nclock: {mode: slow}\ncomponents:\n  a: {rate: 0}\n", "m.yaml");
    FAIL() << "accepted";
  } catch (const ConfigError& e) {
    EXPECT_GE(e.issues().size(), 3u) << e.what();
  }
}

TEST(PipelineFile, ClosestNameCatchesTyposOnly) {
  EXPECT_EQ(closest_name("threshhold", {"threshold", "rate"}), "threshold");
  EXPECT_EQ(closest_name("componets", {"components", "clock"}), "components");
  EXPECT_EQ(closest_name("xyz", {"threshold", "rate"}), "");
}

}  // namespace wysiwyf::test
