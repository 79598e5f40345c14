// puma_sim: the PUMA 560 of the display, simulated, behind the same safety gate as the real arm.
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
//      link 6 through the Jacobian transpose) advance by semi-implicit Euler substeps.
#include <cmath>
#include <memory>
#include <random>
#include <stdexcept>

#include "arm_joint_sim/arm_dynamics.hpp"
#include "arm_joint_sim/joint_servo.hpp"
#include "puma_model/drive_params.hpp"
#include "puma_model/puma_model.hpp"
#include "safety_gate/safety_gate.hpp"
#include "arm_interface/arm_messages.hpp"
#include "arm_interface/gate_params.hpp"
#include "arm_interface/gate_status.hpp"
#include "setpoint_following/setpoint_follower.hpp"
#include "tool_geometry.hpp"
#include "wysiwyf/component.hpp"
#include "wysiwyf/config_files.hpp"
#include "wysiwyf/msg_eigen.hpp"
#include "wysiwyf/msgs.hpp"

namespace wysiwyf::robot::sim {
namespace {

// The ready pose: the plate's centre 0.7 m in front of the base, 0.2 m above the mounting plane
// (the table top of config/scenes), facing +x (away from the robot, towards the user), dev x
// pointing down: base_T_dev = (0.7, 0, 0.2), Ry(pi/2). The one IK solution within limits.
const std::vector<double> kReadyPose = {0.255486131, -0.152351627, -2.593612368, 0.275843098, 1.188686600, -0.105157403};

Vector6d to_vector6(const std::vector<double>& v) {
  Vector6d out;
  for (int j = 0; j < kDof; ++j) out[j] = v[static_cast<std::size_t>(j)];
  return out;
}

}  // namespace

class PumaSim final : public Component {
 public:
  void configure(Context& ctx) override {
    ctx.summary("simulated PUMA 560: arm dynamics, 1 kHz joint servo behind the safety gate, Cartesian setpoint "
                "tracking, wrist F/T sensor and the user's fingertip in contact with the plate");
    // ---- the robot
    urdf_path_ = ctx.param<std::string>("urdf", "robots/puma560.urdf",
                                        "robot URDF; relative paths are tried from the working directory, then config/");
    drive_path_ = ctx.param<std::string>("drive", "robots/puma560_drive.yaml",
                                         "drive-train file (gears, rotor inertia, friction); same search as urdf");
    tip_frame_ = ctx.param<std::string>("tip_frame", "dev", "the frame the Cartesian setpoints place (fixed to link 6)");
    sensor_frame_ = ctx.param<std::string>("sensor_frame", "ft_sensor", "the F/T sensor's measurement frame");
    const auto q0 = ctx.param<std::vector<double>>(
        "initial_q", kReadyPose,
        "joint angles at activation, rad (default: the ready pose, plate centre at (0.7, 0, 0.2) m facing +x)",
        Range{-10, 10});
    // ---- safety gate
    gate_config_ = declare_gate_params(ctx);
    // ---- trajectory generator and servo
    tracker_hz_ = ctx.param<double>("tracker_bandwidth_hz", 10.0,
                                    "natural frequency of the critically damped Cartesian setpoint tracker, Hz",
                                    Range{0.1, 200});
    servo_config_.bandwidth_hz = ctx.param<double>("servo_bandwidth_hz", 10.0,
                                  "PD gains from M(q0): kp = M_jj w^2, kd = 2 zeta M_jj w, w = 2 pi this, Hz",
                                  Range{0.1, 100});
    servo_config_.damping = ctx.param<double>("servo_damping", 1.0, "damping ratio zeta of the derived PD gains", Range{0.05, 10});
    servo_config_.kp = ctx.param<std::vector<double>>("servo_kp", {}, "explicit position gains, N m/rad (empty: derived)",
                                               Range{0, 1e7});
    servo_config_.kd = ctx.param<std::vector<double>>("servo_kd", {}, "explicit velocity gains, N m s/rad (empty: derived)",
                                               Range{0, 1e6});
    servo_config_.accel_feedforward = ctx.param<double>("accel_feedforward", 1.0,
                                  "share of the inverse-dynamics feedforward M(q) qdd_ref + C(q, qd) qd added to the "
                                  "torque (0 with friction_feedforward 0: PD + gravity only, the Unimation servo)",
                                  Range{0, 1});
    servo_config_.friction_feedforward = ctx.param<double>("friction_feedforward", 1.0,
                                     "share of the drive friction model at the measured velocity added to the torque while the "
                                     "reference moves",
                                     Range{0, 1});
    substeps_ = ctx.param<int>("substeps", 4, "semi-implicit Euler steps of the arm and hand per tick", Range{1, 100});
    encoder_counts_ = ctx.param<int>("encoder_counts", 1000,
                                     "encoder counts per motor revolution after quadrature (0: no quantisation); joint "
                                     "quantum 2 pi / (counts |gear|)",
                                     Range{0, 10000000});
    servo_config_.coulomb_smoothing = ctx.param<double>("coulomb_smoothing", 0.01,
                                           "rad/s joint velocity over which Coulomb friction turns (tanh)", Range{1e-6, 1});
    // ---- F/T sensor
    noise_force_ = ctx.param<double>("ft_noise_force", 0.05, "N, sigma of the Gaussian noise per force axis", Range{0, 100});
    noise_torque_ = ctx.param<double>("ft_noise_torque", 0.002, "N m, sigma of the Gaussian noise per torque axis",
                                      Range{0, 10});
    const auto bias = ctx.param<std::vector<double>>("ft_bias", {0, 0, 0, 0, 0, 0},
                                                     "constant offset of the F/T reading: fx fy fz (N) tx ty tz (N m)",
                                                     Range{-1000, 1000});
    seed_ = ctx.param<std::int64_t>("seed", 1, "seed of the sensor noise (runs are repeatable)");
    // ---- the user's fingertip
    hand_mass_ = ctx.param<double>("hand_mass", 0.5, "kg, the fingertip's moving mass", Range{0.01, 20});
    hand_radius_ = ctx.param<double>("hand_radius", 0.01, "m, the fingertip sphere's radius", Range{0.001, 0.1});
    hand_k_ = ctx.param<double>("hand_stiffness", 500.0, "N/m, impedance pulling the fingertip to hand_target",
                                Range{0, 1e5});
    hand_d_ = ctx.param<double>("hand_damping", 30.0, "N s/m, damping of the fingertip's impedance", Range{0, 1e4});
    const auto park = ctx.param<std::vector<double>>(
        "hand_park", {1.1, 0.0, 0.2}, "where the fingertip waits until a hand_target arrives, base frame, m",
        Range{-10, 10});
    contact_k_ = ctx.param<double>("contact_stiffness", 20000.0, "N/m, penalty stiffness of fingertip contact",
                                   Range{1, 1e7});
    contact_d_ = ctx.param<double>("contact_damping", 100.0, "N s/m, penalty damping of fingertip contact (pushes only)",
                                   Range{0, 1e5});

    setpoint_in_ = ctx.input<msg::CartesianSetpoint>("setpoint", "base_T_dev and its twist, at any period of 1-20 ms",
                                                     Qos::reliable(32));
    hand_in_ = ctx.input<msg::PoseStamped>("hand_target", "where the user's fingertip is driven (base frame)",
                                           Qos::reliable(4));
    joint_out_ = ctx.output<msg::JointState>("joint_state", "encoder-quantised angles, velocities, motor torques");
    pose_out_ = ctx.output<msg::PoseStamped>("device_pose", "base_T_dev by FK of the measured joints");
    wrench_out_ = ctx.output<msg::WrenchStamped>("wrench", "wrist F/T sensor, frame ft_sensor, about its origin",
                                                 Qos::sensor(8));
    hand_out_ = ctx.output<msg::PoseStamped>("hand_pose", "the fingertip's true position (base frame)");
    status_out_ = ctx.output<msg::RobotStatus>(
        "status", "safety state (RobotStatus): ok following a source, holding, or fault, with the reason",
        Qos{Reliability::kReliable, Durability::kTransientLocal, 4, 0});

    auto six = [](const std::vector<double>& v, const char* name) {
      if (v.size() != static_cast<std::size_t>(kDof))
        throw std::invalid_argument(std::string(name) + " needs 6 values, one per joint (got " +
                                    std::to_string(v.size()) + ")");
    };
    six(q0, "initial_q");
    six(bias, "ft_bias");
    servo_config_.validate();
    if (park.size() != 3) throw std::invalid_argument("hand_park needs 3 values (x y z, m)");
    q0_ = to_vector6(q0);
    bias_ = to_vector6(bias);
    park_ = Eigen::Vector3d(park[0], park[1], park[2]);
    dt_ = ctx.period_ns() > 0 ? static_cast<double>(ctx.period_ns()) * 1e-9 : 1e-3;
    gate_config_.dt = dt_;

    // Load now so that a wrong file or frame is reported before anything starts.
    model_ = std::make_unique<PumaModel>(find_config_file(urdf_path_), tip_frame_);
    drive_ = load_drive_params(find_config_file(drive_path_), *model_);
    model_->set_rotor_inertia(drive_.reflected_inertia());
    tip_ = model_->tip();
    if (model_->frame_body(tip_) != kDof) throw std::invalid_argument("tip_frame '" + tip_frame_ + "' is not on link 6");
    sensor_ = model_->frame(sensor_frame_);
    tool_ = load_tool_geometry(find_config_file(urdf_path_), *model_, sensor_frame_);
    gate_config_.limits = model_->limits();
    gate_config_.validate();
    if (!model_->limits().within(q0_))
      throw std::invalid_argument("initial_q is outside the joint limits of " + urdf_path_);
    servo_ = std::make_unique<JointServo>(*model_, drive_, servo_config_, q0_);
    arm_ = std::make_unique<ArmDynamics>(*model_, drive_, encoder_counts_, servo_config_.coulomb_smoothing);
  }

  void activate() override {
    arm_->reset(q0_);
    tau_ = model_->gravity_torques(q0_);
    hand_x_ = hand_target_ = park_;
    hand_v_ = Eigen::Vector3d::Zero();
    rng_.seed(static_cast<std::uint64_t>(seed_));
    gate_ = std::make_unique<SafetyGate>(gate_config_);
    follower_ = std::make_unique<SetpointFollower>(*model_, tip_frame_, *gate_, tracker_hz_, dt_);
    status_ = GateStatus();
    started_ = false;
    seq_ = 0;
    rejected_hand_ = 0;
  }

  void tick(Time now) override {
    // ---- 1. sample and publish
    const Vector6d q_meas = arm_->measured_q();
    const Vector6d qd_meas = arm_->qd();
    const Contacts contacts = contact_forces(arm_->q(), arm_->qd());
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
    while (setpoint_in_.take(setpoint_msg_)) follower_->take(setpoint_msg_, now.ns);
    while (hand_in_.take(hand_msg_)) {
      const auto& p = hand_msg_.pose().position();
      const Eigen::Vector3d x(p.x(), p.y(), p.z());
      if (x.allFinite()) {
        hand_target_ = x;
      } else if (++rejected_hand_ == 1) {
        log("ignored a non-finite hand_target (further ones are counted silently)");
      }
    }
    follower_->update(now.ns);

    // ---- 4. the reference, 5. the servo
    // PD on the reference for now (the last step's result), feedforward of the acceleration that
    // takes the reference to now + dt.
    const Vector6d ref_q = gate_->reference().q, ref_qd = gate_->reference().qd;
    const JointReference& ref = gate_->step(now.ns);
    tau_ = servo_->torque(q_meas, qd_meas, ref_q, ref_qd, ref.qdd);

    // ---- 6. the arm and the hand over one period
    const double h = dt_ / substeps_;
    for (int s = 0; s < substeps_; ++s) {
      const Contacts c = s == 0 ? contacts : contact_forces(arm_->q(), arm_->qd());
      const Eigen::Vector3d f_hand =
          hand_k_ * (hand_target_ - hand_x_) - hand_d_ * hand_v_ + c.on_hand;  // no gravity: the user carries it
      arm_->step(h, tau_, c.joint_torque);
      hand_v_ += f_hand / hand_mass_ * h;
      hand_x_ += hand_v_ * h;
    }
    if (status_.publish(now.ns, *gate_, follower_->source(), status_out_)) log("fault: " + gate_->reason());
  }

  void hold() noexcept override {
    try {
      if (gate_) gate_->fault("hold: the pipeline stopped on a fault");
    } catch (...) {
    }
  }

 private:
  struct Contacts {
    Eigen::Vector3d on_hand = Eigen::Vector3d::Zero();        // force on the fingertip, base frame
    Vector6d joint_torque = Vector6d::Zero();                  // the reaction on the arm, at the joints
    Eigen::Vector3d measured_force = Eigen::Vector3d::Zero();  // on the parts beyond the sensor, base frame
    Eigen::Vector3d measured_torque = Eigen::Vector3d::Zero(); // about the sensor origin, base frame
    Eigen::Isometry3d base_T_sensor = Eigen::Isometry3d::Identity();
  };

  Contacts contact_forces(const Vector6d& q, const Vector6d& qd) const {
    Contacts out;
    out.base_T_sensor = model_->fk(q, sensor_);
    const Eigen::Vector3d o = out.base_T_sensor.translation();
    if ((hand_x_ - o).norm() > tool_.bounding_radius + hand_radius_) return out;
    Matrix6d J;
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

  void publish(Time now, const Vector6d& q, const Vector6d& qd, const Eigen::Vector3d& f, const Eigen::Vector3d& t) {
    fill_joint_state(joint_msg_, now.ns, seq_, q, qd, tau_);
    joint_out_.write(joint_msg_);
    fill_device_pose(pose_msg_, now.ns, seq_, tip_frame_, model_->fk(q, tip_));
    pose_out_.write(pose_msg_);

    wrench_msg_.header().stamp_ns(now.ns);
    wrench_msg_.header().seq(seq_);
    wrench_msg_.header().frame_id(sensor_frame_);
    auto& w = wrench_msg_.wrench();
    w.force().x(f.x()), w.force().y(f.y()), w.force().z(f.z());
    w.torque().x(t.x()), w.torque().y(t.y()), w.torque().z(t.z());
    wrench_out_.write(wrench_msg_);

    hand_msg_out_.header().stamp_ns(now.ns);
    hand_msg_out_.header().seq(seq_);
    hand_msg_out_.header().frame_id("base");
    hand_msg_out_.child_frame_id("hand");
    Eigen::Isometry3d hand = Eigen::Isometry3d::Identity();
    hand.translation() = hand_x_;
    msgs::to_msg(hand, hand_msg_out_.pose());
    hand_out_.write(hand_msg_out_);
    ++seq_;
  }

  // parameters
  std::string urdf_path_, drive_path_, tip_frame_, sensor_frame_;
  Vector6d q0_ = Vector6d::Zero(), bias_ = Vector6d::Zero();
  SafetyConfig gate_config_;
  JointServoConfig servo_config_;
  double tracker_hz_ = 10;
  int substeps_ = 4, encoder_counts_ = 1000;
  double noise_force_ = 0.05, noise_torque_ = 0.002;
  std::int64_t seed_ = 1;
  double hand_mass_ = 0.5, hand_radius_ = 0.01, hand_k_ = 500, hand_d_ = 30, contact_k_ = 2e4, contact_d_ = 100;
  Eigen::Vector3d park_ = Eigen::Vector3d::Zero();
  double dt_ = 1e-3;

  // model
  std::unique_ptr<PumaModel> model_;
  DriveParams drive_;
  ToolGeometry tool_;
  FrameId tip_, sensor_;
  std::unique_ptr<JointServo> servo_;

  // state
  std::unique_ptr<ArmDynamics> arm_;
  Vector6d tau_ = Vector6d::Zero();
  Eigen::Vector3d hand_x_ = Eigen::Vector3d::Zero(), hand_v_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d hand_target_ = Eigen::Vector3d::Zero();
  std::unique_ptr<SafetyGate> gate_;
  std::unique_ptr<SetpointFollower> follower_;
  GateStatus status_;
  bool started_ = false;
  std::mt19937_64 rng_;
  std::normal_distribution<double> normal_{0.0, 1.0};
  std::uint64_t seq_ = 0, rejected_hand_ = 0;

  // messages and ports (reused: no allocation per tick)
  msg::CartesianSetpoint setpoint_msg_;
  msg::PoseStamped hand_msg_, pose_msg_, hand_msg_out_;
  msg::JointState joint_msg_;
  msg::WrenchStamped wrench_msg_;
  Input<msg::CartesianSetpoint> setpoint_in_;
  Input<msg::PoseStamped> hand_in_;
  Output<msg::JointState> joint_out_;
  Output<msg::PoseStamped> pose_out_;
  Output<msg::WrenchStamped> wrench_out_;
  Output<msg::PoseStamped> hand_out_;
  Output<msg::RobotStatus> status_out_;
};

}  // namespace wysiwyf::robot::sim

WYSIWYF_COMPONENT(wysiwyf::robot::sim::PumaSim, "puma_sim")
