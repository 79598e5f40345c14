#include <atomic>
#include <csignal>

#include "wysiwyf/runtime.hpp"

namespace wysiwyf {

static std::atomic<bool> g_stop_signal{false};

extern "C" void wysiwyf_on_stop_signal(int) { g_stop_signal.store(true); }

void install_stop_signal_handlers() {
  struct sigaction action {};
  action.sa_handler = wysiwyf_on_stop_signal;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

bool stop_signal_received() { return g_stop_signal.load(std::memory_order_relaxed); }

}  // namespace wysiwyf
