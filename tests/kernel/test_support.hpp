#pragma once
// Helpers shared by the kernel tests: a loader over the test components, scratch files, runs.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "wysiwyf/loader.hpp"
#include "wysiwyf/pipeline_spec.hpp"
#include "wysiwyf/runtime.hpp"
#include "wysiwyf/validator.hpp"

namespace wysiwyf::test {

// Test components first, then the project's own.
inline std::vector<std::string> test_search_dirs() { return {WYSIWYF_TEST_COMPONENT_DIR}; }

// A fresh directory for one test's files.
inline std::filesystem::path scratch_dir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::string name = std::string(info->test_suite_name()) + "." + info->name();
  for (auto& ch : name)
    if (ch == '/') ch = '_';
  const auto dir = std::filesystem::path(WYSIWYF_TEST_SCRATCH_DIR) / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

inline std::string read_file(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Parses, validates (failing the test on any error) and runs a pipeline in this process;
// `log_text`, if given, receives what the runtime and the components logged.
inline RunResult run_pipeline(const std::string& yaml, const std::vector<std::string>& sets = {},
                              std::string* log_text = nullptr) {
  Loader loader(test_search_dirs());
  const PipelineSpec spec = load_pipeline_from_string(yaml, "test.yaml", sets);
  const ValidationResult v = validate_pipeline(spec, loader);
  for (const auto& e : v.errors) ADD_FAILURE() << e.str();
  std::ostringstream log;
  Runtime runtime(spec, loader, RunOptions{"", false, &log});
  RunResult r = runtime.run();
  if (log_text) *log_text = log.str();
  return r;
}

}  // namespace wysiwyf::test
