// arm_sim: the display's arm, simulated, behind the same safety gate as the real arm: the PUMA
// 560 by default, or any serial arm of up to kMaxArmDof joints from its URDF (`urdf`, with the
// ft_sensor and dev frames fixed to its last link; `drive` empty for ideal drives; `initial_q` and
// `acceleration_limits` of one value per joint).
//
// Every tick (1 kHz, the Unimation servo rate):
//   1. sample: encoder-quantised joint angles, joint velocities, the F/T sensor (hand contact +
//      tool weight + Gaussian noise + bias), FK of the measured joints; publish them;
//   2. the safety gate checks the measurements (limits, overspeed, following error, force);
//   3. trajectory generator (RCCL style): each Cartesian setpoint (base_T_dev + twist, at any
//      period from 1 to 20 ms) passes the gate's screening, is extrapolated by its twist and
//      followed by a critically damped second-order tracker (continuous velocity whatever the
//      setpoint period), whose pose goes through ik_nearest to a joint target;
//   4. the gate turns the joint target into a bounded reference (limits, watchdog, faults);
//   5. joint servo: PD + gravity compensation on the reference (the Unimation servo) plus, by
//      default, inverse-dynamics and friction feedforward; torques saturated at the effort limits;
//   6. the arm (forward dynamics with reflected rotor inertia, viscous + smoothed Coulomb
//      friction) and the user's fingertip (a sphere on an impedance towards `hand_target`, in
//      penalty contact with the plate, the knob and the sensor housing, the reaction applied to
//      the last link through the Jacobian transpose) advance by semi-implicit Euler substeps.
#include <array>
#include <cmath>
#include <memory>
#include <random>
#include <stdexcept>
#include <vector>

#include "arm_interface/arm_params.hpp"
#include "arm_interface/arm_ports.hpp"
#include "arm_joint_sim/arm_dynamics.hpp"
#include "arm_joint_sim/drive_params.hpp"
#include "arm_joint_sim/joint_servo.hpp"
#include "arm_model/arm_model.hpp"
#include "safety_gate/safety_gate.hpp"
#include "setpoint_following/setpoint_follower.hpp"
#include "tool_geometry.hpp"
#include "wysiwyf/component.hpp"
#include "wysiwyf/config_files.hpp"
#include "wysiwyf/msg_checks.hpp"
#include "wysiwyf/msg_eigen.hpp"
#include "wysiwyf/msgs.hpp"

namespace wysiwyf::robot::sim {
namespace {

// The PUMA 560's ready pose: the plate's centre 0.7 m in front of the base, 0.2 m above the
// mounting plane (the table top of config/scenes), facing +x (away from the robot, towards the
// user), dev x pointing down: base_T_dev = (0.7, 0, 0.2), Ry(pi/2). The one IK solution within
// limits.
const std::vector<double> kPumaReadyPose = {0.255486131, -0.152351627, -2.593612368,
                                            0.275843098, 1.188686600,  -0.105157403};

// Per-joint lists: up to kMaxArmDof values (the URDF's joint count is checked once it is loaded).
const Length kPerJoint{1, static_cast<std::size_t>(kMaxArmDof), 1, false};
const Length kPerJointOrNone{1, static_cast<std::size_t>(kMaxArmDof), 1, true};

}  // namespace

class ArmSim final : public Component {
 public:
  void configure(Context& ctx) override {
    ctx.summary(
        "simulated arm (the PUMA 560, or any serial arm's URDF): arm dynamics, 1 kHz joint servo behind the safety "
        "gate, Cartesian setpoint tracking, wrist F/T sensor and the user's fingertip in contact with the plate");
    // ---- the robot, the setpoint tracker and the safety gate (as puma_driver)
    arm_ = declare_arm_params(ctx);
    drive_path_ = ctx.param<std::string>(
        "drive", "robots/puma560_drive.yaml",
        "drive-train file naming the URDF's joints (gears, rotor inertia, friction); same search as urdf. Empty: "
        "ideal drives (no rotor inertia, no drive friction, joints read without encoder quantisation), for arms "
        "whose makers publish no motor data");
    sensor_frame_ = ctx.param<std::string>("sensor_frame", "ft_sensor", "the F/T sensor's measurement frame");
    q0_list_ = ctx.param<std::vector<double>>("initial_q", kPumaReadyPose,
                                              "joint angles at activation, rad, one per joint of the URDF (default: "
                                              "the PUMA 560's ready pose, plate centre at (0.7, 0, 0.2) m facing +x)",
                                              Range{-10, 10}, kPerJoint);
    // ---- the servo
    servo_config_.bandwidth_hz =
        ctx.param<double>("servo_bandwidth_hz", 10.0,
                          "PD gains from M(q0): kp = M_jj w^2, kd = 2 zeta M_jj w, w = 2 pi this, Hz", Range{0.1, 100});
    servo_config_.damping =
        ctx.param<double>("servo_damping", 1.0, "damping ratio zeta of the derived PD gains", Range{0.05, 10});
    servo_config_.kp = ctx.param<std::vector<double>>(
        "servo_kp", {}, "explicit position gains, N m/rad, one per joint (empty: derived)", Range{0, 1e7},
        kPerJointOrNone);
    servo_config_.kd = ctx.param<std::vector<double>>("servo_kd", {},
                                                      "explicit velocity gains, N m s/rad, one per joint (empty: "
                                                      "derived)",
                                                      Range{0, 1e6}, kPerJointOrNone);
    servo_config_.accel_feedforward =
        ctx.param<double>("accel_feedforward", 1.0,
                          "share of the inverse-dynamics feedforward M(q) qdd_ref + C(q, qd) qd added to the "
                          "torque (0 with friction_feedforward 0: PD + gravity only, the Unimation servo)",
                          Range{0, 1});
    servo_config_.friction_feedforward =
        ctx.param<double>("friction_feedforward", 1.0,
                          "share of the drive friction model at the measured velocity added to the torque while the "
                          "reference moves",
                          Range{0, 1});
    substeps_ = ctx.param<int>("substeps", 4, "semi-implicit Euler steps of the arm and hand per tick", Range{1, 100});
    encoder_counts_ = ctx.param<int>("encoder_counts", 1000,
                                     "encoder counts per motor revolution after quadrature (0: no quantisation); joint "
                                     "quantum 2 pi / (counts |gear|)",
                                     Range{0, 10000000});
    servo_config_.coulomb_smoothing = ctx.param<double>(
        "coulomb_smoothing", 0.01, "rad/s joint velocity over which Coulomb friction turns (tanh)", Range{1e-6, 1});
    // ---- F/T sensor
    noise_force_ =
        ctx.param<double>("ft_noise_force", 0.05, "N, sigma of the Gaussian noise per force axis", Range{0, 100});
    noise_torque_ =
        ctx.param<double>("ft_noise_torque", 0.002, "N m, sigma of the Gaussian noise per torque axis", Range{0, 10});
    const auto bias = ctx.param<std::array<double, 6>>(
        "ft_bias", {0, 0, 0, 0, 0, 0}, "constant offset of the F/T reading: fx fy fz (N) tx ty tz (N m)",
        Range{-1000, 1000});
    seed_ = ctx.param<std::int64_t>("seed", 1, "seed of the sensor noise (runs are repeatable)");
    // ---- the user's fingertip
    hand_mass_ = ctx.param<double>("hand_mass", 0.5, "kg, the fingertip's moving mass", Range{0.01, 20});
    hand_radius_ = ctx.param<double>("hand_radius", 0.01, "m, the fingertip sphere's radius", Range{0.001, 0.1});
    hand_k_ = ctx.param<double>("hand_stiffness", 500.0, "N/m, impedance pulling the fingertip to hand_target",
                                Range{0, 1e5});
    hand_d_ = ctx.param<double>("hand_damping", 30.0, "N s/m, damping of the fingertip's impedance", Range{0, 1e4});
    const auto park = ctx.param<std::array<double, 3>>(
        "hand_park", {1.1, 0.0, 0.2}, "where the fingertip waits until a hand_target arrives, base frame, m",
        Range{-10, 10});
    contact_k_ =
        ctx.param<double>("contact_stiffness", 20000.0, "N/m, penalty stiffness of fingertip contact", Range{1, 1e7});
    contact_d_ = ctx.param<double>("contact_damping", 100.0,
                                   "N s/m, penalty damping of fingertip contact (pushes only)", Range{0, 1e5});

    ports_.declare(ctx, {[this](const auto& in, const std::string& why) { reject(in, why); },
                         [this](const auto& in, const std::string& why) { reject(in, why); },
                         [this](const std::string& line) { log(line); }});
    hand_in_ = ctx.input<msg::PoseStamped>(
        "hand_target", "where the user's fingertip is driven, and the hand's orientation", Qos::reliable(4));
    wrench_out_ =
        ctx.output<msg::WrenchStamped>("wrench", "wrist F/T sensor, frame ft_sensor, about its origin", Qos::sensor(8));
    hand_out_ = ctx.output<msg::PoseStamped>(
        "hand_pose", "base_T_fingertip: the fingertip's true position, oriented as the target (x along the finger)");

    bias_ = Eigen::Map<const Vector6d>(bias.data());
    park_ = Eigen::Vector3d(park[0], park[1], park[2]);
    dt_ = arm_.gate.dt;

    // Load now so that a wrong file or frame is reported before anything starts.
    model_ = load_arm_model(ctx, arm_);
    if (!model_) return;
    tip_ = model_->tip();
    const int n = model_->dof();
    if (q0_list_.size() != static_cast<std::size_t>(n))
      return ctx.reject("initial_q", "needs one angle per joint of " + arm_.urdf_path + ": " + std::to_string(n) +
                                         " values, got " + std::to_string(q0_list_.size()));
    q0_ = Eigen::Map<const Eigen::VectorXd>(q0_list_.data(), n);
    const auto gains_fit = [&](const char* name, const std::vector<double>& gains) {
      if (gains.empty() || gains.size() == static_cast<std::size_t>(n)) return true;
      ctx.reject(name, "needs one gain per joint of " + arm_.urdf_path + ": " + std::to_string(n) +
                           " values (or none), got " + std::to_string(gains.size()));
      return false;
    };
    if (!gains_fit("servo_kp", servo_config_.kp) || !gains_fit("servo_kd", servo_config_.kd)) return;
    try {
      drive_ = drive_path_.empty() ? DriveParams::ideal(n)
                                   : load_drive_params(find_config_file(drive_path_), model_->joint_names());
    } catch (const std::exception& e) {
      return ctx.reject("drive", e.what());
    }
    model_->set_rotor_inertia(drive_.reflected_inertia());
    try {
      sensor_ = model_->frame(sensor_frame_);
      tool_ = load_tool_geometry(find_config_file(arm_.urdf_path), *model_, sensor_frame_);
    } catch (const std::exception& e) {
      return ctx.reject("sensor_frame", e.what());
    }
    const ArmLimits& limits = model_->limits();
    for (int j = 0; j < n; ++j)
      if (q0_[j] < limits.lower[j] || q0_[j] > limits.upper[j])
        return ctx.reject("initial_q", "joint " + std::to_string(j + 1) + " (" + model_->joint_names()[j] + ") at " +
                                           std::to_string(q0_[j]) + " rad is outside its limits [" +
                                           std::to_string(limits.lower[j]) + ", " + std::to_string(limits.upper[j]) +
                                           "] of " + arm_.urdf_path);
    servo_ = std::make_unique<JointServo>(*model_, drive_, servo_config_, q0_);
    arm_dynamics_ = std::make_unique<ArmDynamics>(*model_, drive_, encoder_counts_, servo_config_.coulomb_smoothing);
  }

  void activate() override {
    arm_dynamics_->reset(q0_);
    tau_ = model_->gravity_torques(q0_);
    hand_x_ = hand_target_ = park_;
    hand_v_ = Eigen::Vector3d::Zero();
    rng_.seed(static_cast<std::uint64_t>(seed_));
    gate_ = std::make_unique<SafetyGate>(arm_.gate);
    follower_ = std::make_unique<SetpointFollower>(*model_, arm_.tip_frame, *gate_, arm_.tracker_hz, dt_);
    ports_.reset_status();
    started_ = false;
    seq_ = 0;
  }

  void tick(Time now) override {
    // ---- 1. sample and publish
    const JointVector q_meas = arm_dynamics_->measured_q();
    const JointVector qd_meas = arm_dynamics_->qd();
    const Contacts contacts = contact_forces(arm_dynamics_->q(), arm_dynamics_->qd());
    Eigen::Vector3d f_sensor, t_sensor;
    sensor_reading(contacts, f_sensor, t_sensor);
    publish(now, q_meas, qd_meas, f_sensor, t_sensor);

    if (!started_) {  // the gate starts from the first measurement
      gate_->reset(q_meas, now.ns);
      started_ = true;
    }
    // ---- 2. the gate checks the measurements
    gate_->check_measured(q_meas, qd_meas);
    gate_->check_wrench(f_sensor, t_sensor);

    // ---- 3. setpoints, hand target, trajectory generator
    ports_.take_requests(*gate_, now.ns);
    ports_.take_setpoints(arm_, *follower_, now.ns);
    while (hand_in_.take(hand_msg_)) {
      const Eigen::Vector3d x = msgs::to_eigen(hand_msg_.pose().position());
      Eigen::Quaterniond q = msgs::to_eigen(hand_msg_.pose().orientation());
      q = q.norm() > 1e-6 ? q.normalized() : Eigen::Quaterniond::Identity();  // (a position only: unturned)
      // (a finite 1e308 would overflow the hand's spring force to infinity)
      if (x.allFinite() && q.coeffs().allFinite() && x.cwiseAbs().maxCoeff() <= msgs::kMaxMagnitude)
        hand_target_ = x, hand_q_ = q;  // the hand turns as the user turns it; only the fingertip touches
      else
        reject(hand_in_, "a non-finite pose or a position beyond 1e4 m");
    }
    follower_->update(now.ns);

    // ---- 4. the reference, 5. the servo
    // PD on the reference for now (the last step's result), feedforward of the acceleration that
    // takes the reference to now + dt.
    const JointVector ref_q = gate_->reference().q, ref_qd = gate_->reference().qd;
    const JointReference& ref = gate_->step(now.ns);
    tau_ = servo_->torque(q_meas, qd_meas, ref_q, ref_qd, ref.qdd);

    // ---- 6. the arm and the hand over one period
    const double h = dt_ / substeps_;
    for (int s = 0; s < substeps_; ++s) {
      const Contacts c = s == 0 ? contacts : contact_forces(arm_dynamics_->q(), arm_dynamics_->qd());
      const Eigen::Vector3d f_hand =
          hand_k_ * (hand_target_ - hand_x_) - hand_d_ * hand_v_ + c.on_hand;  // no gravity: the user carries it
      arm_dynamics_->step(h, tau_, c.joint_torque);
      hand_v_ += f_hand / hand_mass_ * h;
      hand_x_ += hand_v_ * h;
    }
    ports_.publish_status(now.ns, *gate_, follower_->source());
    report_health(ports_.health(*gate_), gate_->reason());  // the kernel logs the changes
  }

  void deactivate() override {
    if (gate_) ports_.log_bursts(*gate_);
  }

  void hold() noexcept override {
    try {
      if (gate_) gate_->fault("hold: the pipeline stopped on a fault");
    } catch (...) {
    }
  }

 private:
  struct Contacts {
    Eigen::Vector3d on_hand = Eigen::Vector3d::Zero();          // force on the fingertip, base frame
    JointVector joint_torque;                                   // the reaction on the arm, at the joints
    Eigen::Vector3d measured_force = Eigen::Vector3d::Zero();   // on the parts beyond the sensor, base frame
    Eigen::Vector3d measured_torque = Eigen::Vector3d::Zero();  // about the sensor origin, base frame
    Eigen::Isometry3d base_T_sensor = Eigen::Isometry3d::Identity();
  };

  Contacts contact_forces(const JointVector& q, const JointVector& qd) const {
    Contacts out;
    out.joint_torque.setZero(q.size());
    out.base_T_sensor = model_->fk(q, sensor_);
    const Eigen::Vector3d o = out.base_T_sensor.translation();
    if ((hand_x_ - o).norm() > tool_.bounding_radius + hand_radius_) return out;
    ArmJacobian J;
    bool have_jacobian = false;
    for (const ContactShape& shape : tool_.shapes) {
      double depth;
      Eigen::Vector3d n, point;
      if (!sphere_contact(shape, out.base_T_sensor * shape.sensor_T_shape, hand_x_, hand_radius_, depth, n, point))
        continue;
      if (!have_jacobian) {
        J = model_->jacobian(q, sensor_);
        have_jacobian = true;
      }
      const Vector6d twist = J * qd;  // of the sensor origin
      const Eigen::Vector3d r = point - o;
      const Eigen::Vector3d v_point = twist.head<3>() + twist.tail<3>().cross(r);
      const double depth_rate = -(hand_v_ - v_point).dot(n);
      const double f = std::max(0.0, contact_k_ * depth + contact_d_ * depth_rate);
      if (f == 0.0) continue;
      const Eigen::Vector3d on_device = -f * n;
      out.on_hand += f * n;
      Vector6d wrench;
      wrench.head<3>() = on_device;
      wrench.tail<3>() = r.cross(on_device);
      out.joint_torque += J.transpose() * wrench;
      if (shape.measured) {
        out.measured_force += on_device;
        out.measured_torque += r.cross(on_device);
      }
    }
    return out;
  }

  // What the sensor reports in its own frame about its origin: the load on its tool side (contact
  // + the weight of what it carries), plus bias and noise.
  void sensor_reading(const Contacts& c, Eigen::Vector3d& force, Eigen::Vector3d& torque) {
    const Eigen::Matrix3d R = c.base_T_sensor.linear();
    const Eigen::Vector3d weight = tool_.sensor_mass * standard_gravity();
    const Eigen::Vector3d com = R * tool_.sensor_com;  // from the sensor origin, base axes
    force = R.transpose() * (c.measured_force + weight);
    torque = R.transpose() * (c.measured_torque + com.cross(weight));
    for (int i = 0; i < 3; ++i) {
      force[i] += bias_[i] + (noise_force_ > 0.0 ? noise_force_ * normal_(rng_) : 0.0);
      torque[i] += bias_[3 + i] + (noise_torque_ > 0.0 ? noise_torque_ * normal_(rng_) : 0.0);
    }
  }

  void publish(Time now, const JointVector& q, const JointVector& qd, const Eigen::Vector3d& f,
               const Eigen::Vector3d& t) {
    ports_.publish_measurement(now.ns, seq_, q, qd, tau_, arm_.tip_frame, model_->fk(q, tip_));

    fill_header(wrench_msg_.header(), now.ns, seq_, sensor_frame_.c_str());
    msgs::to_msg(f, t, wrench_msg_.wrench());
    wrench_out_.write(wrench_msg_);

    fill_header(hand_msg_out_.header(), now.ns, seq_, "base");
    hand_msg_out_.child_frame_id("hand");
    Eigen::Isometry3d hand = Eigen::Isometry3d::Identity();
    hand.linear() = hand_q_.toRotationMatrix();
    hand.translation() = hand_x_;
    msgs::to_msg(hand, hand_msg_out_.pose());
    hand_out_.write(hand_msg_out_);
    ++seq_;
  }

  // parameters
  ArmParams arm_;
  std::string drive_path_, sensor_frame_;
  std::vector<double> q0_list_;
  JointVector q0_;
  Vector6d bias_ = Vector6d::Zero();  // fx fy fz tx ty tz
  JointServoConfig servo_config_;
  int substeps_ = 4, encoder_counts_ = 1000;
  double noise_force_ = 0.05, noise_torque_ = 0.002;
  std::int64_t seed_ = 1;
  double hand_mass_ = 0.5, hand_radius_ = 0.01, hand_k_ = 500, hand_d_ = 30, contact_k_ = 2e4, contact_d_ = 100;
  Eigen::Vector3d park_ = Eigen::Vector3d::Zero();
  double dt_ = 1e-3;

  // model
  std::unique_ptr<ArmModel> model_;
  DriveParams drive_;
  ToolGeometry tool_;
  FrameId tip_, sensor_;
  std::unique_ptr<JointServo> servo_;

  // state
  std::unique_ptr<ArmDynamics> arm_dynamics_;
  JointVector tau_;
  Eigen::Vector3d hand_x_ = Eigen::Vector3d::Zero(), hand_v_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d hand_target_ = Eigen::Vector3d::Zero();
  Eigen::Quaterniond hand_q_ = Eigen::Quaterniond::Identity();  // the hand's orientation (as the target's)
  std::unique_ptr<SafetyGate> gate_;
  std::unique_ptr<SetpointFollower> follower_;
  bool started_ = false;
  std::mt19937_64 rng_;
  std::normal_distribution<double> normal_{0.0, 1.0};
  std::uint64_t seq_ = 0;

  // messages and ports (reused: no allocation per tick)
  msg::PoseStamped hand_msg_, hand_msg_out_;
  msg::WrenchStamped wrench_msg_;
  ArmPorts ports_;
  Input<msg::PoseStamped> hand_in_;
  Output<msg::WrenchStamped> wrench_out_;
  Output<msg::PoseStamped> hand_out_;
};

}  // namespace wysiwyf::robot::sim

WYSIWYF_COMPONENT(wysiwyf::robot::sim::ArmSim, "arm_sim")
