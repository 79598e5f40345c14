// include:, --set, durations and the merged view of a pipeline.
#include <cstdlib>
#include <filesystem>
#include <fstream>

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
  const PipelineSpec spec =
      load_pipeline((dir / "top.yaml").string(), {"a.params.gain=3", "clock.duration=250ms", "domain=9"});
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

// The search for an unclosed bracket or quote (named in a syntax error) reads YAML's rules: an
// apostrophe or a bracket inside plain text, '' and \" inside quotes, a # inside quotes and a
// quoted text over two lines open nothing.
TEST(PipelineFile, QuotesAndBracketsInsideTextOpenNothing) {
  const std::string yaml =
      "wysiwyf: 1\n"
      "name: don't stop # it's a comment with a [ and a \"\n"
      "components:\n"
      "  a: {type: 'test_probe', rate: 100, params: {record: 'it''s # not a comment'}}\n"
      "  b:\n"
      "    type: \"test_probe\"\n"
      "    rate: 100\n"
      "    params: {lifecycle_log: \"a \\\" b\n      c\", weights: [1, 0, 0]}\n"
      "    process: x[1]\n";
  const PipelineSpec spec = load_pipeline_from_string(yaml, "tricky.yaml");
  EXPECT_EQ(spec.name.value, "don't stop");
  ASSERT_NE(spec.find("b"), nullptr);
  EXPECT_EQ(spec.find("b")->process.value, "x[1]");
  EXPECT_EQ(spec.find("a")->params.at("record").value.as<std::string>(), "it's # not a comment");
}

// A later file that defines an included component again (with a type) replaces it whole when it
// says `override: true`: none of the earlier definition's parameters is kept.
TEST(PipelineFile, AnOverrideReplacesAnIncludedComponentWhole) {
  const auto dir = scratch_dir();
  std::ofstream(dir / "base.yaml") << "wysiwyf: 1\nclock: {mode: sim, step: 1ms}\ncomponents:\n"
                                      "  a: {type: test_probe, rate: 100, params: {gain: 1, record: x.txt}}\n";
  std::ofstream(dir / "top.yaml") << "wysiwyf: 1\ninclude: base.yaml\ncomponents:\n"
                                     "  a: {type: test_probe, rate: 50, override: true, params: {gain: 2}}\n";
  const PipelineSpec spec = load_pipeline((dir / "top.yaml").string());
  const ComponentSpec* a = spec.find("a");
  ASSERT_NE(a, nullptr);
  EXPECT_EQ(a->rate.value, 50);
  EXPECT_EQ(a->params.at("gain").value.as<double>(), 2.0);
  EXPECT_EQ(a->params.count("record"), 0u);
  EXPECT_EQ(a->where.line, 4);
  EXPECT_NE(a->where.file.find("top.yaml"), std::string::npos);
}

// `~` in a later file or --set removes a key set before: a parameter or topic goes back to the
// component's default, a component leaves the pipeline, a clock or real-time key is unset.
TEST(PipelineFile, ANullRemovesAParameterATopicOrAComponent) {
  const auto dir = scratch_dir();
  std::ofstream(dir / "shipped.yaml") << "wysiwyf: 1\nclock: {mode: sim, step: 1ms}\ncomponents:\n"
                                         "  a: {type: test_probe, rate: 100, params: {gain: 1, record: x.txt},"
                                         " topics: {out: probe/out}}\n"
                                         "  b: {type: test_probe, rate: 50}\n";
  std::ofstream(dir / "mine.yaml") << "wysiwyf: 1\ninclude: shipped.yaml\ncomponents:\n"
                                      "  a: {params: {record: ~}}\n"
                                      "  b: ~\n";
  const PipelineSpec spec = load_pipeline((dir / "mine.yaml").string(), {"a.topics.out=~"});
  ASSERT_EQ(spec.components.size(), 1u);
  EXPECT_EQ(spec.find("b"), nullptr);
  const ComponentSpec* a = spec.find("a");
  EXPECT_EQ(a->params.count("record"), 0u);
  EXPECT_EQ(a->params.count("gain"), 1u);
  EXPECT_EQ(a->topics.count("out"), 0u);
  // And from the command line alone.
  EXPECT_EQ(load_pipeline((dir / "shipped.yaml").string(), {"b=~"}).components.size(), 1u);
  // A clock key: a paced sim pipeline run on the real clock drops its pace and step.
  std::ofstream(dir / "paced.yaml") << "wysiwyf: 1\nclock: {mode: sim, step: 1ms, pace: 1}\ncomponents:\n"
                                       "  a: {type: test_probe, rate: 100}\n";
  const PipelineSpec real =
      load_pipeline((dir / "paced.yaml").string(), {"clock.mode=real", "clock.pace=null", "clock.step=~"});
  EXPECT_EQ(real.clock_mode(), ClockMode::kReal);
  EXPECT_FALSE(real.clock.pace.set);
  EXPECT_FALSE(real.clock.step_ns.set);
  // A real-time key: a loop shipped SCHED_FIFO and pinned, run as a normal thread anywhere.
  std::ofstream(dir / "fifo.yaml") << "wysiwyf: 1\nclock: {mode: real}\ncomponents:\n"
                                      "  a: {type: test_probe, rate: 1000, spin: 100us, priority: 80, cpus: [1]}\n";
  const ComponentSpec normal = *load_pipeline((dir / "fifo.yaml").string(), {"a.priority=~", "a.cpus=null"}).find("a");
  EXPECT_FALSE(normal.priority.set);
  EXPECT_FALSE(normal.cpus.set);
  EXPECT_TRUE(normal.spin_ns.set);
}

// include: looks beside the including file, then in the config path ($WYSIWYF_CONFIG_PATH first).
TEST(PipelineFile, IncludeSearchesTheConfigPath) {
  const auto dir = scratch_dir();
  std::filesystem::create_directories(dir / "lab" / "pipelines");
  std::filesystem::create_directories(dir / "mine");
  std::ofstream(dir / "lab" / "pipelines" / "shared.yaml")
      << "wysiwyf: 1\nclock: {mode: sim, step: 1ms}\ncomponents:\n  a: {type: test_probe, rate: 100}\n";
  std::ofstream(dir / "mine" / "top.yaml") << "wysiwyf: 1\ninclude: pipelines/shared.yaml\n";
  setenv("WYSIWYF_CONFIG_PATH", (dir / "lab").c_str(), 1);
  const PipelineSpec spec = load_pipeline((dir / "mine" / "top.yaml").string());
  unsetenv("WYSIWYF_CONFIG_PATH");
  ASSERT_NE(spec.find("a"), nullptr);
  // A shipped pipeline, from this build's config folder with no variable.
  std::ofstream(dir / "mine" / "demo.yaml") << "wysiwyf: 1\ninclude: pipelines/puma-setpoints.yaml\n";
  EXPECT_NE(load_pipeline((dir / "mine" / "demo.yaml").string()).find("arm"), nullptr);
  // Not found anywhere: the error says where it looked.
  std::ofstream(dir / "mine" / "bad.yaml") << "wysiwyf: 1\ninclude: pipelines/nowhere.yaml\n";
  try {
    load_pipeline((dir / "mine" / "bad.yaml").string());
    FAIL() << "a missing include loaded";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.yaml:2:10"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("config path"), std::string::npos) << e.what();
  }
}

TEST(PipelineFile, AllErrorsAreReportedNotJustTheFirst) {
  try {
    load_pipeline_from_string("wysiwyf: 1\ndomain: -1\nclock: {mode: slow}\ncomponents:\n  a: {rate: 0}\n", "m.yaml");
    FAIL() << "accepted";
  } catch (const ConfigError& e) {
    EXPECT_GE(e.issues().size(), 3u) << e.what();
  }
}

// security: names a folder of keys (beside the file) and an identity per process group.
TEST(PipelineFile, SecurityNamesAKeysFolderAndAnIdentityPerProcessGroup) {
  const auto dir = scratch_dir();
  std::filesystem::create_directories(dir / "keys");
  const std::string file = (dir / "p.yaml").string();
  const PipelineSpec spec = load_pipeline_from_string(
      "wysiwyf: 1\nsecurity: {keys: keys, identities: {display: display, robot: arm}}\ncomponents:\n"
      "  a: {type: t, rate: 10, process: display}\n  b: {type: t, rate: 10, process: robot}\n",
      file);
  ASSERT_TRUE(spec.security.enabled());
  EXPECT_EQ(spec.security.keys.value, (dir / "keys").string());
  EXPECT_EQ(spec.security.identities.at("robot").value, "arm");
  EXPECT_EQ(spec.process_label("robot"), "robot");
  EXPECT_EQ(spec.process_label(""), "all");  // both groups in one process
  try {
    load_pipeline_from_string("wysiwyf: 1\nsecurity: {keys: nowhere, identity: {a: b}}\n", file);
    FAIL() << "accepted";
  } catch (const ConfigError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("p.yaml:2:18: error: security keys: found '"), std::string::npos) << what;
    EXPECT_NE(what.find("unknown security key 'identity'"), std::string::npos) << what;
  }
}

// dds.discovery_server: an IPv4:port, or a list of them (servers 0, 1, ...).
TEST(PipelineFile, DiscoveryServersAreAddressesWithPorts) {
  const PipelineSpec spec = load_pipeline_from_string(
      "wysiwyf: 1\ndds: {discovery_server: [10.0.0.5:11811, 10.0.0.6:11812]}\ncomponents:\n  a: {type: t, rate: 10}\n",
      "d.yaml");
  EXPECT_EQ(spec.dds.discovery_servers.value, (std::vector<std::string>{"10.0.0.5:11811", "10.0.0.6:11812"}));
  try {
    load_pipeline_from_string("wysiwyf: 1\ndds: {discovery_server: server.local}\ncomponents:\n  a: {type: t}\n",
                              "d.yaml");
    FAIL() << "accepted a host name";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("d.yaml:2:25: error: dds discovery_server: found 'server.local'; expected "
                                         "IPv4:port"),
              std::string::npos)
        << e.what();
  }
}

TEST(PipelineFile, ClosestNameCatchesTyposOnly) {
  EXPECT_EQ(closest_name("threshhold", {"threshold", "rate"}), "threshold");
  EXPECT_EQ(closest_name("componets", {"components", "clock"}), "components");
  EXPECT_EQ(closest_name("xyz", {"threshold", "rate"}), "");
}

// The pipeline's own keys and component parameters read scalars by one set of rules.
TEST(PipelineFile, KeysAndParametersReadScalarsAlike) {
  const PipelineSpec spec = load_pipeline_from_string(
      "wysiwyf: 1\nclock: {mode: sim, step: 1ms}\ncomponents:\n"
      "  a: {type: test_probe, rate: 0x64, enabled: True,\n"
      "      params: {fail_tick: 0x64, tick_sleep_us: 010, emit_nan: True, gain: 1e-1, lo: -2, hi: +0o17}}\n",
      "scalars.yaml");
  const ComponentSpec* a = spec.find("a");
  EXPECT_EQ(a->rate.value, 100.0);  // hex integer as a rate
  EXPECT_TRUE(a->is_enabled());     // True as a key, as it is as a bool parameter
  Loader loader(test_search_dirs());
  const auto v = validate_pipeline(spec, loader);
  EXPECT_TRUE(v.ok()) << (v.errors.empty() ? "" : v.errors[0].str());
  for (const char* bad : {"rate: 1.5.2", "rate: .inf", "rate: yes", "enabled: yes", "enabled: 1"}) {
    const std::string yaml = std::string("wysiwyf: 1\ncomponents:\n  a: {type: test_probe, ") + bad + "}\n";
    EXPECT_THROW(load_pipeline_from_string(yaml, "bad.yaml"), ConfigError) << bad;
  }
  // An integer parameter refuses a fraction and reads a leading zero as decimal (YAML 1.2).
  for (const auto& [text, ok] :
       std::vector<std::pair<std::string, bool>>{{"1.5", false}, {"010", true}, {"0x1G", false}}) {
    const PipelineSpec s = load_pipeline_from_string(
        "wysiwyf: 1\ncomponents:\n  a: {type: test_probe, rate: 100, params: {fail_tick: " + text + "}}\n", "int.yaml");
    EXPECT_EQ(validate_pipeline(s, loader).ok(), ok) << text;
  }
}

}  // namespace wysiwyf::test
