#pragma once
// The supervisor's recovery, off the arm's tick: the dashboard's unlock and the program sent
// again (restart_program, each step bounded by its timeout) run on a thread of their own, so the
// tick keeps sending the hold package every period while a slow or silent controller answers.
// (In lockstep the tick waits for it instead: the simulated clock stands still meanwhile, and the
// run stays the same from one run to the next.)
#include <future>
#include <optional>
#include <string>

#include "program_start.hpp"

namespace wysiwyf::robot::ur {

class ProgramRestart {
 public:
  struct Outcome {
    bool done = false;  // the program was sent again (then its start shows on the stream)
    std::string what;   // what was done, or why it could not be
  };

  // Starts a restart (none may be in flight: in_flight()).
  void start(const Endpoints& c, const std::string& program, double timeout_s, bool unlock);
  bool in_flight() const { return pending_.valid(); }
  // Waits for the restart in flight to end (lockstep: the simulated clock does not run meanwhile).
  void wait() const {
    if (pending_.valid()) pending_.wait();
  }
  // The outcome, once the restart has ended (nullopt while it runs or when none was started).
  std::optional<Outcome> poll();

 private:
  std::future<std::string> pending_;
};

}  // namespace wysiwyf::robot::ur
