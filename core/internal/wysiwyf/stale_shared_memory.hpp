#pragma once
// Fast DDS's shared-memory files that a dead process left behind. A process killed (SIGKILL, a
// crash, a power cut) never removes its segments (32 MB each with the kernel's transport), ports
// and data-sharing pools from /dev/shm, and nothing else does: after a day of tests a machine
// held 800 MB of them. Every participant this project creates first removes those whose owner is
// gone, as Fast DDS's `fastdds shm clean` tells it (a segment's or port's lock file that nobody
// holds), and the data-sharing pools no process maps or holds open.
#include <chrono>
#include <cstdint>
#include <functional>
#include <string>

namespace wysiwyf::dds {

struct StaleSharedMemory {
  int files = 0;
  std::uintmax_t bytes = 0;
};

// Removes, in `directory`, the Fast DDS files of this user older than `min_age` (a younger one may
// belong to a process still starting) whose owners are dead. Never throws.
StaleSharedMemory remove_stale_shared_memory(const std::string& directory = "/dev/shm",
                                             std::chrono::seconds min_age = std::chrono::seconds(10));
// The same in /dev/shm, once per process, before its first participant on a transport with shared
// memory (dds::uses_shared_memory), saying what it removed.
void remove_stale_shared_memory_once(const std::string& transport, const std::function<void(const std::string&)>& say);

}  // namespace wysiwyf::dds
