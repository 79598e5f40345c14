#pragma once
// `wysiwyf calibrate` run as a lab runs it, for the calibration tests: its exit status and output,
// and a scratch folder.
#include <array>
#include <cstdio>
#include <filesystem>
#include <string>
#include <sys/wait.h>

namespace wysiwyf::test {

struct CliRun {
  int status = -1;
  std::string output;
};

inline CliRun calibrate(const std::string& args) {
  CliRun r;
  FILE* p = popen((std::string(WYSIWYF_CLI) + " calibrate " + args + " 2>&1").c_str(), "r");
  if (!p) return r;
  std::array<char, 4096> buf{};
  while (std::fgets(buf.data(), buf.size(), p)) r.output += buf.data();
  const int s = pclose(p);
  r.status = WIFEXITED(s) ? WEXITSTATUS(s) : -1;
  return r;
}

inline std::filesystem::path scratch(const std::string& name) {
  const std::filesystem::path dir = std::filesystem::path(WYSIWYF_TEST_SCRATCH_DIR) / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace wysiwyf::test
