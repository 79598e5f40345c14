#pragma once
// Helpers of the display tests: the loop (loop_run.hpp) in a scratch folder named after the test.
#include <gtest/gtest.h>

#include "loop_run.hpp"

namespace wysiwyf::test {

inline std::filesystem::path display_scratch(const std::string& suffix = "") {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const auto dir = std::filesystem::path(WYSIWYF_TEST_SCRATCH_DIR) /
                   (std::string(info->test_suite_name()) + "." + info->name() + suffix);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

inline LoopRun run_loop(const LoopSetup& setup) {
  std::vector<std::string> errors;
  LoopRun run = run_loop_in(setup, display_scratch("." + std::to_string(setup.domain)), &errors);
  for (const auto& e : errors) ADD_FAILURE() << e;
  return run;
}

}  // namespace wysiwyf::test
