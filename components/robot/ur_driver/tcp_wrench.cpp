#include "tcp_wrench.hpp"

namespace wysiwyf::robot::ur {

TcpWrench::TcpWrench(const ArmModel& model, const std::string& flange_frame, const std::string& sensor_frame,
                     const Payload& payload)
    : model_(model), flange_(model.frame(flange_frame)), sensor_(model.frame(sensor_frame)), payload_(payload) {}

void TcpWrench::to_sensor(const JointVector& q, const std::array<double, 6>& tcp_force, Eigen::Vector3d& force,
                          Eigen::Vector3d& torque) const {
  const Eigen::Isometry3d base_T_flange = model_.fk(q, flange_);
  const Eigen::Isometry3d base_T_sensor = model_.fk(q, sensor_);
  const Eigen::Vector3d f(tcp_force[0], tcp_force[1], tcp_force[2]);
  const Eigen::Vector3d t_flange(tcp_force[3], tcp_force[4], tcp_force[5]);
  const Eigen::Vector3d sensor_origin = base_T_sensor.translation();
  // About the sensor's origin: t_s = t_f + (p_flange - p_sensor) x f.
  Eigen::Vector3d t = t_flange + (base_T_flange.translation() - sensor_origin).cross(f);
  // The payload's weight, which the controller took out, put back.
  const Eigen::Vector3d weight = payload_.mass * standard_gravity();
  const Eigen::Vector3d com = base_T_flange * payload_.com_flange;
  const Eigen::Vector3d f_total = f + weight;
  t += (com - sensor_origin).cross(weight);
  const Eigen::Matrix3d sensor_R_base = base_T_sensor.linear().transpose();
  force = sensor_R_base * f_total;
  torque = sensor_R_base * t;
}

}  // namespace wysiwyf::robot::ur
