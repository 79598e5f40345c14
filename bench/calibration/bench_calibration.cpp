// How long each calibration step takes, and how many poses or views it needs for its thresholds:
// each step timed on simulated data (tests/calibration's truth: the shipped camera and tool
// perturbed by seeded errors), and its error against the truth as counters, the largest over
// several seeds, per number of poses or views. Thresholds (issue 53): bias 0.05 N and mass 2 %;
// focal length 0.3 % and principal point 0.5 px; the camera's pose 0.5 mm and 0.05 deg. A set the
// step refuses (too little coverage or rotation) counts in `refused`, the errors are the accepted
// sets'; the time is the first seed's, refused or not.
#include <benchmark/benchmark.h>

#include <map>
#include <random>

#include "../common/smoke.hpp"
#include "calibration/board_view_sim.hpp"
#include "calibration/camera_file.hpp"
#include "calibration/intrinsics_fit.hpp"
#include "calibration/robot_world_fit.hpp"
#include "calibration/robot_world_poses.hpp"
#include "wrist_calibration/tool_load_fit.hpp"
#include "wrist_calibration/wrist_poses.hpp"

namespace {

namespace cal = wysiwyf::vision::calibration;
namespace robot = wysiwyf::robot;

const std::string kConfig = WYSIWYF_CONFIG_DIR;

int seeds() { return wysiwyf::bench::smoke() ? 1 : 5; }

cal::CameraIntrinsics perturbed_camera(unsigned seed) {
  return cal::perturbed_camera(cal::load_camera_file(kConfig + "/calibration/sim_camera.yaml").intrinsics, seed);
}

// ---- the wrist: poses from wrist_calibration_poses, arm_sim's sensor noise, one sample per pose
void BM_WristFit(benchmark::State& state) {
  const robot::ArmModel arm(kConfig + "/robots/puma560.urdf", "ft_sensor");
  const robot::FrameId sensor = arm.frame("ft_sensor");
  Eigen::VectorXd home(6);
  home << 0.0, -0.6, 0.3, 0.0, 0.5, 0.0;
  const auto poses = robot::wrist_calibration_poses(arm, home, sensor, static_cast<int>(state.range(0)));
  double bias = 0, mass = 0, refused = 0;
  std::vector<robot::WristReading> first;
  for (int seed = 1; seed <= seeds(); ++seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> n(0, 1);
    const Eigen::Vector3d f0(n(rng), n(rng), n(rng)), t0 = 0.05 * Eigen::Vector3d(n(rng), n(rng), n(rng));
    const double m = 1.1563 * (1 + 0.2 * n(rng));
    const Eigen::Vector3d c(0.002, -0.001, 0.01665);
    std::vector<robot::WristReading> readings;
    for (const auto& q : poses) {
      robot::WristReading r;
      r.label = "pose";
      r.gravity_sensor = robot::gravity_in_frame(arm, q, sensor);
      r.force = f0 + m * r.gravity_sensor + 0.05 * Eigen::Vector3d(n(rng), n(rng), n(rng));
      r.torque = t0 + c.cross(m * r.gravity_sensor) + 0.002 * Eigen::Vector3d(n(rng), n(rng), n(rng));
      readings.push_back(r);
    }
    const robot::ToolLoadFit fit = robot::fit_tool_load(readings);
    if (first.empty()) first = readings;
    if (!fit.accepted) {
      ++refused;
      continue;
    }
    bias = std::max(bias, (fit.force_bias - f0).norm());
    mass = std::max(mass, 100 * std::abs(fit.tool_mass - m) / m);
  }
  for (auto _ : state) benchmark::DoNotOptimize(robot::fit_tool_load(first));
  state.counters["bias_error_N"] = bias;
  state.counters["mass_error_pct"] = mass;
  state.counters["refused"] = refused;
}
BENCHMARK(BM_WristFit)->Arg(6)->Arg(8)->Arg(12)->Arg(24)->Unit(benchmark::kMicrosecond);

// ---- the intrinsics: rendered views (cached per seed), detected once
struct ViewSet {
  cal::CameraIntrinsics truth;
  std::vector<cv::Mat> images;
  std::vector<cal::BoardDetection> detections;
};

const cal::CharucoTarget& target() {
  static const cal::CharucoTarget t{cal::CharucoSpec{}};
  return t;
}

const ViewSet& views(unsigned seed) {
  static std::map<unsigned, ViewSet> cache;
  auto it = cache.find(seed);
  if (it != cache.end()) return it->second;
  ViewSet s;
  s.truth = perturbed_camera(seed);
  std::mt19937 rng(seed);
  const cal::BoardViewSim sim(target(), s.truth);
  for (const auto& pose : cal::board_view_poses(target(), s.truth, 32, rng)) {
    s.images.push_back(sim.render(pose, {}, rng));
    s.detections.push_back(cal::detect_board(s.images.back(), target(), "view"));
  }
  return cache.emplace(seed, std::move(s)).first->second;
}

void BM_BoardDetection(benchmark::State& state) {
  const ViewSet& s = views(11);
  std::size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(cal::detect_board(s.images[i++ % s.images.size()], target(), "view"));
}
BENCHMARK(BM_BoardDetection)->Unit(benchmark::kMillisecond);

void BM_IntrinsicsFit(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  double focal = 0, pp = 0, refused = 0;
  for (int seed = 11; seed < 11 + seeds(); ++seed) {
    const ViewSet& s = views(static_cast<unsigned>(seed));
    const cal::IntrinsicsFit fit =
        cal::fit_intrinsics({s.detections.begin(), s.detections.begin() + static_cast<std::ptrdiff_t>(n)}, target());
    if (!fit.accepted) {
      ++refused;
      continue;
    }
    const cv::Matx33d &K = fit.camera.camera_matrix, &T = s.truth.camera_matrix;
    focal = std::max({focal, 100 * std::abs(K(0, 0) / T(0, 0) - 1), 100 * std::abs(K(1, 1) / T(1, 1) - 1)});
    pp = std::max(pp, std::hypot(K(0, 2) - T(0, 2), K(1, 2) - T(1, 2)));
  }
  const ViewSet& s = views(11);
  const std::vector<cal::BoardDetection> used(s.detections.begin(),
                                              s.detections.begin() + static_cast<std::ptrdiff_t>(n));
  for (auto _ : state) benchmark::DoNotOptimize(cal::fit_intrinsics(used, target()));
  state.counters["focal_error_pct"] = focal;
  state.counters["principal_point_error_px"] = pp;
  state.counters["refused"] = refused;
}
BENCHMARK(BM_IntrinsicsFit)
    ->Arg(12)
    ->Arg(16)
    ->Arg(24)
    ->Arg(32)
    ->Iterations(wysiwyf::bench::iterations(3))
    ->Unit(benchmark::kMillisecond);

// ---- the camera's pose: generated poses, projected corners with 0.2 px of noise
void BM_RobotWorldFit(benchmark::State& state) {
  const robot::ArmModel arm(kConfig + "/robots/puma560.urdf", "dev");
  const robot::FrameId flange = arm.frame("flange");
  const auto shipped = cal::load_camera_file(kConfig + "/calibration/sim_camera.yaml");
  Eigen::VectorXd home(6);
  home << 0.344932, 0.380005, -3.43618, 0.346061, 1.49034, 3.11254;
  const Eigen::VectorXd q0 = Eigen::VectorXd::Zero(6);
  const Eigen::Isometry3d mount =
      arm.fk(q0, flange).inverse() * arm.fk(q0, arm.frame("dev")) * cal::dev_T_board(target());
  double mm = 0, deg = 0, refused = 0;
  std::vector<cal::FlangeView> first;
  cal::CameraIntrinsics first_camera;
  for (int seed = 31; seed < 31 + seeds(); ++seed) {
    std::mt19937 rng(static_cast<unsigned>(seed));
    std::normal_distribution<float> noise(0.0f, 0.2f);
    const cal::CameraIntrinsics camera = perturbed_camera(static_cast<unsigned>(seed));
    const Eigen::Isometry3d base_T_eye = *shipped.base_T_eye * Eigen::Translation3d(0.01, -0.01, 0.005) *
                                         Eigen::AngleAxisd(0.02, Eigen::Vector3d::UnitY());
    const auto poses = cal::robot_world_poses(arm, home, flange, mount, *shipped.base_T_eye, camera, target(),
                                              static_cast<int>(state.range(0)), rng);
    std::vector<cal::FlangeView> seen;
    for (const auto& q : poses) {
      cal::FlangeView v{"pose", arm.fk(q, flange), {}, {}};
      const auto p = cal::project(camera, base_T_eye.inverse() * v.base_T_flange * mount, target().corners());
      for (std::size_t i = 0; i < p.size(); ++i) {
        v.corners.emplace_back(p[i].x + noise(rng), p[i].y + noise(rng));
        v.ids.push_back(static_cast<int>(i));
      }
      seen.push_back(v);
    }
    const cal::RobotWorldFit fit = cal::fit_robot_world(seen, target(), camera);
    if (first.empty()) first = seen, first_camera = camera;
    if (!fit.accepted) {
      ++refused;
      continue;
    }
    mm = std::max(mm, 1e3 * (fit.base_T_eye.translation() - base_T_eye.translation()).norm());
    deg = std::max(deg,
                   Eigen::AngleAxisd(base_T_eye.linear().transpose() * fit.base_T_eye.linear()).angle() * 180 / M_PI);
  }
  for (auto _ : state) benchmark::DoNotOptimize(cal::fit_robot_world(first, target(), first_camera));
  state.counters["camera_error_mm"] = mm;
  state.counters["camera_error_deg"] = deg;
  state.counters["refused"] = refused;
}
BENCHMARK(BM_RobotWorldFit)
    ->Arg(8)
    ->Arg(12)
    ->Arg(20)
    ->Arg(30)
    ->Iterations(wysiwyf::bench::iterations(5))
    ->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
