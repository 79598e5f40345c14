// ros2_mirror: the display's joint state, wrist wrench and poses again, as ROS 2's own types
// (sensor_msgs/JointState, geometry_msgs/WrenchStamped, geometry_msgs/PoseStamped, with ROS 2's
// DDS type names, interfaces/ros2/*.idl), so that ROS 2 tools (ros2 topic echo, rosbag2, RViz,
// PlotJuggler) read them. ROS 2 names its DDS topics "rt/<name>": the pipeline maps the outputs
// there (config/pipelines/ros2/mirror.yaml; docs/ros2.md). Values pass unchanged; the stamp goes
// from int64 ns to ROS 2's {int32 sec, uint32 nanosec} exactly, frame ids are kept, the sequence
// number and a pose's child frame have no place in ROS 2's types and are left out.
#include <cmath>
#include <algorithm>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "wysiwyf/component.hpp"
#include "wysiwyf/msgs.hpp"
#include "wysiwyf_ros2_msgs/messages.hpp"

namespace wysiwyf::io {

namespace ros2 = ::sensor_msgs::msg::dds_;
namespace ros2_geometry = ::geometry_msgs::msg::dds_;

namespace {

// WYSIWYF's int64 ns stamp as builtin_interfaces/Time: sec = floor(ns / 1e9), nanosec the rest in
// [0, 1e9) (-1.7 s is {-2, 300000000}). False where the seconds do not fit ROS 2's int32 (before
// 1901-12-13 or after 2038-01-19 as wall-clock time).
bool to_ros2_time(std::int64_t ns, ::builtin_interfaces::msg::dds_::Time_& out) {
  constexpr std::int64_t kNsPerS = 1'000'000'000;
  std::int64_t sec = ns / kNsPerS;  // (truncates toward zero)
  std::int64_t rest = ns % kNsPerS;
  if (rest < 0) {
    rest += kNsPerS;
    --sec;
  }
  if (sec < std::numeric_limits<std::int32_t>::min() || sec > std::numeric_limits<std::int32_t>::max()) return false;
  out.sec(static_cast<std::int32_t>(sec));
  out.nanosec(static_cast<std::uint32_t>(rest));
  return true;
}

}  // namespace

class Ros2Mirror final : public Component {
 public:
  void configure(Context& ctx) override {
    ctx.summary("the joint state, wrench and poses as ROS 2's types, for ROS 2 tools (topics rt/...)");
    const std::vector<std::string> kinds = {"joint_state", "wrench", "pose"};
    mirror_ = ctx.param<std::vector<std::string>>(
        "mirror", kinds,
        "the streams this instance mirrors, an input and an output each (a second instance mirrors a second pose)",
        std::nullopt, Length::at_least(1));
    for (std::size_t i = 0; i < mirror_.size(); ++i) {
      if (std::find(kinds.begin(), kinds.end(), mirror_[i]) == kinds.end())
        ctx.reject("mirror", "found '" + mirror_[i] + "'; expected joint_state, wrench or pose");
      if (std::find(mirror_.begin(), mirror_.begin() + static_cast<std::ptrdiff_t>(i), mirror_[i]) !=
          mirror_.begin() + static_cast<std::ptrdiff_t>(i))
        ctx.reject("mirror", "'" + mirror_[i] + "' twice; one port each (a second instance mirrors a second pose)");
    }
    const auto names = ctx.param<std::vector<std::string>>(
        "joint_names", {"joint1", "joint2", "joint3", "joint4", "joint5", "joint6"},
        "sensor_msgs/JointState's name, base to tip (the URDF's joints, for robot_state_publisher; as many as "
        "the arm's joint states carry)",
        std::nullopt, Length{1, kMaxJoints});
    // Every sample counts (a bag or a plot should hold what the display had): deep queues read
    // with take(). Best effort, so that the mirror may run in another process group than a
    // best-effort writer (the wrist sensor's); inside one process nothing is lost either way.
    // Outputs as ROS 2's default profile (reliable, keep last 10): RViz's displays and
    // robot_state_publisher subscribe reliable, and ros2 topic echo takes either.
    if (has("joint_state")) {
      joint_in_ = ctx.input<msg::JointState>("joint_state", "the arm's joints (one per joint_names)", Qos::sensor(64));
      joint_out_ = ctx.output<ros2::JointState_>(
          "ros2_joint_state", "sensor_msgs/JointState (map it to rt/<name>: ROS 2's /<name>)", Qos::reliable(10));
      joint_.name(names);
      joint_.position().resize(names.size());
      joint_.velocity().resize(names.size());
      joint_.effort().resize(names.size());
    }
    if (has("wrench")) {
      wrench_in_ = ctx.input<msg::WrenchStamped>("wrench", "a wrench (the wrist sensor's)", Qos::sensor(64));
      wrench_out_ = ctx.output<ros2_geometry::WrenchStamped_>("ros2_wrench", "geometry_msgs/WrenchStamped (rt/<name>)",
                                                              Qos::reliable(10));
    }
    if (has("pose")) {
      pose_in_ = ctx.input<msg::PoseStamped>("pose", "a pose, parent_T_child (child_frame_id is not mirrored)",
                                             Qos::sensor(64));
      pose_out_ = ctx.output<ros2_geometry::PoseStamped_>("ros2_pose", "geometry_msgs/PoseStamped (rt/<name>)",
                                                          Qos::reliable(10));
    }
  }

  void tick(Time) override {
    while (joint_in_.take(joint_in_msg_)) {
      const std::size_t n = joint_.name().size();
      if (joint_in_msg_.position().size() != n) {
        reject(joint_in_, std::to_string(joint_in_msg_.position().size()) + " joints, expected " + std::to_string(n) +
                              " (joint_names)");
        continue;
      }
      if (!header(joint_in_, joint_in_msg_.header(), joint_.header())) continue;
      // Velocities and efforts the source does not know are NaN, as ROS 2's JointState has them.
      const auto& in = joint_in_msg_;
      for (std::size_t j = 0; j < n; ++j) {
        joint_.position()[j] = in.position()[j];
        joint_.velocity()[j] = in.velocity().size() == n ? in.velocity()[j] : std::nan("");
        joint_.effort()[j] = in.effort().size() == n ? in.effort()[j] : std::nan("");
      }
      joint_out_.write(joint_);
    }
    while (wrench_in_.take(wrench_in_msg_)) {
      if (!header(wrench_in_, wrench_in_msg_.header(), wrench_.header())) continue;
      vector(wrench_in_msg_.wrench().force(), wrench_.wrench().force());
      vector(wrench_in_msg_.wrench().torque(), wrench_.wrench().torque());
      wrench_out_.write(wrench_);
    }
    while (pose_in_.take(pose_in_msg_)) {
      if (!header(pose_in_, pose_in_msg_.header(), pose_.header())) continue;
      const auto& p = pose_in_msg_.pose();
      pose_.pose().position().x(p.position().x());
      pose_.pose().position().y(p.position().y());
      pose_.pose().position().z(p.position().z());
      pose_.pose().orientation().x(p.orientation().x());
      pose_.pose().orientation().y(p.orientation().y());
      pose_.pose().orientation().z(p.orientation().z());
      pose_.pose().orientation().w(p.orientation().w());
      pose_out_.write(pose_);
    }
  }

 private:
  static constexpr std::size_t kMaxJoints = 8;  // WYSIWYF's JointState: up to 8 joints

  bool has(const std::string& kind) const { return std::find(mirror_.begin(), mirror_.end(), kind) != mirror_.end(); }

  // The header in ROS 2's form; false (the sample refused) where its stamp has no ROS 2 form.
  template <class T>
  bool header(Input<T>& in, const std_msgs::Header& from, ::std_msgs::msg::dds_::Header_& to) {
    if (!to_ros2_time(from.stamp_ns(), to.stamp())) {
      reject(in, "a stamp outside ROS 2's time (int32 seconds)");
      return false;
    }
    to.frame_id().assign(from.frame_id().c_str(), from.frame_id().size());  // (no allocation once it fits)
    return true;
  }
  static void vector(const geometry_msgs::Vector3& from, ros2_geometry::Vector3_& to) {
    to.x(from.x());
    to.y(from.y());
    to.z(from.z());
  }

  std::vector<std::string> mirror_;
  // messages (members, reused: no allocation per tick) and ports; a port this instance does not
  // have (`mirror`) stays unconnected and its take() finds nothing
  msg::JointState joint_in_msg_;
  msg::WrenchStamped wrench_in_msg_;
  msg::PoseStamped pose_in_msg_;
  ros2::JointState_ joint_;
  ros2_geometry::WrenchStamped_ wrench_;
  ros2_geometry::PoseStamped_ pose_;
  Input<msg::JointState> joint_in_;
  Input<msg::WrenchStamped> wrench_in_;
  Input<msg::PoseStamped> pose_in_;
  Output<ros2::JointState_> joint_out_;
  Output<ros2_geometry::WrenchStamped_> wrench_out_;
  Output<ros2_geometry::PoseStamped_> pose_out_;
};

}  // namespace wysiwyf::io

WYSIWYF_COMPONENT(wysiwyf::io::Ros2Mirror, "ros2_mirror")
