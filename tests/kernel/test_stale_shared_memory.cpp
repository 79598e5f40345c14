// Shared-memory files that dead processes left behind are removed; those of live processes, and
// any still being created, are not (wysiwyf/stale_shared_memory.hpp).
#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>
#include <utime.h>

#include <chrono>
#include <fstream>
#include <set>
#include <thread>

#include "cli_process.hpp"
#include "test_support.hpp"
#include "wysiwyf/stale_shared_memory.hpp"

namespace wysiwyf::test {

namespace fs = std::filesystem;

namespace {

// Sets the file's last change `by` ago.
bool age(const fs::path& path, std::chrono::seconds by) {
  const std::time_t when = std::time(nullptr) - by.count();
  const utimbuf times{when, when};
  return utime(path.c_str(), &times) == 0;
}

// A file of `bytes`, last changed `ago`.
void make(const fs::path& path, std::size_t bytes, std::chrono::seconds ago) {
  std::ofstream(path) << std::string(bytes, 'x');
  ASSERT_TRUE(age(path, ago)) << path;
}

// The files of /dev/shm that process `pid` maps or holds open.
std::set<std::string> shm_files_of(pid_t pid) {
  std::set<std::string> files;
  std::ifstream maps("/proc/" + std::to_string(pid) + "/maps");
  for (std::string line; std::getline(maps, line);)
    if (const auto at = line.find("/dev/shm/"); at != std::string::npos)
      files.insert(line.substr(at + 9, line.find(' ', at) - at - 9));
  std::error_code ec;
  for (const auto& fd : fs::directory_iterator("/proc/" + std::to_string(pid) + "/fd", ec)) {
    const fs::path target = fs::read_symlink(fd.path(), ec);
    if (!ec && target.parent_path() == "/dev/shm") files.insert(target.filename());
  }
  return files;
}

}  // namespace

TEST(StaleSharedMemory, OnlyFilesWhoseOwnersAreGoneAreRemoved) {
  const fs::path dir = scratch_dir();
  const auto old = std::chrono::seconds(60), young = std::chrono::seconds(0);
  // A dead participant's segment and its lock; a live one's (this test holds its lock); a dead
  // one's that is too young to judge (its process may be starting).
  make(dir / "fastrtps_0123456789abcdef", 4096, old);
  make(dir / "fastrtps_0123456789abcdef_el", 0, old);
  make(dir / "fastrtps_fedcba9876543210", 4096, old);
  make(dir / "fastrtps_fedcba9876543210_el", 0, old);
  make(dir / "fastrtps_00000000000000aa", 4096, young);
  make(dir / "fastrtps_00000000000000aa_el", 0, young);
  const int held = open((dir / "fastrtps_fedcba9876543210_el").c_str(), O_RDONLY);
  ASSERT_EQ(flock(held, LOCK_EX | LOCK_NB), 0);
  // A port nobody listens on any more; one with a live shared listener.
  make(dir / "fastrtps_port7411", 2048, old);
  make(dir / "fastrtps_port7411_el", 0, old);
  make(dir / "sem.fastrtps_port7411_mutex", 32, old);
  make(dir / "fastrtps_port7413", 2048, old);
  make(dir / "fastrtps_port7413_el", 0, old);
  make(dir / "fastrtps_port7413_sl", 0, old);
  const int listener = open((dir / "fastrtps_port7413_sl").c_str(), O_RDONLY);
  ASSERT_EQ(flock(listener, LOCK_SH | LOCK_NB), 0);
  // Data-sharing pools: one nobody maps, one this test maps; and a file that is not Fast DDS's.
  make(dir / "fast_datasharing_01.0f.aa_0.0.1.3", 8192, old);
  make(dir / "fast_datasharing_01.0f.bb_0.0.1.3", 8192, old);
  make(dir / "someone_elses", 100, old);
  const int pool = open((dir / "fast_datasharing_01.0f.bb_0.0.1.3").c_str(), O_RDONLY);
  void* mapped = mmap(nullptr, 8192, PROT_READ, MAP_SHARED, pool, 0);
  ASSERT_NE(mapped, MAP_FAILED);
  close(pool);  // (the mapping alone keeps it in use)

  const dds::StaleSharedMemory removed = dds::remove_stale_shared_memory(dir.string());

  for (const char* gone : {"fastrtps_0123456789abcdef", "fastrtps_0123456789abcdef_el", "fastrtps_port7411",
                           "fastrtps_port7411_el", "sem.fastrtps_port7411_mutex", "fast_datasharing_01.0f.aa_0.0.1.3"})
    EXPECT_FALSE(fs::exists(dir / gone)) << gone << " belongs to nobody: expected removed";
  for (const char* kept : {"fastrtps_fedcba9876543210", "fastrtps_fedcba9876543210_el", "fastrtps_00000000000000aa",
                           "fastrtps_00000000000000aa_el", "fastrtps_port7413", "fastrtps_port7413_el",
                           "fastrtps_port7413_sl", "fast_datasharing_01.0f.bb_0.0.1.3", "someone_elses"})
    EXPECT_TRUE(fs::exists(dir / kept)) << kept << " is in use, too young or not Fast DDS's: expected kept";
  EXPECT_EQ(removed.files, 6);
  EXPECT_EQ(removed.bytes, 4096u + 2048u + 32u + 8192u);
  munmap(mapped, 8192);
  close(held);
  close(listener);
}

// The real thing: a pipeline process killed with SIGKILL leaves its segment, its lock and its
// writers' data-sharing pools in /dev/shm; they go, and a live process's stay. (The files are
// aged by hand past the 10 s a starting process is given.)
TEST(StaleSharedMemory, AKilledPipelinesFilesGoAndALiveOnesStay) {
  const fs::path dir = scratch_dir();
  auto pipeline = [&](int domain) {
    const fs::path file = dir / ("p" + std::to_string(domain) + ".yaml");
    std::ofstream(file) << "wysiwyf: 1\nname: shm\ndomain: " << domain
                        << "\ndds: {transport: local}\n"
                           "clock: {mode: sim, step: 1ms, duration: 120s, pace: 1}\n"
                           "components:\n"
                           "  src: {type: test_probe, rate: 100, topics: {out: crossing}}\n";
    return file;
  };
  const pid_t killed = spawn_cli({"run", pipeline(97).string(), "--no-progress"}, dir / "killed.log");
  const pid_t live = spawn_cli({"run", pipeline(98).string(), "--no-progress"}, dir / "live.log");
  // Both running, each with its segment mapped (a bounded wait, not a timing check).
  std::set<std::string> killed_files, live_files;
  for (int i = 0; i < 300 && (killed_files.empty() || live_files.empty()); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    killed_files = shm_files_of(killed), live_files = shm_files_of(live);
  }
  ASSERT_FALSE(killed_files.empty()) << read_file(dir / "killed.log");
  ASSERT_FALSE(live_files.empty()) << read_file(dir / "live.log");
  kill(killed, SIGKILL);
  EXPECT_EQ(wait_exit(killed, std::chrono::seconds(30)), 128 + SIGKILL);
  std::set<std::string> segments;  // the killed process's own segments (not the ports it wrote to)
  for (const auto& f : killed_files) {
    if (f.rfind("fastrtps_port", 0) == 0 || f.rfind("sem.", 0) == 0) continue;
    segments.insert(f);
    age(fs::path("/dev/shm") / f, std::chrono::seconds(60));
  }
  for (const auto& f : live_files) age(fs::path("/dev/shm") / f, std::chrono::seconds(60));
  ASSERT_FALSE(segments.empty());
  for (const auto& f : segments) EXPECT_TRUE(fs::exists(fs::path("/dev/shm") / f)) << f << ": left behind";

  const dds::StaleSharedMemory removed = dds::remove_stale_shared_memory();

  for (const auto& f : segments) EXPECT_FALSE(fs::exists(fs::path("/dev/shm") / f)) << f << " was the killed one's";
  for (const auto& f : live_files) EXPECT_TRUE(fs::exists(fs::path("/dev/shm") / f)) << f << " is the live one's";
  // (Its count is not compared with segments.size(): a process of a test running beside this one
  // may start between the ageing and this call, and remove them first.)
  std::printf("[measured] a killed pipeline left %zu files in /dev/shm; this call removed %d files (%ju MB)\n",
              segments.size(), removed.files, removed.bytes >> 20);
  kill(live, SIGINT);
  EXPECT_EQ(wait_exit(live, std::chrono::seconds(30)), 0) << read_file(dir / "live.log");
}

}  // namespace wysiwyf::test
