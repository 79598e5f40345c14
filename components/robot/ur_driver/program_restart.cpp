#include "program_restart.hpp"

#include <chrono>
#include <exception>

namespace wysiwyf::robot::ur {

void ProgramRestart::start(const Endpoints& c, const std::string& program, double timeout_s, bool unlock) {
  pending_ = std::async(std::launch::async,
                        [c, program, timeout_s, unlock] { return restart_program(c, program, timeout_s, unlock); });
}

std::optional<ProgramRestart::Outcome> ProgramRestart::poll() {
  if (!pending_.valid() || pending_.wait_for(std::chrono::seconds(0)) != std::future_status::ready) return std::nullopt;
  try {
    return Outcome{true, pending_.get()};
  } catch (const std::exception& e) {
    return Outcome{false, e.what()};
  }
}

}  // namespace wysiwyf::robot::ur
