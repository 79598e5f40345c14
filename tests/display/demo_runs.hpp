#pragma once
// Runs a shipped simulated demo in this process on the sim clock, as scripts/demo does, and checks
// what every demo promises (the display tests and the demo-figure tests share it).
#include <gtest/gtest.h>

#include <cstdio>
#include <regex>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "wysiwyf/loader.hpp"
#include "wysiwyf/pipeline_spec.hpp"
#include "wysiwyf/runtime.hpp"

namespace wysiwyf::test {

inline const std::string kPipelines = std::string(WYSIWYF_CONFIG_DIR) + "/pipelines/";

// Runs a simulated demo as scripts/demo does (the overrides added) and checks that the user's
// script runs to its end with no fault. `file`: a shipped pipeline (under config/pipelines/) or an
// absolute path; `component_dirs`: where the loader looks (the shipped components by default).
// Returns the run's log.
inline std::string run_demo(const std::string& file, std::vector<std::string> overrides,
                            const std::vector<std::string>& component_dirs = {WYSIWYF_COMPONENT_DIR}) {
  Loader loader(component_dirs);
  overrides.insert(overrides.end(), {"dds.transport=local", "clock.pace=0"});
  const PipelineSpec spec = load_pipeline(file.rfind('/', 0) == 0 ? file : kPipelines + file, overrides);
  std::ostringstream log;
  RunResult result;
  {
    Runtime runtime(spec, loader, RunOptions{"", false, &log});
    result = runtime.run();
  }
  const std::string text = log.str();
  EXPECT_TRUE(result.ok) << result.error << text;
  EXPECT_NE(result.stop_reason.find("the user's script is done"), std::string::npos) << result.stop_reason;
  EXPECT_EQ(text.find("-> fault"), std::string::npos) << text;
  return text;
}

// What every demo promises, from its log: every contact is a hit with the plate still >= 100 ms
// before the finger and <= 1 mm and <= 1 deg off the feature, and `expected_contacts` of them.
inline void expect_every_contact_hit(const std::string& text, const std::string& what, int expected_contacts) {
  const std::regex line(
      R"(\[metrics\] contact (\d+) \(([^)]*)\): (hit|MISS), plate still (-?\d+) ms before the finger, )"
      R"(([0-9.]+) mm / ([0-9.]+) deg)");
  int contacts = 0;
  for (std::sregex_iterator it(text.begin(), text.end(), line), end; it != end; ++it) {
    const auto& m = *it;
    ++contacts;
    std::printf("[measured] %s contact %s (%s): %s, plate still %s ms before the finger, %s mm / %s deg off\n",
                what.c_str(), m[1].str().c_str(), m[2].str().c_str(), m[3].str().c_str(), m[4].str().c_str(),
                m[5].str().c_str(), m[6].str().c_str());
    EXPECT_EQ(m[3].str(), "hit") << m[0];
    EXPECT_GE(std::stoi(m[4].str()), 100) << m[0];
    EXPECT_LE(std::stod(m[5].str()), 1.0) << m[0];
    EXPECT_LE(std::stod(m[6].str()), 1.0) << m[0];
  }
  EXPECT_EQ(contacts, expected_contacts) << text;
}

// run_demo, and what every demo promises (expect_every_contact_hit). Returns the run's log.
inline std::string run_demo_hitting_every_contact(const std::string& file, std::vector<std::string> overrides,
                                                  int expected_contacts) {
  const std::string text = run_demo(file, std::move(overrides));
  expect_every_contact_hit(text, file, expected_contacts);
  return text;
}

}  // namespace wysiwyf::test
