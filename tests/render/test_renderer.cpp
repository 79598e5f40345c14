// The renderer component: the scene drawn from the tracked pose with the camera's intrinsics (its
// camera_info), following the object states; the scene's knobs drawn on their faces.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstring>

#include "wysiwyf/harness.hpp"
#include "wysiwyf/msg_eigen.hpp"

namespace wysiwyf::render {

msg::CameraInfo camera_info(int width, int height, double fx, double fy, double cx, double cy) {
  msg::CameraInfo info;
  info.width(static_cast<std::uint32_t>(width)), info.height(static_cast<std::uint32_t>(height));
  info.k() = {fx, 0, cx, 0, fy, cy, 0, 0, 1};
  return info;
}

float depth_at(const msg::Image& d, int u, int v) {
  float z;
  std::memcpy(&z, &d.data()[(static_cast<std::size_t>(v) * d.width() + u) * 4], 4);
  return z;
}

TEST(Renderer, DrawsTheCubeFromTheTrackedPoseAndFollowsIt) {
  const double fx = 615.3, fy = 612.8, cx = 321.7, cy = 238.4;
  Harness h("renderer", "{samples: 1}", 60);
  auto info_in = h.feed<msg::CameraInfo>("camera_info");
  auto pose_in = h.feed<msg::PoseStamped>("eye_T_base");
  auto objects_in = h.feed<msg::ObjectState>("objects");
  auto color = h.watch<msg::Image>("color");
  auto depth = h.watch<msg::Image>("depth");
  h.activate();
  // The camera 0.8 m in front of the cube's centre (0.6, 0, 0.1), looking along base +y, image
  // x along base +x, image y down (base -z).
  Eigen::Isometry3d base_T_eye = Eigen::Isometry3d::Identity();
  base_T_eye.linear() << 1, 0, 0, 0, 0, 1, 0, -1, 0;
  base_T_eye.translation() = Eigen::Vector3d(0.6, -0.8, 0.1);
  msg::PoseStamped p;
  msgs::to_msg(base_T_eye.inverse(), p.pose());
  pose_in.write(p);
  h.tick(Time{0});
  msg::Image c, d;
  EXPECT_FALSE(color.take_latest(c)) << "drawn before the camera's intrinsics arrived";
  info_in.write(camera_info(640, 480, fx, fy, cx, cy));
  h.tick(Time{1'000'000});
  ASSERT_TRUE(color.take_latest(c));
  ASSERT_TRUE(depth.take_latest(d));
  EXPECT_EQ(c.width(), 640u);
  EXPECT_EQ(std::string(d.encoding().c_str()), "32FC1");
  const int u0 = static_cast<int>(std::lround(cx)), v0 = static_cast<int>(std::lround(cy));
  EXPECT_NEAR(depth_at(d, u0, v0), 0.7, 1e-3);  // the cube's near face
  // Its edge: 0.1 m right of centre at 0.7 m depth.
  const double edge_u = cx + fx * 0.1 / 0.7;
  EXPECT_NEAR(depth_at(d, static_cast<int>(edge_u) - 2, v0), 0.7, 1e-3);
  const float beyond = depth_at(d, static_cast<int>(edge_u) + 3, v0);  // past the edge: the table or nothing
  EXPECT_TRUE(beyond == 0.0f || beyond > 0.75f) << beyond;
  (void)fy;
  // The simulation moves the cube 10 cm along base x: the renderer follows.
  msg::ObjectState o;
  o.child_frame_id("cube");
  Eigen::Isometry3d moved = Eigen::Isometry3d::Identity();
  moved.translation() = Eigen::Vector3d(0.7, 0.0, 0.1);
  msgs::to_msg(moved, o.pose());
  objects_in.write(o);
  h.tick(Time{16'666'667});
  ASSERT_TRUE(depth.take_latest(d));
  const int u1 = static_cast<int>(std::lround(cx + fx * 0.1 / 0.8));
  EXPECT_NEAR(depth_at(d, u1, v0), 0.7, 1e-3);
  // A corrupt pose is ignored: the last good one stays.
  p.pose().position().x(std::nan(""));
  pose_in.write(p);
  h.tick(Time{33'333'333});
  ASSERT_TRUE(depth.take_latest(d));
  EXPECT_NEAR(depth_at(d, u1, v0), 0.7, 1e-3);
}

// The knob the scene declares on the cube's +x face, drawn there: seen from in front of the face,
// the depth at the knob's centre is the knob's tip, 4 cm nearer than the face around it; and a
// new camera_info (another size and focal length) is followed.
TEST(Renderer, DrawsTheScenesKnobsAndFollowsTheCameraInfo) {
  Harness h("renderer", "{scene: scenes/display_demo.yaml, samples: 1}", 60);
  auto info_in = h.feed<msg::CameraInfo>("camera_info");
  auto pose_in = h.feed<msg::PoseStamped>("eye_T_base");
  auto depth = h.watch<msg::Image>("depth");
  h.activate();
  // 0.5 m in front of the +x face (x = 0.7), looking along base -x at the knob (0.74, 0, 0.1):
  // image x along base +y, image y down.
  Eigen::Isometry3d base_T_eye = Eigen::Isometry3d::Identity();
  base_T_eye.linear() << 0, 0, -1, 1, 0, 0, 0, -1, 0;
  base_T_eye.translation() = Eigen::Vector3d(1.2, 0.0, 0.1);
  msg::PoseStamped p;
  msgs::to_msg(base_T_eye.inverse(), p.pose());
  pose_in.write(p);
  info_in.write(camera_info(320, 240, 300, 300, 159.5, 119.5));
  h.tick(Time{0});
  msg::Image d;
  ASSERT_TRUE(depth.take_latest(d));
  ASSERT_EQ(d.width(), 320u);
  EXPECT_NEAR(depth_at(d, 160, 120), 1.2 - 0.74, 1e-3);  // the knob's tip
  // 3 cm off the knob's axis (radius 1.5 cm): the face.
  EXPECT_NEAR(depth_at(d, 160 + static_cast<int>(300 * 0.03 / 0.5), 120), 0.5, 1e-3);
  info_in.write(camera_info(640, 480, 600, 600, 319.5, 239.5));
  h.tick(Time{40'000'000});
  ASSERT_TRUE(depth.take_latest(d));
  ASSERT_EQ(d.width(), 640u);
  EXPECT_NEAR(depth_at(d, 320, 240), 1.2 - 0.74, 1e-3);
  EXPECT_NEAR(depth_at(d, 320 + static_cast<int>(600 * 0.03 / 0.5), 240), 0.5, 1e-3);
}

}  // namespace wysiwyf::render
