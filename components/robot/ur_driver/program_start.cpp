#include "program_start.hpp"

#include <chrono>
#include <stdexcept>
#include <thread>

#include "text_ports.hpp"

namespace wysiwyf::robot::ur {
namespace {

using Clock = std::chrono::steady_clock;

Clock::time_point after(double s) {
  return Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(s));
}

std::uint16_t port(int p) { return static_cast<std::uint16_t>(p); }

}  // namespace

void start_program_before_stream(const Endpoints& c, const std::string& program, double timeout_s) {
  send_script(c.host, port(c.script_port), program, timeout_s);
  const auto deadline = after(timeout_s);
  std::string state;
  while (Clock::now() < deadline) {
    state = dashboard_command(c.host, port(c.dashboard_port), "programState", timeout_s);
    if (state.rfind("PLAYING", 0) == 0) return;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  throw std::runtime_error("the follow program did not start within " + std::to_string(timeout_s) +
                           " s: the dashboard says '" + state + "', expected 'PLAYING ...'");
}

void start_program_on_stream(const Endpoints& c, const std::string& program, double timeout_s, RtdeLink& link,
                             const std::function<void()>& hold) {
  send_script(c.host, port(c.script_port), program, timeout_s);
  const auto deadline = after(timeout_s);
  const std::uint64_t before = link.output_packages();
  while (Clock::now() < deadline) {
    link.service(0.002);
    if (!link.streaming()) throw std::runtime_error(link.error());
    hold();
    if (link.output_packages() > before && program_running(link.state())) return;
  }
  throw std::runtime_error("the follow program did not start within " + std::to_string(timeout_s) +
                           " s: " + controller_problem(link.state()));
}

std::string restart_program(const Endpoints& c, const std::string& program, double timeout_s, bool unlock) {
  std::string done;
  if (unlock) {
    const std::string reply = dashboard_command(c.host, port(c.dashboard_port), "unlock protective stop", timeout_s);
    if (reply.rfind("Protective stop releasing", 0) != 0)
      throw std::runtime_error("the dashboard did not unlock the protective stop: '" + reply +
                               "', expected 'Protective stop releasing' (a UR allows it 5 s after the stop)");
    done = "the protective stop unlocked, ";
  }
  send_script(c.host, port(c.script_port), program, timeout_s);
  return done + "the follow program sent again";
}

}  // namespace wysiwyf::robot::ur
