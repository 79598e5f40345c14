// The renderer component: the scene drawn from the tracked pose, following the object states.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstring>

#include "wysiwyf/harness.hpp"
#include "wysiwyf/msg_eigen.hpp"

namespace wysiwyf::render {

float depth_at(const msg::Image& d, int u, int v) {
  float z;
  std::memcpy(&z, &d.data()[(static_cast<std::size_t>(v) * d.width() + u) * 4], 4);
  return z;
}

TEST(Renderer, DrawsTheCubeFromTheTrackedPoseAndFollowsIt) {
  const double fx = 615.3, fy = 612.8, cx = 321.7, cy = 238.4;
  Harness h("renderer", "{intrinsics: [615.3, 612.8, 321.7, 238.4], samples: 1}", 60);
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

}  // namespace wysiwyf::render
