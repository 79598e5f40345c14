#pragma once
// The `wysiwyf` command line as a child process of a test: started with its output to a log,
// waited for with a hang guard (not a timing check); `topic list` asked until it shows something.
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace wysiwyf::test {

// Runs the wysiwyf command line with stdout+stderr to `log`; returns the pid.
inline pid_t spawn_cli(const std::vector<std::string>& args, const std::filesystem::path& log) {
  const pid_t pid = fork();
  if (pid == 0) {
    const int fd = open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    dup2(fd, 1);
    dup2(fd, 2);
    std::vector<char*> argv{const_cast<char*>(WYSIWYF_CLI)};
    for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    setenv("WYSIWYF_COMPONENT_PATH", WYSIWYF_TEST_COMPONENT_DIR, 1);
    execv(WYSIWYF_CLI, argv.data());
    _exit(127);
  }
  return pid;
}

// Exit status, or -1 if it did not end within the limit (a hang guard, not a timing check).
inline int wait_exit(pid_t pid, std::chrono::seconds limit) {
  const auto deadline = std::chrono::steady_clock::now() + limit;
  int status = 0;
  while (std::chrono::steady_clock::now() < deadline) {
    if (waitpid(pid, &status, WNOHANG) == pid) return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  kill(pid, SIGKILL);
  waitpid(pid, &status, 0);
  return -1;
}

// `topic list` on a domain of the local transport, asked again (a bounded number of times:
// discovery may take a few announcement periods on a loaded machine) until `done` holds for its
// listing; the last listing.
inline std::string list_topics_until(int domain, const std::filesystem::path& log,
                                     const std::function<bool(const std::string&)>& done) {
  std::string listing;
  for (int attempt = 0; attempt < 8; ++attempt) {
    const pid_t lister =
        spawn_cli({"topic", "list", "--domain", std::to_string(domain), "--transport", "local", "--wait", "2"}, log);
    EXPECT_EQ(wait_exit(lister, std::chrono::seconds(30)), 0);
    std::ifstream in(log);
    std::stringstream text;
    text << in.rdbuf();
    listing = text.str();
    if (done(listing)) break;
  }
  return listing;
}

}  // namespace wysiwyf::test
