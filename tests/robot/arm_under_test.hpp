#pragma once
// One arm component (arm_sim, puma_driver, ur_driver) in a Harness on the sim clock: feeds it
// setpoints and requests, records every joint state it publishes and its newest status. The
// drivers' tests run a driver and arm_sim side by side through it and compare what they record.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "wysiwyf/harness.hpp"
#include "wysiwyf/msg_eigen.hpp"

namespace wysiwyf::test {

// A Cartesian setpoint of the plate (base_T_dev) with its linear velocity, from "test".
inline msg::CartesianSetpoint setpoint(std::int64_t stamp_ns, const Eigen::Isometry3d& T,
                                       const Eigen::Vector3d& v = Eigen::Vector3d::Zero()) {
  msg::CartesianSetpoint s;
  s.header().stamp_ns(stamp_ns);
  s.header().frame_id("base");
  s.child_frame_id("dev");
  msgs::to_msg(T, s.pose());
  msgs::to_msg(v, Eigen::Vector3d::Zero(), s.twist());
  s.source("test");
  return s;
}

// The setpoint due at `ms`, if any: a 3 cm circle at 0.5 Hz around `parked` (the plate's pose)
// streamed every `period_ms`, after a 4 cm step along y held for the first second.
inline bool circle_setpoint_at(int ms, int period_ms, const Eigen::Isometry3d& parked, msg::CartesianSetpoint& out) {
  if (ms % period_ms != 0) return false;
  constexpr double kPi = 3.14159265358979323846;
  constexpr std::int64_t kMs = 1'000'000;
  Eigen::Isometry3d T = parked;
  const double t = ms * 1e-3;
  T.translation() += Eigen::Vector3d(0, 0.04, 0);
  if (t < 1.0) {
    out = setpoint(ms * kMs, T);
    return true;
  }
  const double w = 2 * kPi * 0.5, s = t - 1.0;
  T.translation() += 0.03 * Eigen::Vector3d(0, std::sin(w * s), 1 - std::cos(w * s));
  out = setpoint(ms * kMs, T, 0.03 * w * Eigen::Vector3d(0, std::cos(w * s), std::sin(w * s)));
  return true;
}

struct ArmUnderTest {
  Harness h;
  Output<msg::CartesianSetpoint> sp;
  Output<msg::ArmRequest> request;
  Input<msg::JointState> js;
  Input<msg::RobotStatus> status;
  msg::RobotStatus last_status;
  std::vector<msgs::Vector6d> q, qd, effort;  // one per joint state published (six-joint arms)
  std::int64_t t = 0;                         // the next tick's time, ns
  std::int64_t period_ns;
  int published = 0;  // joint states published by the last tick

  ArmUnderTest(const std::string& type, const std::string& params, double rate_hz = 1000)
      : h(type, params, rate_hz),
        sp(h.feed<msg::CartesianSetpoint>("setpoint")),
        request(h.feed<msg::ArmRequest>("request")),
        js(h.watch<msg::JointState>("joint_state", 4)),
        status(h.watch<msg::RobotStatus>("status", 64)),
        period_ns(static_cast<std::int64_t>(1e9 / rate_hz + 0.5)) {
    h.activate();
  }
  // One tick, with a setpoint written before it when given.
  void tick(const msg::CartesianSetpoint* s = nullptr) {
    if (s) sp.write(*s);
    h.tick(Time{t});
    t += period_ns;
    msg::JointState j;
    published = 0;
    while (js.take(j)) {
      ++published;
      msgs::Vector6d a, b, c;
      for (std::size_t k = 0; k < 6; ++k) a[k] = j.position()[k], b[k] = j.velocity()[k], c[k] = j.effort()[k];
      q.push_back(a), qd.push_back(b), effort.push_back(c);
    }
    while (status.take(last_status)) {
    }
  }
  // The supervisor's request to clear an input fault, stamped now.
  void clear(const std::string& why) {
    msg::ArmRequest r;
    r.header().stamp_ns(t);
    r.request(msg::ARM_CLEAR_INPUT_FAULT);
    r.reason(why);
    request.write(r);
  }
  int state() const { return static_cast<int>(last_status.state()); }
  std::string source() const { return last_status.source().c_str(); }
  std::string reason() const { return last_status.reason().c_str(); }
};

// The largest differences between two recordings, sample by sample, and how far the first moved.
struct Difference {
  double q = 0, qd = 0, effort = 0;  // rad, rad/s, N m
  double travel = 0;                 // rad: the first arm's largest joint excursion from its start
};

inline Difference compare(const ArmUnderTest& a, const ArmUnderTest& b) {
  Difference d;
  for (std::size_t i = 0; i < std::min(a.q.size(), b.q.size()); ++i) {
    d.q = std::max(d.q, (a.q[i] - b.q[i]).cwiseAbs().maxCoeff());
    d.qd = std::max(d.qd, (a.qd[i] - b.qd[i]).cwiseAbs().maxCoeff());
    d.effort = std::max(d.effort, (a.effort[i] - b.effort[i]).cwiseAbs().maxCoeff());
    d.travel = std::max(d.travel, (a.q[i] - a.q[0]).cwiseAbs().maxCoeff());
  }
  return d;
}

}  // namespace wysiwyf::test
