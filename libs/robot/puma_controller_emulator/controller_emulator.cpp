#include "puma_controller_emulator/controller_emulator.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstring>
#include <mutex>
#include <stdexcept>
#include <tuple>

#include "arm_joint_sim/arm_dynamics.hpp"
#include "arm_joint_sim/drive_params.hpp"
#include "arm_model/arm_model.hpp"
#include "wysiwyf/config_files.hpp"

namespace wysiwyf::robot::link {

ControllerEmulator::Options::Options() {
  // arm_sim's ready pose (plate centre at (0.7, 0, 0.2) m facing +x).
  initial_q << 0.255486131, -0.152351627, -2.593612368, 0.275843098, 1.188686600, -0.105157403;
}

namespace {

// The joints puma-link carries: the PUMA 560's six.
constexpr int kJoints = static_cast<int>(std::tuple_size<Joints>::value);

}  // namespace

struct ControllerEmulator::Impl {
  Options options;
  ArmModel model;
  DriveParams drive;
  JointServo servo;
  ArmDynamics arm;
  int socket = -1;
  std::uint16_t port = 0;
  std::thread thread;
  std::atomic<bool> stop{false}, silent{false};
  mutable std::mutex mutex;  // guards counters and the arm between periods
  Counters counters;

  // The reference the servo follows and the controller's own state.
  JointVector ref_q, ref_qd, ref_qdd;
  JointVector tau;
  Status status = Status::kHolding;
  Fault fault = Fault::kNone;
  bool latched = false;
  bool have_command = false;
  std::uint32_t last_command = 0, ack = 0, state_sequence = 0;
  sockaddr_in client{};
  bool have_client = false;

  // The arm of puma-link's six joints (std::runtime_error otherwise).
  static ArmModel load_arm(const Options& o) {
    ArmModel m(find_config_file(o.urdf), "flange");
    if (m.dof() != kJoints)
      throw std::runtime_error("puma-link emulator: " + o.urdf + " has " + std::to_string(m.dof()) +
                               " joints; puma-link carries " + std::to_string(kJoints));
    return m;
  }
  // The drive file's parameters (empty: ideal drives); the model gets their reflected rotor
  // inertia (the servo's gains come from its M(q)).
  static DriveParams load_drive(const Options& o, ArmModel& m) {
    DriveParams d =
        o.drive.empty() ? DriveParams::ideal(m.dof()) : load_drive_params(find_config_file(o.drive), m.joint_names());
    m.set_rotor_inertia(d.reflected_inertia());
    return d;
  }

  explicit Impl(Options o)
      : options(std::move(o)),
        model(load_arm(options)),
        drive(load_drive(options, model)),
        servo(model, drive, options.servo, options.initial_q),
        arm(model, drive, options.encoder_counts, options.servo.coulomb_smoothing) {
    if (!model.limits().within(options.initial_q))
      throw std::runtime_error("puma-link emulator: the initial joint angles are outside the limits of " +
                               options.urdf);
    if (!(options.period > 0.0) || options.substeps < 1 || options.timeout_periods < 1)
      throw std::runtime_error("puma-link emulator: period, substeps and timeout_periods must be positive");
    arm.reset(options.initial_q);
    hold_here();
    tau = model.gravity_torques(options.initial_q);
  }

  void hold_here() {
    ref_q = arm.measured_q();
    ref_qd = ref_qdd = JointVector::Zero(kJoints);
  }

  // Checks a command as a real controller would; false (and a latched fault) when it is refused.
  bool acceptable(const Command& c) {
    const ArmLimits& lim = model.limits();
    for (int j = 0; j < kJoints; ++j) {
      const double q = c.q[static_cast<std::size_t>(j)], qd = c.qd[static_cast<std::size_t>(j)];
      if (q < lim.lower[j] || q > lim.upper[j]) {
        fault = Fault::kJointLimit;
        return false;
      }
      // One period of the velocity limit (with slack for a reference restarting from a hold).
      const double max_step = lim.velocity[j] * options.period * 1.5 + 5e-3;
      if (std::abs(q - ref_q[j]) > max_step || std::abs(qd) > lim.velocity[j]) {
        fault = Fault::kBadCommand;
        return false;
      }
    }
    return true;
  }

  void apply(const Command& c) {
    ack = c.sequence;
    if (c.reset_fault && latched) {
      latched = false;
      fault = Fault::kNone;
      hold_here();
    }
    if (c.query) {
      ++counters.queries;
      return;
    }
    ++counters.commands_applied;
    if (latched) return;  // holding until a reset
    if (c.hold) {
      if (status != Status::kHolding || fault != Fault::kNone) hold_here();
      status = Status::kHolding;
      fault = Fault::kNone;
      return;
    }
    if (!acceptable(c)) {
      ++counters.rejected;
      latched = true;
      status = Status::kFault;
      hold_here();
      return;
    }
    for (int j = 0; j < kJoints; ++j) {
      const auto k = static_cast<std::size_t>(j);
      ref_q[j] = c.q[k], ref_qd[j] = c.qd[k], ref_qdd[j] = c.qdd[k];
    }
    status = Status::kOk;
    fault = Fault::kNone;
  }

  // One servo period: measure, servo, integrate.
  void advance() {
    tau = servo.torque(arm.measured_q(), arm.qd(), ref_q, ref_qd, ref_qdd);
    const double h = options.period / options.substeps;
    const JointVector no_contact = JointVector::Zero(kJoints);
    for (int s = 0; s < options.substeps; ++s) arm.step(h, tau, no_contact);
    if (status != Status::kOk) ref_qdd.setZero();
  }

  void send_state() {
    if (!have_client || silent) return;
    State s;
    s.sequence = state_sequence++;
    s.ack = ack;
    s.status = latched ? Status::kFault : status;
    s.fault = fault;
    const JointVector q = arm.measured_q();
    for (int j = 0; j < kJoints; ++j) {
      const auto k = static_cast<std::size_t>(j);
      s.q[k] = q[j], s.qd[k] = arm.qd()[j], s.tau[k] = tau[j];
    }
    const auto bytes = encode(s);
    if (::sendto(socket, bytes.data(), bytes.size(), 0, reinterpret_cast<const sockaddr*>(&client), sizeof client) > 0)
      ++counters.states_sent;
  }

  // Reads one datagram if there is one within `timeout`; returns true and fills `c` for a valid,
  // newer command.
  bool receive(std::chrono::nanoseconds timeout, Command& c) {
    pollfd pfd{socket, POLLIN, 0};
    const auto ns = std::max<std::int64_t>(0, timeout.count());
    const timespec ts{static_cast<time_t>(ns / 1'000'000'000), static_cast<long>(ns % 1'000'000'000)};
    if (::ppoll(&pfd, 1, &ts, nullptr) <= 0) return false;
    std::uint8_t buffer[512];
    sockaddr_in from{};
    socklen_t len = sizeof from;
    const ssize_t n = ::recvfrom(socket, buffer, sizeof buffer, MSG_DONTWAIT, reinterpret_cast<sockaddr*>(&from), &len);
    if (n <= 0 || silent) return false;
    if (decode(buffer, static_cast<std::size_t>(n), c) != DecodeError::kNone) {
      ++counters.dropped_damaged;
      return false;
    }
    const bool new_client =
        !have_client || from.sin_port != client.sin_port || from.sin_addr.s_addr != client.sin_addr.s_addr;
    // A new host (or the same one restarted) starts its own sequence: accept it.
    if (!new_client && have_command && !newer(c.sequence, last_command)) {
      ++counters.dropped_stale;
      return false;
    }
    client = from;
    have_client = true;
    have_command = true;
    last_command = c.sequence;
    return true;
  }

  void run_lockstep() {
    Command c;
    while (!stop) {
      if (!receive(std::chrono::milliseconds(20), c)) continue;
      std::lock_guard<std::mutex> lock(mutex);
      apply(c);
      if (!c.query) advance();
      send_state();
    }
  }

  void run_real_time() {
    using Clock = std::chrono::steady_clock;
    const auto period = std::chrono::nanoseconds(static_cast<std::int64_t>(std::llround(options.period * 1e9)));
    auto next = Clock::now() + period;
    int periods_without_command = 0;
    Command c;
    while (!stop) {
      bool got = false;
      Command newest;
      for (;;) {  // everything that arrived before this period's deadline; the newest command wins
        if (!receive(next - Clock::now(), c)) {
          if (Clock::now() >= next) break;
          continue;
        }
        if (c.query) {
          std::lock_guard<std::mutex> lock(mutex);
          apply(c);
          send_state();  // answered at once: the host is waiting to start
          continue;
        }
        newest = c;
        got = true;
      }
      next += period;
      std::lock_guard<std::mutex> lock(mutex);
      if (got) {
        periods_without_command = 0;
        apply(newest);
      } else if (++periods_without_command == options.timeout_periods && status == Status::kOk) {
        ++counters.timeouts;
        hold_here();  // the host fell silent: hold where the arm is (not latched)
        status = Status::kHolding;
        fault = Fault::kCommandTimeout;
      }
      advance();
      if (periods_without_command < 1000) send_state();  // a host gone for a second is not fed
    }
  }
};

ControllerEmulator::ControllerEmulator(Options options) : impl_(std::make_unique<Impl>(std::move(options))) {
  Impl& m = *impl_;
  m.socket = ::socket(AF_INET, SOCK_DGRAM, 0);
  if (m.socket < 0) throw std::runtime_error(std::string("puma-link emulator: socket: ") + std::strerror(errno));
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(m.options.port);
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);  // loopback only
  if (::bind(m.socket, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0) {
    const std::string why = std::strerror(errno);
    ::close(m.socket);
    throw std::runtime_error("puma-link emulator: cannot bind 127.0.0.1:" + std::to_string(m.options.port) + ": " +
                             why);
  }
  socklen_t len = sizeof addr;
  ::getsockname(m.socket, reinterpret_cast<sockaddr*>(&addr), &len);
  m.port = ntohs(addr.sin_port);
  m.thread = std::thread([&m] { m.options.lockstep ? m.run_lockstep() : m.run_real_time(); });
}

ControllerEmulator::~ControllerEmulator() {
  impl_->stop = true;
  if (impl_->thread.joinable()) impl_->thread.join();
  ::close(impl_->socket);
}

std::uint16_t ControllerEmulator::port() const { return impl_->port; }

ControllerEmulator::Counters ControllerEmulator::counters() const {
  std::lock_guard<std::mutex> lock(impl_->mutex);
  return impl_->counters;
}

void ControllerEmulator::set_silent(bool silent) { impl_->silent = silent; }

Vector6d ControllerEmulator::true_q() const {
  std::lock_guard<std::mutex> lock(impl_->mutex);
  return impl_->arm.q();
}

}  // namespace wysiwyf::robot::link
