// stereo_depth on camera_sim's stereo pair (noise, blur, spill) against its ground truth, and on
// synthetic pairs for the exact disparity -> depth relation and for bad input.
#include <gtest/gtest.h>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <array>
#include <iostream>
#include <sstream>

#include "wysiwyf/harness.hpp"
#include "wysiwyf/msg_eigen.hpp"

namespace wysiwyf::vision {

namespace {

constexpr double kBaseline = 0.06;  // m, about a human's interocular distance
constexpr double kFx = 600, kFy = 600, kCx = 319.5, kCy = 239.5;
const Eigen::Vector3d kEye(1.3, -0.5, 0.75), kLookAt(0.55, 0.0, 0.35);  // camera_sim's default camera

cv::Mat view(msg::Image& m, int type) {
  return cv::Mat(static_cast<int>(m.height()), static_cast<int>(m.width()), type, m.data().data(), m.step());
}

// Where camera_sim draws the palm's centre in the fingertip's frame (the hand pose is the
// index fingertip's: x along the finger, z out of the back of the hand).
const Eigen::Vector3d kPalmCentre(-0.124, 0.032, -0.004);

// The hand's palm `distance` from the camera on the ray through image offset (a, b) (tangents of
// the angles right and down from the optical axis), the back of the hand toward the camera, the
// finger turned by `roll` about the view direction, then tilted by `tilt` about the camera's x
// axis. Returns the fingertip's pose (camera_sim's hand_pose).
Eigen::Isometry3d hand_in_view(double distance, double a, double b, double roll, double tilt) {
  const Eigen::Vector3d d = (kLookAt - kEye).normalized();
  const Eigen::Vector3d x = d.cross(Eigen::Vector3d::UnitZ()).normalized(), y = d.cross(x);
  Eigen::Matrix3d R;
  R.col(2) = -d;
  R.col(0) = std::cos(roll) * x + std::sin(roll) * y;
  R.col(1) = R.col(2).cross(R.col(0));
  Eigen::Isometry3d base_T_hand = Eigen::Isometry3d::Identity();
  base_T_hand.linear() = Eigen::AngleAxisd(tilt, x).toRotationMatrix() * R;
  base_T_hand.translation() = kEye + distance * (d + a * x + b * y).normalized();
  base_T_hand.translation() -= base_T_hand.linear() * kPalmCentre;  // the palm there, the fingertip ahead of it
  return base_T_hand;
}

// The centroid of the hand's visible surface from ground truth, eye frame: the true mask's pixels
// back-projected with their true depth, the point stereo_depth's `centroid` measures. The mask
// (multisampled) and the depth (one sample) disagree on the silhouette's edge, where the depth is
// the background's: only depths within 8 cm of the mask's median depth count (the component's
// hand_band). With `nearest`, the centroid of the nearest `nearest` fraction of them instead.
Eigen::Vector3d true_hand_point(msg::Image& mask, msg::Image& depth, double nearest = 0) {
  const cv::Mat m = view(mask, CV_8UC1), z = view(depth, CV_32FC1);
  std::vector<Eigen::Vector3d> points;
  for (int v = 0; v < m.rows; ++v)
    for (int u = 0; u < m.cols; ++u)
      if (m.at<std::uint8_t>(v, u) && z.at<float>(v, u) > 0) {
        const double Z = z.at<float>(v, u);
        points.emplace_back((u - kCx) * Z / kFx, (v - kCy) * Z / kFy, Z);
      }
  EXPECT_GT(points.size(), 1000u) << "the hand is not in view";
  std::sort(points.begin(), points.end(), [](const auto& p, const auto& q) { return p.z() < q.z(); });
  const double median = points[points.size() / 2].z();
  points.erase(
      std::remove_if(points.begin(), points.end(), [&](const auto& p) { return std::abs(p.z() - median) > 0.08; }),
      points.end());
  if (nearest > 0) {
    points.resize(static_cast<std::size_t>(std::ceil(nearest * static_cast<double>(points.size()))));
  }
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const auto& p : points) sum += p;
  return sum / static_cast<double>(points.size());
}

struct DepthErrors {
  double median = 0, p90 = 0, coverage = 0;  // |error| in m over pixels with both depths; share of truth estimated
  double bias = 0;                           // median signed error (estimate - truth), m
};

// Depth error against the truth over `where` (mono8, nonzero = count it).
DepthErrors depth_errors(msg::Image& estimate, msg::Image& truth, const cv::Mat& where) {
  const cv::Mat e = view(estimate, CV_32FC1), t = view(truth, CV_32FC1);
  std::vector<double> err, signed_err;
  int truths = 0;
  for (int v = 0; v < t.rows; ++v)
    for (int u = 0; u < t.cols; ++u) {
      if (!where.at<std::uint8_t>(v, u) || !(t.at<float>(v, u) > 0)) continue;
      ++truths;
      if (e.at<float>(v, u) > 0) signed_err.push_back(e.at<float>(v, u) - t.at<float>(v, u));
    }
  if (signed_err.empty()) return {1e9, 1e9, 0, 1e9};
  for (double x : signed_err) err.push_back(std::abs(x));
  std::sort(err.begin(), err.end());
  std::sort(signed_err.begin(), signed_err.end());
  return {err[err.size() / 2], err[err.size() * 9 / 10], static_cast<double>(err.size()) / truths,
          signed_err[signed_err.size() / 2]};
}

// camera_sim (stereo) -> chroma_keyer -> stereo_depth, driven frame by frame on the sim clock.
class StereoRig {
 public:
  explicit StereoRig(const std::string& stereo_params, const std::string& more_camera_params = "")
      : cam_("camera_sim",
             "{stereo_baseline: " + std::to_string(kBaseline) + ", noise: 2.0, spill: 0.3, seed: 7" +
                 more_camera_params + "}",
             25),
        keyer_("chroma_keyer", "{min_luma: 45}", 25),  // as demo-sim keys: the arm's shaded side is cloth too
        stereo_("stereo_depth", stereo_params, 25) {
    hand_in_ = cam_.feed<msg::PoseStamped>("hand_pose");
    joints_in_ = cam_.feed<msg::JointState>("joint_state");
    image_ = cam_.watch<msg::Image>("image");
    image_right_ = cam_.watch<msg::Image>("image_right");
    info_ = cam_.watch<msg::CameraInfo>("camera_info");
    true_mask_ = cam_.watch<msg::Image>("true_hand_mask");
    true_depth_ = cam_.watch<msg::Image>("true_depth");
    true_eye_T_base_ = cam_.watch<msg::PoseStamped>("true_eye_T_base");
    true_eye_T_dev_ = cam_.watch<msg::PoseStamped>("true_eye_T_dev");
    keyer_in_ = keyer_.feed<msg::Image>("image");
    keyed_ = keyer_.watch<msg::Image>("hand");
    left_ = stereo_.feed<msg::Image>("left");
    right_ = stereo_.feed<msg::Image>("right");
    stereo_info_ = stereo_.feed<msg::CameraInfo>("camera_info");
    stereo_keyed_ = stereo_.feed<msg::Image>("keyed");
    stereo_pose_ = stereo_.feed<msg::PoseStamped>("eye_T_base");
    stereo_dev_ = stereo_.feed<msg::PoseStamped>("eye_T_dev");
    depth_ = stereo_.watch<msg::Image>("depth");
    hand_out_ = stereo_.watch<msg::HandPosition>("hand_position");
    cam_.activate(), keyer_.activate(), stereo_.activate();
  }

  // The arm in view from now on (camera_sim draws it, with the plate, from joint state).
  void show_arm(const msg::JointState& joints) { joints_in_.write(joints); }

  // Films the hand at base_T_hand and runs the keyer and stereo_depth on the frame; with the
  // flags, stereo_depth also gets the true eye_T_base and eye_T_dev. in_view: whether a hand
  // position must come (else none may).
  void shoot(const Eigen::Isometry3d& base_T_hand, bool feed_eye_T_base = false, bool feed_eye_T_dev = false,
             bool in_view = true) {
    msg::PoseStamped p;
    msgs::to_msg(base_T_hand, p.pose());
    hand_in_.write(p);
    const Time t{frame_++ * 40'000'000LL};
    cam_.tick(t);
    msg::Image img, right;
    msg::CameraInfo info;
    ASSERT_TRUE(image_.take_latest(img) && image_right_.take_latest(right) && info_.take_latest(info));
    ASSERT_TRUE(true_mask_.take_latest(true_mask) && true_depth_.take_latest(true_depth) &&
                true_eye_T_base_.take_latest(eye_T_base));
    keyer_in_.write(img);
    keyer_.tick(t);
    msg::Image keyed;
    ASSERT_TRUE(keyed_.take_latest(keyed));
    left_.write(img), right_.write(right), stereo_info_.write(info), stereo_keyed_.write(keyed);
    if (feed_eye_T_base) stereo_pose_.write(eye_T_base);
    if (feed_eye_T_dev) {
      ASSERT_TRUE(true_eye_T_dev_.take_latest(eye_T_dev)) << "no arm in view";
      stereo_dev_.write(eye_T_dev);
    }
    stereo_.tick(t);
    ASSERT_TRUE(depth_.take_latest(depth)) << "no depth for this frame";
    if (in_view)
      ASSERT_TRUE(hand_out_.take_latest(hand)) << "no hand position for this frame";
    else
      ASSERT_FALSE(hand_out_.take_latest(hand)) << "a hand position with no hand in view";
  }

  msg::Image true_mask, true_depth, depth;
  msg::PoseStamped eye_T_base, eye_T_dev;
  msg::HandPosition hand;

 private:
  Harness cam_, keyer_, stereo_;
  std::int64_t frame_ = 0;
  Output<msg::PoseStamped> hand_in_, stereo_pose_, stereo_dev_;
  Output<msg::JointState> joints_in_;
  Input<msg::Image> image_, image_right_, true_mask_, true_depth_, keyed_, depth_;
  Input<msg::CameraInfo> info_;
  Input<msg::PoseStamped> true_eye_T_base_, true_eye_T_dev_;
  Input<msg::HandPosition> hand_out_;
  Output<msg::Image> keyer_in_, left_, right_, stereo_keyed_;
  Output<msg::CameraInfo> stereo_info_;
};

Eigen::Vector3d position(const msg::HandPosition& p) { return msgs::to_eigen(p.position()); }

// For a look: the depth error (red: estimate too far, green: too near; 1 cm = 64 levels) over the
// true hand, grey where the truth has no estimate.
void dump_depth_error(const std::string& dir, int shot, StereoRig& rig) {
  const cv::Mat e = view(rig.depth, CV_32FC1), t = view(rig.true_depth, CV_32FC1), m = view(rig.true_mask, CV_8UC1);
  cv::Mat out(e.size(), CV_8UC3, cv::Scalar(0, 0, 0));
  for (int v = 0; v < e.rows; ++v)
    for (int u = 0; u < e.cols; ++u) {
      if (!m.at<std::uint8_t>(v, u)) continue;
      const float err = e.at<float>(v, u) - t.at<float>(v, u);
      out.at<cv::Vec3b>(v, u) = e.at<float>(v, u) > 0 ? cv::Vec3b(0, cv::saturate_cast<std::uint8_t>(-err * 6400),
                                                                  cv::saturate_cast<std::uint8_t>(err * 6400))
                                                      : cv::Vec3b(128, 128, 128);
    }
  cv::imwrite(dir + "/stereo_error_" + std::to_string(shot) + ".png", out);
  cv::Mat both;
  cv::hconcat(e, t, both);
  both.convertTo(both, CV_8U, -255 / 1.7, 255 * 2.0 / 1.7);  // 0.3 m white .. 2 m black
  cv::imwrite(dir + "/stereo_depth_" + std::to_string(shot) + ".png", both);
}

}  // namespace

TEST(StereoDepth, HandPositionWithinACentimetreAtSixtyCentimetres) {
  StereoRig rig("{baseline: " + std::to_string(kBaseline) + ", hand_frame: eye}");
  double worst = 0;
  DepthErrors worst_hand;
  worst_hand.coverage = 1;
  int shots = 0;
  for (const auto& [a, b, roll, tilt] : std::vector<std::array<double, 4>>{{0, 0, 0, 0},
                                                                           {0.15, -0.1, 0.8, 0.3},
                                                                           {-0.2, 0.1, -1.2, -0.4},
                                                                           {0.1, 0.2, 2.0, 0.5},
                                                                           {-0.1, -0.2, 0.4, -0.6}}) {
    rig.shoot(hand_in_view(0.6, a, b, roll, tilt));
    if (::testing::Test::HasFatalFailure()) return;
    EXPECT_EQ(std::string(rig.hand.header().frame_id().c_str()), "eye");
    const Eigen::Vector3d truth = true_hand_point(rig.true_mask, rig.true_depth);
    const double error = (position(rig.hand) - truth).norm();
    worst = std::max(worst, error);
    if (const char* dump = std::getenv("WYSIWYF_DUMP_DIR")) dump_depth_error(dump, shots, rig);
    const DepthErrors hand = depth_errors(rig.depth, rig.true_depth, view(rig.true_mask, CV_8UC1));
    const DepthErrors all = depth_errors(rig.depth, rig.true_depth, cv::Mat(480, 640, CV_8UC1, cv::Scalar(255)));
    std::cout << "hand at " << truth.transpose() << " m (eye): error " << error * 1000 << " mm ("
              << (position(rig.hand) - truth).transpose() * 1000 << "); depth |error| on the hand median "
              << hand.median * 1000 << " mm (bias " << hand.bias * 1000 << " mm), p90 " << hand.p90 * 1000
              << " mm, coverage " << hand.coverage << "; whole image median " << all.median * 1000 << " mm, p90 "
              << all.p90 * 1000 << " mm, coverage " << all.coverage << "\n";
    worst_hand.median = std::max(worst_hand.median, hand.median), worst_hand.p90 = std::max(worst_hand.p90, hand.p90);
    worst_hand.coverage = std::min(worst_hand.coverage, hand.coverage);
    ++shots;
  }
  std::cout << "worst of " << shots << " shots: hand position error " << worst * 1000
            << " mm; depth on the hand: median |error| " << worst_hand.median * 1000 << " mm, p90 "
            << worst_hand.p90 * 1000 << " mm, coverage " << worst_hand.coverage << "\n";
  EXPECT_LE(worst, 0.01);
  // At 0.6 m one pixel of disparity is 1 cm of depth (Z^2 / (fx B)): the hand's depth within a
  // pixel of disparity for most of it. The cloth (uniform blue, independent noise in the two
  // cameras) cannot be matched: the whole-image figures are printed, not held to a bound.
  EXPECT_LE(worst_hand.median, 0.01);
  EXPECT_LE(worst_hand.p90, 0.025);
  EXPECT_GE(worst_hand.coverage, 0.9);
}

TEST(StereoDepth, GivesTheHandInTheBaseFrameOnceEyeTBaseArrives) {
  StereoRig rig("{baseline: " + std::to_string(kBaseline) + "}");
  const Eigen::Isometry3d base_T_hand = hand_in_view(0.6, 0.05, 0.05, 0.5, 0.2);
  rig.shoot(base_T_hand, true);
  if (::testing::Test::HasFatalFailure()) return;
  EXPECT_EQ(std::string(rig.hand.header().frame_id().c_str()), "base");
  const Eigen::Isometry3d base_T_eye = msgs::to_isometry(rig.eye_T_base.pose()).inverse();
  const Eigen::Vector3d truth = base_T_eye * true_hand_point(rig.true_mask, rig.true_depth);
  EXPECT_LE((position(rig.hand) - truth).norm(), 0.01);
  // The visible surface's centre lies on the palm and fingers, a few cm from the palm centre:
  // the palm is 9 x 8 cm, the index finger reaches 8 cm beyond it.
  const Eigen::Vector3d palm = base_T_hand * kPalmCentre;
  std::cout << "base frame: error " << (position(rig.hand) - truth).norm() * 1000 << " mm; the palm centre is "
            << (position(rig.hand) - palm).norm() * 1000 << " mm away\n";
  EXPECT_LE((position(rig.hand) - palm).norm(), 0.06);
}

TEST(StereoDepth, NearestPointIsTheHandsPartNearestTheCamera) {
  StereoRig rig("{baseline: " + std::to_string(kBaseline) +
                ", hand_frame: eye, hand_point: nearest, nearest_fraction: 0.1}");
  rig.shoot(hand_in_view(0.6, 0, 0, 0.3, 0.7));  // tilted: its top is nearer than its bottom
  if (::testing::Test::HasFatalFailure()) return;
  const Eigen::Vector3d nearest = true_hand_point(rig.true_mask, rig.true_depth, 0.1);
  const Eigen::Vector3d centroid = true_hand_point(rig.true_mask, rig.true_depth);
  std::cout << "nearest 10 %: error " << (position(rig.hand) - nearest).norm() * 1000 << " mm; "
            << (centroid.z() - nearest.z()) * 1000 << " mm nearer than the centroid\n";
  // The nearest tenth is mostly the index finger: 1.8 cm wide, 9 px at the matcher's half size,
  // where a pixel of disparity is a centimetre of depth.
  EXPECT_LE((position(rig.hand) - nearest).norm(), 0.012);
  EXPECT_LT(position(rig.hand).z(), centroid.z() - 0.01);
}

// hand_point tip: the pointing fingertip (the hand pose's origin), wherever the hand is in view,
// at the image's left edge too (where the matcher once had no disparity for 140 px).
TEST(StereoDepth, TipIsThePointingFingertipAcrossTheViewAndAtTheImagesLeftEdge) {
  StereoRig rig("{baseline: " + std::to_string(kBaseline) + ", hand_point: tip}");
  double worst = 0;
  for (const auto& [a, b, roll, tilt] : std::vector<std::array<double, 4>>{{0, 0, 0, 0},
                                                                           {0.15, -0.1, 0.8, 0.3},
                                                                           {-0.2, 0.1, -1.2, -0.4},
                                                                           {0.1, 0.2, 2.0, 0.5},
                                                                           {-0.1, -0.2, 0.4, -0.6},
                                                                           {-0.42, 0.0, 0.2, 0.0},
                                                                           {-0.42, 0.15, -0.5, 0.3}}) {
    const Eigen::Isometry3d base_T_hand = hand_in_view(0.6, a, b, roll, tilt);
    rig.shoot(base_T_hand, true);
    if (::testing::Test::HasFatalFailure()) return;
    const Eigen::Vector3d tip = base_T_hand.translation(), palm = base_T_hand * kPalmCentre;
    const double error = (position(rig.hand) - tip).norm();
    std::cout << "hand at image offset (" << a << ", " << b << "): tip error " << error * 1000
              << " mm (the palm centre " << (position(rig.hand) - palm).norm() * 1000 << " mm away)\n";
    worst = std::max(worst, error);
  }
  EXPECT_LE(worst, 0.025) << "the fingertip, not the palm 12 cm behind it";
}

TEST(StereoDepth, LeavesTheKeyedPlateOutOfTheHandGivenEyeTDev) {
  // The arm as demo-sim starts it: the plate (not blue: the keyer keeps it) facing the camera.
  msg::JointState joints;
  const double q[6] = {0.255486, -0.429048, -2.231546, 0.286487, 1.106586, 3.010371};
  joints.position().resize(6);
  for (int i = 0; i < 6; ++i) joints.position()[static_cast<std::size_t>(i)] = q[i];
  Eigen::Isometry3d base_T_dev;
  {  // where the plate is, from camera_sim's ground truth
    Harness cam("camera_sim", "{}", 25);
    auto joints_in = cam.feed<msg::JointState>("joint_state");
    auto eye_T_dev = cam.watch<msg::PoseStamped>("true_eye_T_dev");
    auto eye_T_base = cam.watch<msg::PoseStamped>("true_eye_T_base");
    cam.activate();
    joints_in.write(joints);
    cam.tick(Time{0});
    msg::PoseStamped a, b;
    ASSERT_TRUE(eye_T_dev.take_latest(a) && eye_T_base.take_latest(b));
    base_T_dev = msgs::to_isometry(b.pose()).inverse() * msgs::to_isometry(a.pose());
  }
  // The camera 0.7 m from the plate, the hand 0.1 m in front of it, palm toward it: 0.6 m away.
  const Eigen::Vector3d plate = base_T_dev.translation(), eye = plate + 0.7 * (kEye - plate).normalized();
  std::ostringstream camera;
  camera << ", eye: [" << eye.x() << ", " << eye.y() << ", " << eye.z() << "], look_at: [" << plate.x() << ", "
         << plate.y() << ", " << plate.z() << "]";
  Eigen::Isometry3d base_T_hand = base_T_dev;
  base_T_hand.translate(Eigen::Vector3d(0.02, 0.0, 0.10));
  base_T_hand.rotate(Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitY()));
  double error[2] = {0, 0};
  for (bool with_dev : {false, true}) {
    StereoRig rig("{baseline: " + std::to_string(kBaseline) + ", hand_frame: eye}", camera.str());
    rig.show_arm(joints);
    rig.shoot(base_T_hand, false, with_dev);
    if (::testing::Test::HasFatalFailure()) return;
    error[with_dev] = (position(rig.hand) - true_hand_point(rig.true_mask, rig.true_depth)).norm();
  }
  std::cout << "hand 10 cm in front of the plate: error " << error[1] * 1000 << " mm with eye_T_dev, "
            << error[0] * 1000 << " mm without\n";
  // The back of the hand, as textureless as the plate 10 cm behind it, takes some of the plate's
  // disparity at half size: 10.3 mm here (about 7 mm matching at full size, downscale: 1).
  EXPECT_LE(error[1], 0.015);
  EXPECT_GT(error[0], 0.03) << "without eye_T_dev the keyed plate pulls the hand's point toward it";
  // The hand gone: what the keyer keeps is device, so there is no hand position at all.
  StereoRig rig("{baseline: " + std::to_string(kBaseline) + ", hand_frame: eye}", camera.str());
  rig.show_arm(joints);
  Eigen::Isometry3d away = Eigen::Isometry3d::Identity();
  away.translation() = Eigen::Vector3d(5, 5, 5);
  rig.shoot(away, false, true, false);
}

namespace {

// A textured plane seen by a rectified pair: the right image is the left shifted by `disparity` px.
void textured_pair(double disparity, msg::Image& left, msg::Image& right) {
  cv::Mat texture(480, 640 + 64, CV_8UC3);
  cv::RNG rng(3);
  cv::Mat small(480 / 4, (640 + 64) / 4, CV_8UC3);
  rng.fill(small, cv::RNG::UNIFORM, 0, 255);
  cv::resize(small, texture, texture.size(), 0, 0, cv::INTER_LINEAR);  // blobs of a few px: matchable
  const cv::Mat l = texture(cv::Rect(64, 0, 640, 480)).clone();
  cv::Mat r;
  const cv::Mat shift = (cv::Mat_<double>(2, 3) << 1, 0, -disparity, 0, 1, 0);
  cv::warpAffine(l, r, shift, l.size(), cv::INTER_CUBIC, cv::BORDER_REFLECT);
  for (auto [img, m] : {std::pair<const cv::Mat*, msg::Image*>{&l, &left}, {&r, &right}}) {
    m->width(640), m->height(480), m->encoding("rgb8"), m->step(640 * 3);
    m->data().assign(img->data, img->data + img->total() * img->elemSize());
  }
}

msg::CameraInfo intrinsics(int width = 640, int height = 480) {
  msg::CameraInfo info;
  info.width(static_cast<std::uint32_t>(width)), info.height(static_cast<std::uint32_t>(height));
  info.k() = {kFx, 0, kCx, 0, kFy, kCy, 0, 0, 1};
  return info;
}

double median_depth(msg::Image& depth) {
  const cv::Mat d = view(depth, CV_32FC1);
  std::vector<float> valid;
  for (auto it = d.begin<float>(); it != d.end<float>(); ++it)
    if (*it > 0) valid.push_back(*it);
  if (valid.size() < d.total() / 2) return 0;  // most of a textured plane must be measured
  std::nth_element(valid.begin(), valid.begin() + static_cast<std::ptrdiff_t>(valid.size() / 2), valid.end());
  return valid[valid.size() / 2];
}

}  // namespace

TEST(StereoDepth, DepthIsFocalLengthTimesBaselineOverDisparityForEveryMatcher) {
  const std::vector<std::pair<std::string, int>> cases{
      {"{algorithm: sgbm, downscale: 1, baseline: 0.06}", 1},
      {"{algorithm: sgbm_3way, downscale: 1, baseline: 0.06}", 1},
      {"{algorithm: bm, block_size: 9, downscale: 1, baseline: 0.06}", 1},
      {"{algorithm: sgbm, downscale: 2, baseline: 0.06}", 2}};
  for (const auto& [params, downscale] : cases) {
    Harness h("stereo_depth", params, 25);
    auto left = h.feed<msg::Image>("left");
    auto right = h.feed<msg::Image>("right");
    auto info = h.feed<msg::CameraInfo>("camera_info");
    auto depth = h.watch<msg::Image>("depth");
    h.activate();
    msg::Image l, r, d;
    textured_pair(45.5, l, r);  // Z = 600 * 0.06 / 45.5 = 0.791 m
    info.write(intrinsics());
    left.write(l), right.write(r);
    h.tick(Time{0});
    ASSERT_TRUE(depth.take_latest(d)) << params;
    EXPECT_EQ(std::string(d.encoding().c_str()), "32FC1");
    // Within a quarter pixel of disparity at the matched resolution.
    const double z = kFx * 0.06 / 45.5;
    EXPECT_NEAR(median_depth(d), z, z * 0.25 * downscale / 45.5) << params;
  }
}

TEST(StereoDepth, TakesTheBaselineFromTheRightCameraInfo) {
  Harness h("stereo_depth", "{downscale: 1}", 25);  // no baseline parameter
  auto left = h.feed<msg::Image>("left");
  auto right = h.feed<msg::Image>("right");
  auto info = h.feed<msg::CameraInfo>("camera_info");
  auto right_info = h.feed<msg::CameraInfo>("right_camera_info");
  auto depth = h.watch<msg::Image>("depth");
  h.activate();
  msg::Image l, r, d;
  textured_pair(30, l, r);
  info.write(intrinsics());
  msg::CameraInfo ri = intrinsics();
  ri.p() = {kFx, 0, kCx, -kFx * 0.1, 0, kFy, kCy, 0, 0, 0, 1, 0};  // ROS: P[3] = -fx B, B = 0.1 m
  right_info.write(ri);
  left.write(l), right.write(r);
  h.tick(Time{0});
  ASSERT_TRUE(depth.take_latest(d));
  EXPECT_NEAR(median_depth(d), kFx * 0.1 / 30, 0.01);
}

TEST(StereoDepth, SkipsAndReportsBadInput) {
  Harness h("stereo_depth", "{baseline: 0.06}", 25);
  auto left = h.feed<msg::Image>("left");
  auto right = h.feed<msg::Image>("right");
  auto info = h.feed<msg::CameraInfo>("camera_info");
  auto keyed = h.feed<msg::Image>("keyed");
  auto depth = h.watch<msg::Image>("depth");
  auto hand = h.watch<msg::HandPosition>("hand_position");
  h.activate();
  msg::Image l, r, d;
  textured_pair(40, l, r);
  std::int64_t t = 0;
  auto run = [&](const msg::Image& a, const msg::Image& b) {
    t += 40'000'000;
    msg::Image a2 = a, b2 = b;
    a2.header().stamp_ns(t), b2.header().stamp_ns(t);
    left.write(a2), right.write(b2);
    ::testing::internal::CaptureStderr();
    h.tick(Time{t});
    return ::testing::internal::GetCapturedStderr();
  };
  // No intrinsics yet.
  EXPECT_NE(run(l, r).find("no intrinsics yet"), std::string::npos);
  EXPECT_FALSE(depth.take_latest(d));
  info.write(intrinsics());
  // Wrong encoding.
  msg::Image bgra = l;
  bgra.encoding("bgra8");
  EXPECT_NE(run(bgra, r).find("input 'left': rejected a sample: encoding 'bgra8', expected rgb8 or mono8"),
            std::string::npos);
  EXPECT_EQ(h.rejected("left"), 1u);
  EXPECT_FALSE(depth.take_latest(d));
  // Sizes that differ.
  msg::Image narrow = r;
  narrow.width(320), narrow.step(320 * 3);
  EXPECT_NE(run(l, narrow).find("input 'right': rejected a sample: size 320x480, expected 640x480"), std::string::npos);
  EXPECT_EQ(h.rejected("right"), 1u);
  EXPECT_FALSE(depth.take_latest(d));
  // Data shorter than its size says.
  msg::Image truncated = r;
  truncated.data().resize(1000);
  EXPECT_NE(run(l, truncated).find("input 'right': rejected a sample: data of 1000 bytes, shorter than step x height"),
            std::string::npos);
  EXPECT_EQ(h.rejected("right"), 2u);
  EXPECT_FALSE(depth.take_latest(d));
  // Intrinsics of another image size.
  info.write(intrinsics(1280, 720));
  EXPECT_NE(run(l, r).find("camera_info is for 1280x720 but the images are 640x480"), std::string::npos);
  EXPECT_FALSE(depth.take_latest(d));
  msg::CameraInfo no_focal = intrinsics();
  no_focal.k()[0] = 0;
  info.write(no_focal);  // rejected: the previous (1280x720) intrinsics stay
  EXPECT_NE(run(l, r).find("input 'camera_info': rejected a sample: no focal length"), std::string::npos);
  EXPECT_EQ(h.rejected("camera_info"), 1u);
  EXPECT_FALSE(depth.take_latest(d));
  // Good input again: depth; a keyed image of another size gives no hand position.
  info.write(intrinsics());
  msg::Image small_keyed;
  small_keyed.width(2), small_keyed.height(2), small_keyed.encoding("rgba8"), small_keyed.step(8);
  small_keyed.data().assign(16, 255);
  small_keyed.header().stamp_ns(t + 40'000'000);
  keyed.write(small_keyed);
  EXPECT_NE(run(l, r).find("input 'keyed': rejected a sample: size 2x2, expected 640x480 (the stereo pair's)"),
            std::string::npos);
  EXPECT_EQ(h.rejected("keyed"), 1u);
  EXPECT_TRUE(depth.take_latest(d));
  msg::HandPosition p;
  EXPECT_FALSE(hand.take_latest(p));
}

}  // namespace wysiwyf::vision
