// Kernel benchmarks: how long one hop of a port takes, for a small message (JointState) and a
// 640x480 RGB Image, in one process and between two processes, next to raw Fast DDS with the
// same QoS and transports (shared memory + loopback) in the same run.
//
// Between processes a child (this binary with --echo) returns every sample; a hop is half the
// round trip. Counters: p50_us / p99_us of the hop, allocs_per_hop (operator new calls in this
// process per hop, steady state) and child_allocs_per_hop (the same in the echoing process).
#include <benchmark/benchmark.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <thread>
#include <vector>

#include "../common/allocation_counter.hpp"
#include "endpoints.hpp"
#include "../common/smoke.hpp"

namespace wysiwyf::bench {

using Clock = std::chrono::steady_clock;
constexpr std::uint64_t kEnd = ~0ull;  // header.seq of the last sample: "report and quit"
constexpr int kWarmup = 200;

static const char* g_self = nullptr;

template <class T>
void fill(T& sample);
template <>
void fill(msg::JointState& s) {
  s.position().resize(6);
  for (int i = 0; i < 6; ++i) s.position()[i] = 0.1 * i;
}
template <>
void fill(msg::Image& s) {
  s.width(640);
  s.height(480);
  s.encoding("rgb8");
  s.step(640 * 3);
  s.data().assign(640 * 480 * 3, 128);
}

// "one-writer": the arm's setpoint's QoS (exclusive ownership, a 0.5 s liveliness lease that
// every sample asserts, the reader following one writer).
Qos qos_for(bool image, const std::string& impl) {
  if (impl == "one-writer") return Qos::reliable(4).one_writer();
  return image ? Qos::sensor(1) : Qos::reliable(4);
}

// The topics of a ping-pong. Under bench/kernel/security-policy-topics.yaml "ping" and "pong" are
// encrypted; the "authenticated" rows' "clear/..." topics are access-controlled but in clear, as
// a policy that lists the robot's topics leaves the camera images.
std::string topic_of(const std::string& impl, const char* name) {
  return (impl == "authenticated" ? "clear/" : "") + std::string(name);
}

// The child: returns every sample from "ping" on "pong" until the end marker, then reports its
// steady-state allocations in the end marker's stamp.
template <class Endpoint, class T>
int echo(int domain, bool image, const std::string& impl) {
  Endpoint ep(domain, topic_of(impl, "pong"), topic_of(impl, "ping"), qos_for(image, impl));
  T sample;
  std::uint64_t echoed = 0, allocs_at_warm = 0;
  while (true) {
    if (!ep.poll(sample)) {
      std::this_thread::yield();
      continue;
    }
    if (sample.header().seq() == kEnd) {
      sample.header().stamp_ns(static_cast<std::int64_t>(allocation_count() - allocs_at_warm));
      sample.header().frame_id(std::to_string(echoed > kWarmup ? echoed - kWarmup : 0));
      for (int i = 0; i < 20; ++i) {  // best effort: say it a few times
        ep.send(sample);
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
      }
      return 0;
    }
    if (++echoed == kWarmup) allocs_at_warm = allocation_count();
    ep.send(sample);
  }
}

struct Child {
  pid_t pid = -1;
  Child(const std::string& impl, const std::string& type, int domain) {
    std::string d = std::to_string(domain);
    const char* argv[] = {g_self, "--echo", impl.c_str(), type.c_str(), d.c_str(), nullptr};
    posix_spawn(&pid, g_self, nullptr, nullptr, const_cast<char* const*>(argv), environ);
  }
  ~Child() {
    if (pid > 0) {
      kill(pid, SIGKILL);
      waitpid(pid, nullptr, 0);
    }
  }
};

void percentiles(benchmark::State& state, std::vector<double>& hops_us) {
  if (hops_us.empty()) return;
  std::sort(hops_us.begin(), hops_us.end());
  state.counters["p50_us"] = hops_us[hops_us.size() / 2];
  state.counters["p99_us"] = hops_us[std::min(hops_us.size() - 1, hops_us.size() * 99 / 100)];
}

// One hop inside one process: write, then take on the same thread. For the kernel this is the
// local channel (no DDS); for raw Fast DDS, intra-process delivery inside one participant.
template <class Endpoint, class T>
void in_process(benchmark::State& state, int domain) {
  const bool image = std::is_same_v<T, msg::Image>;
  Endpoint ep(domain, "loop", "loop", qos_for(image, ""));
  T out, in;
  fill(out);
  for (int i = 0; i < kWarmup; ++i) {
    ep.send(out);
    while (!ep.poll(in)) std::this_thread::yield();
  }
  std::vector<double> hops;
  const auto allocs = allocation_count();
  const auto bytes = allocated_bytes();
  for (auto _ : state) {
    const auto t0 = Clock::now();
    out.header().seq(out.header().seq() + 1);
    ep.send(out);
    while (!ep.poll(in)) std::this_thread::yield();
    const double dt = std::chrono::duration<double>(Clock::now() - t0).count();
    state.SetIterationTime(dt);
    hops.push_back(dt * 1e6);
  }
  state.counters["allocs_per_hop"] =
      static_cast<double>(allocation_count() - allocs) / static_cast<double>(hops.size());
  state.counters["alloc_bytes_per_hop"] =
      static_cast<double>(allocated_bytes() - bytes) / static_cast<double>(hops.size());
  state.counters["hops_per_s"] = benchmark::Counter(static_cast<double>(hops.size()), benchmark::Counter::kIsRate);
  percentiles(state, hops);
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations()) * (image ? 640 * 480 * 3 : 152));
}

// One hop between two processes: half a ping-pong round trip through an echoing child.
template <class Endpoint, class T>
void two_process(benchmark::State& state, const std::string& impl, int domain) {
  const bool image = std::is_same_v<T, msg::Image>;
  Child child(impl, image ? "image" : "joint", domain);
  Endpoint ep(domain, topic_of(impl, "ping"), topic_of(impl, "pong"), qos_for(image, impl));
  T out, in;
  fill(out);
  // Until the child answers (discovery), then a warm-up.
  int answered = 0;
  const auto give_up = Clock::now() + std::chrono::seconds(20);
  while (answered < kWarmup && Clock::now() < give_up) {
    out.header().seq(answered);
    ep.send(out);
    const auto wait_until = Clock::now() + std::chrono::milliseconds(answered ? 100 : 20);
    while (Clock::now() < wait_until)
      if (ep.poll(in)) {
        ++answered;
        break;
      }
  }
  if (answered < kWarmup) {
    state.SkipWithError("the echoing child did not answer");
    return;
  }
  std::vector<double> hops;
  std::uint64_t lost = 0;
  const auto allocs = allocation_count();
  const auto bytes = allocated_bytes();
  std::uint64_t seq = 1'000'000;
  for (auto _ : state) {
    out.header().seq(++seq);
    const auto t0 = Clock::now();
    ep.send(out);
    const auto deadline = t0 + std::chrono::milliseconds(200);
    bool got = false;
    while (!got && Clock::now() < deadline) {
      got = ep.poll(in) && in.header().seq() == seq;
      if (!got) std::this_thread::yield();  // leave the core to the DDS receive threads
    }
    const double hop = std::chrono::duration<double>(Clock::now() - t0).count() / 2;
    if (!got) ++lost;  // best-effort images may be dropped: counted, time still charged
    state.SetIterationTime(hop);
    hops.push_back(hop * 1e6);
  }
  state.counters["allocs_per_hop"] =
      static_cast<double>(allocation_count() - allocs) / static_cast<double>(hops.size());
  state.counters["alloc_bytes_per_hop"] =
      static_cast<double>(allocated_bytes() - bytes) / static_cast<double>(hops.size());
  state.counters["lost"] = static_cast<double>(lost);
  percentiles(state, hops);
  // Ask the child for its own allocation count.
  out.header().seq(kEnd);
  ep.send(out);
  const auto deadline = Clock::now() + std::chrono::seconds(2);
  while (Clock::now() < deadline) {
    if (ep.poll(in) && in.header().seq() == kEnd) {
      const double echoed = std::atof(in.header().frame_id().c_str());
      if (echoed > 0) state.counters["child_allocs_per_hop"] = static_cast<double>(in.header().stamp_ns()) / echoed;
      break;
    }
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations()) * (image ? 640 * 480 * 3 : 152));
}

// Domains 100+: apart from the tests' and the demo's.
void BM_JointState_InProcess_Kernel(benchmark::State& s) {
  in_process<KernelEndpoint<msg::JointState>, msg::JointState>(s, 100);
}
void BM_JointState_InProcess_RawDds(benchmark::State& s) {
  in_process<RawEndpoint<msg::JointState>, msg::JointState>(s, 101);
}
void BM_Image640x480_InProcess_Kernel(benchmark::State& s) {
  in_process<KernelEndpoint<msg::Image>, msg::Image>(s, 102);
}
void BM_Image640x480_InProcess_RawDds(benchmark::State& s) { in_process<RawEndpoint<msg::Image>, msg::Image>(s, 103); }
void BM_JointState_TwoProcess_Kernel(benchmark::State& s) {
  two_process<KernelEndpoint<msg::JointState>, msg::JointState>(s, "kernel", 104);
}
void BM_JointState_TwoProcess_RawDds(benchmark::State& s) {
  two_process<RawEndpoint<msg::JointState>, msg::JointState>(s, "raw", 105);
}
void BM_JointState_TwoProcess_KernelOneWriter(benchmark::State& s) {
  two_process<KernelEndpoint<msg::JointState>, msg::JointState>(s, "one-writer", 129);
}
void BM_Image640x480_TwoProcess_Kernel(benchmark::State& s) {
  two_process<KernelEndpoint<msg::Image>, msg::Image>(s, "kernel", 106);
}
void BM_Image640x480_TwoProcess_RawDds(benchmark::State& s) {
  two_process<RawEndpoint<msg::Image>, msg::Image>(s, "raw", 107);
}
// The same hops with DDS-Security on (keys made in main()). "secured": every message encrypted
// (as shipped); "secured-topic": the topic's submessages encrypted; "authenticated":
// authenticated and access-controlled, in clear.
bool per_topic(const std::string& impl) { return impl != "secured"; }
template <class T>
void two_process_secured(benchmark::State& s, const std::string& impl, int domain) {
  if (!std::getenv("WYSIWYF_BENCH_KEYS")) return s.SkipWithError("no keys: scripts/security failed (see above)");
  if (per_topic(impl)) return two_process<SecuredKernelEndpoint<T, true>, T>(s, impl, domain);
  two_process<SecuredKernelEndpoint<T>, T>(s, impl, domain);
}
template <class T>
int echo_secured(int domain, bool image, const std::string& impl) {
  if (per_topic(impl)) return echo<SecuredKernelEndpoint<T, true>, T>(domain, image, impl);
  return echo<SecuredKernelEndpoint<T>, T>(domain, image, impl);
}
void BM_JointState_TwoProcess_KernelSecured(benchmark::State& s) {
  two_process_secured<msg::JointState>(s, "secured", 108);
}
void BM_JointState_TwoProcess_KernelSecuredTopic(benchmark::State& s) {
  two_process_secured<msg::JointState>(s, "secured-topic", 123);  // (116, 119: the net tests)
}
void BM_Image640x480_TwoProcess_KernelSecured(benchmark::State& s) {
  two_process_secured<msg::Image>(s, "secured", 109);
}
void BM_Image640x480_TwoProcess_KernelAuthenticated(benchmark::State& s) {
  two_process_secured<msg::Image>(s, "authenticated", 128);  // (110-115, 118, 125: the security tests)
}

BENCHMARK(BM_JointState_InProcess_Kernel)
    ->UseManualTime()
    ->Iterations(wysiwyf::bench::iterations(200000))
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_JointState_InProcess_RawDds)
    ->UseManualTime()
    ->Iterations(wysiwyf::bench::iterations(200000))
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Image640x480_InProcess_Kernel)
    ->UseManualTime()
    ->Iterations(wysiwyf::bench::iterations(2000))
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Image640x480_InProcess_RawDds)
    ->UseManualTime()
    ->Iterations(wysiwyf::bench::iterations(2000))
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_JointState_TwoProcess_Kernel)
    ->UseManualTime()
    ->Iterations(wysiwyf::bench::iterations(20000))
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_JointState_TwoProcess_RawDds)
    ->UseManualTime()
    ->Iterations(wysiwyf::bench::iterations(20000))
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_JointState_TwoProcess_KernelOneWriter)
    ->UseManualTime()
    ->Iterations(wysiwyf::bench::iterations(20000))
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_JointState_TwoProcess_KernelSecured)
    ->UseManualTime()
    ->Iterations(wysiwyf::bench::iterations(20000))
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_JointState_TwoProcess_KernelSecuredTopic)
    ->UseManualTime()
    ->Iterations(wysiwyf::bench::iterations(20000))
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Image640x480_TwoProcess_Kernel)
    ->UseManualTime()
    ->Iterations(wysiwyf::bench::iterations(2000))
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Image640x480_TwoProcess_RawDds)
    ->UseManualTime()
    ->Iterations(wysiwyf::bench::iterations(2000))
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Image640x480_TwoProcess_KernelSecured)
    ->UseManualTime()
    ->Iterations(wysiwyf::bench::iterations(2000))
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Image640x480_TwoProcess_KernelAuthenticated)
    ->UseManualTime()
    ->Iterations(wysiwyf::bench::iterations(2000))
    ->Unit(benchmark::kMicrosecond);

// Keys for the secured rows, once per run, inherited by the echoing children.
void make_keys() {
  if (std::getenv("WYSIWYF_BENCH_KEYS")) return;
  const std::string dir = "/tmp/wysiwyf-bench-keys-" + std::to_string(getpid());
  const auto keys = [&](const char* policy, const char* folder) {
    const std::string command = std::string(WYSIWYF_SOURCE_DIR) + "/scripts/security " + WYSIWYF_SOURCE_DIR +
                                "/bench/kernel/" + policy + " " + dir + "/" + folder + " >/dev/null";
    return std::system(command.c_str()) == 0;
  };
  if (keys("security-policy.yaml", "messages") && keys("security-policy-topics.yaml", "topics"))
    setenv("WYSIWYF_BENCH_KEYS", dir.c_str(), 1);
}

}  // namespace wysiwyf::bench

int main(int argc, char** argv) {
  using namespace wysiwyf;
  bench::g_self = argv[0];
  if (argc == 5 && std::strcmp(argv[1], "--echo") == 0) {
    const bool image = std::strcmp(argv[3], "image") == 0;
    const int domain = std::atoi(argv[4]);
    const bool kernel = std::strcmp(argv[2], "kernel") == 0 || std::strcmp(argv[2], "one-writer") == 0;
    const std::string impl = argv[2];
    if (impl == "secured" || impl == "secured-topic" || impl == "authenticated")
      return image ? bench::echo_secured<msg::Image>(domain, true, impl)
                   : bench::echo_secured<msg::JointState>(domain, false, impl);
    if (image)
      return kernel ? bench::echo<bench::KernelEndpoint<msg::Image>, msg::Image>(domain, true, impl)
                    : bench::echo<bench::RawEndpoint<msg::Image>, msg::Image>(domain, true, impl);
    return kernel ? bench::echo<bench::KernelEndpoint<msg::JointState>, msg::JointState>(domain, false, impl)
                  : bench::echo<bench::RawEndpoint<msg::JointState>, msg::JointState>(domain, false, impl);
  }
  benchmark::Initialize(&argc, argv);
  bench::make_keys();
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  if (const char* keys = std::getenv("WYSIWYF_BENCH_KEYS"); keys && std::strstr(keys, "/tmp/wysiwyf-bench-keys-"))
    std::filesystem::remove_all(keys);
  return 0;
}
