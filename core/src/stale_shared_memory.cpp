#include "wysiwyf/stale_shared_memory.hpp"

#include "wysiwyf/dds.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <regex>
#include <set>
#include <string>
#include <system_error>
#include <vector>

namespace wysiwyf::dds {

namespace fs = std::filesystem;

namespace {

// Whether nobody holds a lock on `path`: its owner (which holds it while alive) is dead. Taking the
// lock and letting it go again is how Fast DDS's own `fastdds shm clean` tells.
bool unlocked(const fs::path& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return false;
  const bool free = ::flock(fd, LOCK_EX | LOCK_NB) == 0;
  ::close(fd);  // (releases the lock)
  return free;
}

// Old enough that its creator has long taken its lock or mapped it: a file younger than this may
// belong to a process still starting.
bool settled(const fs::path& path, std::chrono::seconds min_age) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return false;
  return st.st_uid == ::geteuid() && std::time(nullptr) - st.st_mtime >= min_age.count();
}

// The /dev/shm files some process of this machine maps or holds open (as far as /proc lets this
// user see: its own processes, or all of them as root).
std::set<std::string> files_in_use(const fs::path& dir) {
  std::set<std::string> used;
  std::error_code ec;
  for (const auto& proc : fs::directory_iterator("/proc", ec)) {
    const std::string pid = proc.path().filename();
    if (pid.find_first_not_of("0123456789") != std::string::npos) continue;
    std::ifstream maps(proc.path() / "maps");
    for (std::string line; std::getline(maps, line);) {
      const auto at = line.find(dir.string());
      if (at != std::string::npos) used.insert(fs::path(line.substr(at)).filename());
    }
    std::error_code fd_ec;
    for (const auto& fd : fs::directory_iterator(proc.path() / "fd", fd_ec)) {
      std::error_code link_ec;
      const fs::path target = fs::read_symlink(fd.path(), link_ec);
      if (!link_ec && target.parent_path() == dir) used.insert(target.filename());
    }
  }
  return used;
}

struct Remover {
  fs::path dir;
  StaleSharedMemory result;
  void remove(const std::string& name) {
    std::error_code ec;
    const auto size = fs::file_size(dir / name, ec);
    if (fs::remove(dir / name, ec)) {
      ++result.files;
      result.bytes += ec ? 0 : size;
    }
  }
};

}  // namespace

StaleSharedMemory remove_stale_shared_memory(const std::string& directory, std::chrono::seconds min_age) {
  const fs::path dir(directory);
  std::vector<std::string> names;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(dir, ec)) names.push_back(entry.path().filename());
  const std::set<std::string> present(names.begin(), names.end());
  Remover r{dir, {}};
  auto has = [&](const std::string& name) { return present.count(name) > 0; };

  // Segments: fastrtps_<16 hex>, with the lock file _el its owner holds while alive.
  static const std::regex segment("^fastrtps_[0-9a-f]{16}$");
  for (const auto& name : names) {
    if (!std::regex_match(name, segment) || !has(name + "_el")) continue;
    const fs::path lock = dir / (name + "_el");
    if (settled(lock, min_age) && unlocked(lock)) r.remove(name), r.remove(name + "_el");
  }
  // Ports: fastrtps_port<N>, its listeners' locks _el (exclusive) and _sl (shared), its mutex
  // sem.fastrtps_port<N>_mutex; dead only when no lock of it is held.
  static const std::regex port("^fastrtps_port[0-9]+$");
  for (const auto& name : names) {
    if (!std::regex_match(name, port)) continue;
    std::vector<std::string> locks;
    for (const char* suffix : {"_el", "_sl"})
      if (has(name + suffix)) locks.push_back(name + suffix);
    if (locks.empty()) continue;
    bool dead = settled(dir / name, min_age);
    for (const auto& lock : locks) dead = dead && unlocked(dir / lock);
    if (!dead) continue;
    r.remove(name);
    for (const auto& lock : locks) r.remove(lock);
    if (has("sem." + name + "_mutex")) r.remove("sem." + name + "_mutex");
  }
  // Data-sharing pools: fast_datasharing_<writer's GUID>; no lock, so dead when no process maps
  // or holds it (a writer and its readers map it while they live).
  std::vector<std::string> pools;
  for (const auto& name : names)
    if (name.rfind("fast_datasharing_", 0) == 0 && settled(dir / name, min_age)) pools.push_back(name);
  if (!pools.empty()) {
    const std::set<std::string> used = files_in_use(dir);
    for (const auto& name : pools)
      if (!used.count(name)) r.remove(name);
  }
  return r.result;
}

void remove_stale_shared_memory_once(const std::string& transport, const std::function<void(const std::string&)>& say) {
  if (!uses_shared_memory(transport)) return;
  static std::once_flag once;
  std::call_once(once, [&] {
    const StaleSharedMemory stale = remove_stale_shared_memory();
    if (stale.files > 0 && say)
      say("removed " + std::to_string(stale.files) + " shared-memory files (" + std::to_string(stale.bytes >> 20) +
          " MB) that dead processes had left in /dev/shm");
  });
}

}  // namespace wysiwyf::dds
