// wysiwyf calibrate lamps: the plate's lamps on the flange from a fixed camera watching them while
// the arm moves through poses (the views file of camera-base-poses, an image at each), fitted with
// the camera's pose (lamp_fit.hpp), and written into a copy of the arm's URDF (the marker_* links
// the marker tracker and the camera simulation read).
#include <iostream>
#include <map>

#include "calibrate_options.hpp"
#include "bright_blobs/blob_detector.hpp"
#include "calibration/camera_model.hpp"
#include "calibration/flange_views_file.hpp"
#include "calibration/lamp_fit.hpp"
#include "calibration/lamp_urdf.hpp"

namespace wysiwyf::cli {

namespace {

namespace cal = vision::calibration;

// The URDF's lamps: links marker_0, marker_1, ... as far as they go.
std::vector<std::string> lamp_links(const robot::ArmModel& arm) {
  std::vector<std::string> out;
  for (int i = 0;; ++i) try {
      arm.frame("marker_" + std::to_string(i));
      out.push_back("marker_" + std::to_string(i));
    } catch (const std::out_of_range&) {
      return out;
    }
}

// Each lamp's blob: the blob nearest where the lamp should be (the nominal lamps through the
// camera's rough pose), within `gate` px, and nearer that lamp than any other; else not seen.
std::vector<std::optional<cv::Point2d>> match(const std::vector<vision::Blob>& blobs,
                                              const std::vector<cv::Point2f>& predicted, double gate) {
  std::vector<std::optional<cv::Point2d>> out(predicted.size());
  auto dist = [](const vision::Blob& b, const cv::Point2f& p) { return std::hypot(b.u - p.x, b.v - p.y); };
  for (std::size_t i = 0; i < predicted.size(); ++i) {
    const vision::Blob* best = nullptr;
    for (const auto& b : blobs)
      if (dist(b, predicted[i]) <= gate && (!best || dist(b, predicted[i]) < dist(*best, predicted[i]))) best = &b;
    if (!best) continue;
    bool mutual = true;
    for (std::size_t j = 0; j < predicted.size(); ++j)
      mutual = mutual && (j == i || dist(*best, predicted[j]) > dist(*best, predicted[i]));
    if (mutual) out[i] = cv::Point2d(best->u, best->v);
  }
  return out;
}

}  // namespace

// lamps --camera FILE --views FILE --out URDF [--urdf U] [--gate PX] [--threshold L] [limits]
int calibrate_lamps(Args& args) {
  const cal::CameraFile camera = camera_option(args);
  if (!camera.base_T_eye)
    throw UsageError("--camera: expected a base_T_eye in it, the camera's pose as measured roughly (a few cm)");
  const std::string views_file = required(args, "--views", "the views file (wysiwyf calibrate camera-base-poses)");
  const std::string out = required(args, "--out", "the URDF to write, with the lamps where they were found");
  const double gate = number_option(args, "--gate", 25, 1, 500, "px a lamp's blob may lie from where it should be");
  vision::BlobSettings blobs;
  blobs.threshold = static_cast<int>(whole_option(args, "--threshold", blobs.threshold, 1, 254, "a luma, 1 to 254"));
  cal::LampLimits limits;
  limits.min_views = static_cast<int>(whole_option(args, "--min-views", limits.min_views, 3, 1000, "3 or more"));
  limits.max_view_error = number_option(args, "--max-view-error", limits.max_view_error, 0, 100, "px");
  const auto arm = arm_option(args, "dev");
  no_unknown_options(args);
  const std::string urdf = arm->urdf_path();
  robot::FrameId flange;
  try {
    flange = arm->frame("flange");
  } catch (const std::out_of_range&) {
    throw UsageError("--urdf: " + urdf + " has no link 'flange'");
  }
  const std::vector<std::string> links = lamp_links(*arm);
  if (links.size() < 3)
    throw UsageError("--urdf: " + urdf + " has " + std::to_string(links.size()) +
                     " lamps (links marker_0, marker_1, ...); expected at least 3");
  const Eigen::VectorXd q0 = Eigen::VectorXd::Zero(arm->dof());
  const Eigen::Isometry3d flange_T_base0 = arm->fk(q0, flange).inverse();
  std::vector<Eigen::Vector3d> nominal;
  std::vector<cv::Point3f> nominal_points;
  for (const auto& l : links) {
    nominal.push_back(flange_T_base0 * arm->fk(q0, arm->frame(l)).translation());
    nominal_points.emplace_back(nominal.back().cast<float>().x(), nominal.back().cast<float>().y(),
                                nominal.back().cast<float>().z());
  }
  std::vector<cal::FlangeViewEntry> entries;
  try {
    entries = cal::load_flange_views(views_file, arm->dof());
  } catch (const std::exception& e) {
    throw UsageError(e.what());
  }
  vision::BlobDetector detector(blobs);
  std::vector<cal::LampView> views;
  std::vector<vision::Blob> found;
  for (const cal::FlangeViewEntry& e : entries) {
    const cv::Mat image = read_view(e, views_file, *arm, camera.intrinsics);
    cal::LampView v;
    v.label = e.label;
    v.base_T_flange = arm->fk(e.joints, flange);
    found.clear();
    detector.detect_all(image, vision::PixelLayout::kMono8, found);
    v.lamp = match(
        found, cal::project(camera.intrinsics, camera.base_T_eye->inverse() * v.base_T_flange, nominal_points), gate);
    views.push_back(std::move(v));
  }
  const cal::LampFit fit = cal::fit_lamps(views, camera.intrinsics, nominal, limits);
  for (std::size_t i = 0; i < views.size(); ++i)
    std::printf("  %-12s %s\n", views[i].label.c_str(),
                fit.view_rms.size() > i && fit.view_rms[i] >= 0 ? (std::to_string(fit.view_rms[i]) + " px").c_str()
                                                                : "no lamp seen");
  if (!fit.accepted) {
    std::cout << "refused: " << fit.refusal << "\n";
    return 1;
  }
  std::map<std::string, Eigen::Vector3d> parent_p_lamp;
  for (std::size_t i = 0; i < links.size(); ++i) {
    std::string parent;
    try {
      parent = cal::joint_parent(urdf, links[i]);
    } catch (const std::exception& e) {
      throw UsageError(std::string("--urdf: ") + e.what());
    }
    const Eigen::Isometry3d parent_T_flange = arm->fk(q0, arm->frame(parent)).inverse() * arm->fk(q0, flange);
    parent_p_lamp[links[i]] = parent_T_flange * fit.flange_p_lamp[i];
    std::printf("  %s: %.2f mm from the URDF's\n", links[i].c_str(), 1e3 * (fit.flange_p_lamp[i] - nominal[i]).norm());
  }
  std::printf("RMS reprojection error %.3f px over %zu views\n", fit.rms, views.size());
  try {
    cal::write_lamps_urdf(urdf, out, parent_p_lamp,
                          "marker_* origins from wysiwyf calibrate lamps: " + std::to_string(views.size()) +
                              " poses of " + views_file + ", RMS reprojection error " + std::to_string(fit.rms) +
                              " px");
  } catch (const std::exception& e) {
    throw UsageError(e.what());
  }
  std::cout << "wrote " << out << "\n";
  return 0;
}

}  // namespace wysiwyf::cli
