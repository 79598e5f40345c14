// The headless renderer against OpenCV's camera model: where points land, and what depth reads.
#include <gtest/gtest.h>

#include <opencv2/calib3d.hpp>

#include <memory>
#include <thread>

#include "offscreen_gl/gl_context.hpp"
#include "offscreen_gl/offscreen_renderer.hpp"

namespace wysiwyf::render {

Pinhole test_camera() {
  Pinhole c;
  c.width = 640;
  c.height = 480;
  c.fx = 615.3;
  c.fy = 612.8;
  c.cx = 321.7;
  c.cy = 238.4;
  c.near_m = 0.05;
  c.far_m = 10.0;
  return c;
}

Eigen::Isometry3d cube_pose() {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = (Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitY()) * Eigen::AngleAxisd(-0.3, Eigen::Vector3d::UnitX()) *
                Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitZ()))
                   .toRotationMatrix();
  T.translation() = Eigen::Vector3d(0.03, -0.02, 0.6);
  return T;
}

TEST(Gl, AHeadlessContextComesUp) {
  GlContext gl;
  EXPECT_FALSE(gl.renderer().empty());
  EXPECT_TRUE(gl.platform() == "device" || gl.platform() == "surfaceless") << gl.platform();
  RecordProperty("renderer", gl.renderer());
}

// The real clock activates a component on the main thread and ticks it on its own: the context
// set up on one thread draws on another (a Scope per tick) and is torn down on the first.
TEST(Gl, AContextSetUpOnOneThreadDrawsOnAnotherAndIsTornDownOnTheFirst) {
  GlContext gl;
  auto r = std::make_unique<OffscreenRenderer>(gl, test_camera(), 1);
  const int box = r->add_mesh(Mesh::box(Eigen::Vector3f(0.1f, 0.1f, 0.1f)));
  std::vector<float> depth;
  std::string error;
  for (int tick = 0; tick < 2; ++tick) {  // two ticks, each on a fresh thread
    std::thread([&] {
      try {
        GlContext::Scope current(gl);
        r->begin(Eigen::Vector4f(0, 0, 0, 1));
        r->draw(box, cube_pose(), Eigen::Vector4f(1, 1, 1, 1));
        r->read_depth(depth);
      } catch (const std::exception& e) {
        error = e.what();
      }
    }).join();
    ASSERT_EQ(error, "");
  }
  EXPECT_FALSE(gl.is_current()) << "a Scope leaves the context free";
  const auto centre = depth[static_cast<std::size_t>(238 * 640 + 321)];
  EXPECT_GT(centre, 0.4f);  // the box's near side, 0.6 m away at its centre
  EXPECT_LT(centre, 0.6f);
  r.reset();  // back on the main thread: no exception, no abort
}

TEST(Gl, CubeCornersLandWhereOpenCvProjectsThem) {
  GlContext gl;
  const Pinhole cam = test_camera();
  OffscreenRenderer r(gl, cam, 16);
  const int dot = r.add_mesh(Mesh::sphere(0.002f, 32, 16));
  const Eigen::Isometry3d camera_T_cube = cube_pose();
  std::vector<cv::Point3d> corners;
  r.begin(Eigen::Vector4f(0, 0, 0, 1));
  for (int i = 0; i < 8; ++i) {
    const Eigen::Vector3d c(i & 1 ? 0.1 : -0.1, i & 2 ? 0.1 : -0.1, i & 4 ? 0.1 : -0.1);
    corners.emplace_back(c.x(), c.y(), c.z());
    Eigen::Isometry3d T = camera_T_cube;
    T.translate(c);
    r.draw(dot, T, Eigen::Vector4f(1, 1, 1, 1), false);
  }
  std::vector<std::uint8_t> rgb;
  r.read_rgb(rgb);
  // OpenCV's projection of the same corners.
  const Eigen::Matrix3d R = camera_T_cube.linear();
  cv::Mat rvec, R_cv(3, 3, CV_64F), tvec(3, 1, CV_64F);
  for (int a = 0; a < 3; ++a) {
    tvec.at<double>(a) = camera_T_cube.translation()[a];
    for (int b = 0; b < 3; ++b) R_cv.at<double>(a, b) = R(a, b);
  }
  cv::Rodrigues(R_cv, rvec);
  const cv::Matx33d K(cam.fx, 0, cam.cx, 0, cam.fy, cam.cy, 0, 0, 1);
  std::vector<cv::Point2d> expected;
  cv::projectPoints(corners, rvec, tvec, K, cv::noArray(), expected);
  double worst = 0;
  for (const auto& e : expected) {
    // Intensity-weighted centroid of the anti-aliased dot around where OpenCV puts it.
    double sum = 0, su = 0, sv = 0;
    for (int v = static_cast<int>(e.y) - 8; v <= static_cast<int>(e.y) + 8; ++v)
      for (int u = static_cast<int>(e.x) - 8; u <= static_cast<int>(e.x) + 8; ++u) {
        const double w = rgb[(static_cast<std::size_t>(v) * cam.width + u) * 3];
        sum += w, su += w * u, sv += w * v;
      }
    ASSERT_GT(sum, 0) << "no dot near (" << e.x << ", " << e.y << ")";
    worst = std::max(worst, std::hypot(su / sum - e.x, sv / sum - e.y));
  }
  EXPECT_LE(worst, 0.5);
  RecordProperty("worst_corner_error_px", std::to_string(worst));
  std::cout << "worst corner error " << worst << " px\n";
}

TEST(Gl, ReadBackDepthIsTheAnalyticMetricDepth) {
  GlContext gl;
  const Pinhole cam = test_camera();
  OffscreenRenderer r(gl, cam, 1);
  const int plane = r.add_mesh(Mesh::plane(1.0f, 1.0f));
  // A plane 0.6 m away, tilted 30 degrees about the camera's x axis.
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(M_PI / 6, Eigen::Vector3d::UnitX()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(0.0, 0.0, 0.6);
  r.begin(Eigen::Vector4f(0, 0, 0, 1));
  r.draw(plane, T, Eigen::Vector4f(0.5f, 0.5f, 0.5f, 1));
  std::vector<float> depth;
  r.read_depth(depth);
  const Eigen::Vector3d n = T.linear().col(2), p0 = T.translation();
  double worst = 0;
  int checked = 0;
  for (int v = 20; v < cam.height; v += 37)
    for (int u = 20; u < cam.width; u += 41) {
      const Eigen::Vector3d ray((u - cam.cx) / cam.fx, (v - cam.cy) / cam.fy, 1.0);
      const double z = n.dot(p0) / n.dot(ray);  // where the pixel's ray meets the plane
      const float got = depth[static_cast<std::size_t>(v) * cam.width + u];
      ASSERT_GT(got, 0) << u << "," << v;
      worst = std::max(worst, std::abs(got - z));
      ++checked;
    }
  EXPECT_GT(checked, 150);
  EXPECT_LE(worst, 1e-3);
  std::cout << "worst depth error " << worst * 1e3 << " mm over " << checked << " pixels\n";
  // Where nothing is drawn, depth reads 0.
  r.begin(Eigen::Vector4f(0, 0, 0, 1));
  r.read_depth(depth);
  EXPECT_EQ(depth[1000], 0.0f);
}

}  // namespace wysiwyf::render
