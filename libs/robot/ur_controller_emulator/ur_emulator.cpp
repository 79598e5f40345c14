#include "ur_controller_emulator/ur_emulator.hpp"

#include <atomic>
#include <cmath>
#include <chrono>
#include <list>
#include <mutex>
#include <thread>

#include "rtde/framer.hpp"
#include "rtde/server_session.hpp"
#include "rtde/tcp.hpp"

namespace wysiwyf::robot::ur {

namespace {

struct RtdeClient {
  rtde::TcpStream stream;
  rtde::PackageFramer framer;
  std::unique_ptr<rtde::ServerSession> session;
  std::uint64_t inputs_seen = 0;
  std::uint64_t periods = 0;
  std::vector<std::vector<std::uint8_t>> held;  // delayed output packages
};

struct TextClient {
  rtde::TcpStream stream;
  std::string text;
};

}  // namespace

struct UrEmulator::Impl {
  Options options;
  UrController controller;
  rtde::TcpListener rtde_listener{"127.0.0.1", options.rtde_port};
  rtde::TcpListener script_listener{"127.0.0.1", options.script_port};
  rtde::TcpListener dashboard_listener{"127.0.0.1", options.dashboard_port};
  rtde::InputOwners owners;
  std::list<RtdeClient> rtde_clients;
  std::list<TextClient> script_clients, dashboard_clients;
  mutable std::mutex mutex;  // guards the controller, the clients and the counters
  Counters counters;
  int delay_periods = 0;
  bool malformed_next = false, dashboard_silent = false;
  std::atomic<bool> stop{false};
  std::thread thread;

  explicit Impl(Options o) : options(std::move(o)), controller(options.controller) {}

  void accept_all() {
    for (rtde::TcpStream s = rtde_listener.accept(0); s.open(); s = rtde_listener.accept(0)) {
      RtdeClient c;
      c.stream = std::move(s);
      rtde_clients.push_back(std::move(c));
      rtde_clients.back().session = std::make_unique<rtde::ServerSession>(rtde::ControllerVersion{5, 11, 3, 0}, owners);
      ++counters.rtde_connections;
    }
    for (rtde::TcpStream s = script_listener.accept(0); s.open(); s = script_listener.accept(0))
      script_clients.push_back({std::move(s), {}});
    for (rtde::TcpStream s = dashboard_listener.accept(0); s.open(); s = dashboard_listener.accept(0)) {
      dashboard_clients.push_back({std::move(s), {}});
      if (!dashboard_silent)
        dashboard_clients.back().stream.send(text_bytes("Connected: Universal Robots Dashboard Server\n"));
    }
  }

  static std::vector<std::uint8_t> text_bytes(const std::string& s) { return {s.begin(), s.end()}; }

  // Sends one period's outputs to every streaming client whose frequency asks for one now.
  void send_outputs(RtdeClient& c) {
    rtde::ServerSession& s = *c.session;
    if (!s.streaming() || !s.outputs()) return;
    const double period = options.controller.period;
    const auto every = static_cast<std::uint64_t>(std::max(1.0, std::round(1.0 / (s.output_frequency() * period))));
    if (c.periods++ % every != 0) return;
    controller.fill_outputs(*s.outputs());
    std::vector<std::uint8_t> out;
    s.encode_outputs(out);
    if (malformed_next) out.resize(out.size() / 2);  // the header still claims the whole package
    if (delay_periods > 0) {
      c.held.push_back(std::move(out));
      return;
    }
    for (auto& h : c.held) c.stream.send(h);
    c.held.clear();
    c.stream.send(out);
    ++counters.outputs_sent;
  }

  // Reads one RTDE client; in lockstep, steps once per input data package.
  void serve(RtdeClient& c) {
    std::vector<std::uint8_t> in, replies;
    c.stream.receive(in);
    c.framer.feed(in.data(), in.size());
    while (const auto pkg = c.framer.next()) {
      const std::uint64_t refused_before = c.session->refused();
      const bool was_streaming = c.session->streaming();
      c.session->handle(*pkg, replies);
      counters.packages_refused += c.session->refused() - refused_before;
      // In lockstep no period passes until the first input package: the state the stream starts
      // from goes out with the start's answer (the controller's periods would send it anyway).
      if (options.lockstep && !was_streaming && c.session->streaming() && c.session->outputs()) {
        controller.fill_outputs(*c.session->outputs());
        c.session->encode_outputs(replies);
        ++counters.outputs_sent;
      }
      if (c.session->input_packages() != c.inputs_seen) {
        c.inputs_seen = c.session->input_packages();
        controller.take_inputs(*c.session->inputs(pkg->payload[0]));
        if (options.lockstep) {
          c.stream.send(replies);
          replies.clear();
          period();
        }
      }
    }
    if (c.framer.failed()) c.stream.close();  // the stream cannot be resynchronised
    c.stream.send(replies);
  }

  void serve_script(TextClient& c) {
    std::vector<std::uint8_t> in;
    const bool open = c.stream.receive(in, 65536);
    c.text.append(in.begin(), in.end());
    const bool ended = c.text.find("\nwysiwyf_follow()") != std::string::npos;
    if (c.text.size() > 65536 || (!open && !c.text.empty()) || ended) {
      std::string why;
      if (controller.load_program(c.text, why))
        ++counters.scripts_run;
      else
        ++counters.scripts_refused;
      c.text.clear();
    }
  }

  void serve_dashboard(TextClient& c) {
    if (dashboard_silent) return;
    std::vector<std::uint8_t> in;
    c.stream.receive(in, 4096);
    c.text.append(in.begin(), in.end());
    for (std::size_t eol; (eol = c.text.find('\n')) != std::string::npos;) {
      std::string command = c.text.substr(0, eol);
      c.text.erase(0, eol + 1);
      if (!command.empty() && command.back() == '\r') command.pop_back();
      ++counters.dashboard_commands;
      std::string reply;
      if (command == "unlock protective stop")
        reply = controller.unlock_protective_stop() ? "Protective stop releasing" : "Cannot unlock protective stop";
      else if (command == "safetystatus")
        reply = "Safetystatus: " + std::string(rtde::to_string(controller.safety_mode()));
      else if (command == "programState")
        reply = controller.program_running() ? "PLAYING wysiwyf_follow" : "STOPPED wysiwyf_follow";
      else if (command == "close safety popup")
        reply = "closing safety popup";
      else
        reply = "could not understand: '" + command.substr(0, 64) + "'";
      c.stream.send(text_bytes(reply + "\n"));
    }
    if (c.text.size() > 4096) c.stream.close();  // a line that never ends
  }

  void period() {
    controller.step();
    ++counters.periods;
    for (RtdeClient& c : rtde_clients) send_outputs(c);
    if (delay_periods > 0) --delay_periods;
    malformed_next = false;
  }

  template <typename List>
  static void remove_closed(List& clients) {
    clients.remove_if([](const auto& c) { return !c.stream.open(); });
  }

  void run() {
    using Clock = std::chrono::steady_clock;
    const auto period_ns = std::chrono::nanoseconds(static_cast<std::int64_t>(options.controller.period * 1e9));
    auto next = Clock::now() + period_ns;
    while (!stop) {
      {
        std::lock_guard<std::mutex> lock(mutex);
        accept_all();
        for (RtdeClient& c : rtde_clients) serve(c);
        for (TextClient& c : script_clients) serve_script(c);
        for (TextClient& c : dashboard_clients) serve_dashboard(c);
        remove_closed(rtde_clients);
        remove_closed(script_clients);
        remove_closed(dashboard_clients);
        if (!options.lockstep && Clock::now() >= next) {
          period();
          next += period_ns;
        }
      }
      std::this_thread::sleep_for(std::chrono::microseconds(options.lockstep ? 50 : 100));
    }
  }
};

UrEmulator::UrEmulator(Options options) : impl_(std::make_unique<Impl>(std::move(options))) {
  impl_->thread = std::thread([this] { impl_->run(); });
}

UrEmulator::~UrEmulator() {
  impl_->stop = true;
  if (impl_->thread.joinable()) impl_->thread.join();
}

std::uint16_t UrEmulator::rtde_port() const { return impl_->rtde_listener.port(); }
std::uint16_t UrEmulator::script_port() const { return impl_->script_listener.port(); }
std::uint16_t UrEmulator::dashboard_port() const { return impl_->dashboard_listener.port(); }

UrEmulator::Counters UrEmulator::counters() const {
  std::lock_guard<std::mutex> lock(impl_->mutex);
  return impl_->counters;
}

void UrEmulator::protective_stop(const std::string& why) {
  std::lock_guard<std::mutex> lock(impl_->mutex);
  impl_->controller.protective_stop(why);
}

void UrEmulator::drop_connections() {
  std::lock_guard<std::mutex> lock(impl_->mutex);
  impl_->rtde_clients.clear();
  impl_->script_clients.clear();
  impl_->dashboard_clients.clear();
}

void UrEmulator::silence_dashboard() {
  std::lock_guard<std::mutex> lock(impl_->mutex);
  impl_->dashboard_silent = true;
}

void UrEmulator::delay_outputs(int periods) {
  std::lock_guard<std::mutex> lock(impl_->mutex);
  impl_->delay_periods = periods;
}

void UrEmulator::send_malformed() {
  std::lock_guard<std::mutex> lock(impl_->mutex);
  impl_->malformed_next = true;
}

JointVector UrEmulator::true_q() const {
  std::lock_guard<std::mutex> lock(impl_->mutex);
  return impl_->controller.true_q();
}

rtde::SafetyMode UrEmulator::safety_mode() const {
  std::lock_guard<std::mutex> lock(impl_->mutex);
  return impl_->controller.safety_mode();
}

rtde::follow::ProgramState UrEmulator::program_state() const {
  std::lock_guard<std::mutex> lock(impl_->mutex);
  return impl_->controller.program_state();
}

}  // namespace wysiwyf::robot::ur
