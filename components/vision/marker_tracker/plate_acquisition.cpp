#include "plate_acquisition.hpp"

#include <opencv2/calib3d.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace wysiwyf::vision {

namespace {

struct Fit {
  Eigen::Isometry3d eye_T_dev;
  std::array<int, 4> blob_of_marker;
  double rms;
};

Eigen::Isometry3d to_isometry(const cv::Mat& rvec, const cv::Mat& tvec) {
  cv::Matx33d R;
  cv::Rodrigues(rvec, R);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) T.linear()(r, c) = R(r, c);
    T.translation()[r] = tvec.at<double>(r);
  }
  return T;
}

// The blobs most likely to be lamps when there are too many: those nearest the median area.
std::vector<int> candidates(const std::vector<Blob>& blobs, int max_count) {
  std::vector<int> idx(blobs.size());
  std::iota(idx.begin(), idx.end(), 0);
  if (static_cast<int>(idx.size()) <= max_count) return idx;
  std::vector<int> areas;
  for (const auto& b : blobs) areas.push_back(b.area);
  std::nth_element(areas.begin(), areas.begin() + static_cast<long>(areas.size() / 2), areas.end());
  const int median = areas[areas.size() / 2];
  std::sort(idx.begin(), idx.end(),
            [&](int a, int b) { return std::abs(blobs[a].area - median) < std::abs(blobs[b].area - median); });
  idx.resize(static_cast<std::size_t>(max_count));
  return idx;
}

// Fits of one set of four blobs: every cyclic order around their centre, both directions, and
// both IPPE solutions.
void fit_four(const std::vector<Blob>& blobs, std::array<int, 4> four, const PlateMarkers& plate,
              const CameraModel& camera, double max_rms, std::vector<Fit>& fits) {
  double cu = 0, cv = 0;
  for (int i : four) cu += blobs[static_cast<std::size_t>(i)].u / 4, cv += blobs[static_cast<std::size_t>(i)].v / 4;
  std::sort(four.begin(), four.end(), [&](int a, int b) {
    return std::atan2(blobs[static_cast<std::size_t>(a)].v - cv, blobs[static_cast<std::size_t>(a)].u - cu) <
           std::atan2(blobs[static_cast<std::size_t>(b)].v - cv, blobs[static_cast<std::size_t>(b)].u - cu);
  });
  std::vector<cv::Point3d> object;
  for (const auto& p : plate.dev_p) object.emplace_back(p.x(), p.y(), p.z());
  std::vector<cv::Point2d> image(4);
  std::vector<cv::Mat> rvecs, tvecs;
  cv::Mat errors;
  for (int direction : {1, -1})
    for (int shift = 0; shift < 4; ++shift) {
      std::array<int, 4> order{};
      for (int m = 0; m < 4; ++m) {
        order[static_cast<std::size_t>(m)] = four[static_cast<std::size_t>(((shift + direction * m) % 4 + 4) % 4)];
        const Blob& b = blobs[static_cast<std::size_t>(order[static_cast<std::size_t>(m)])];
        image[static_cast<std::size_t>(m)] = cv::Point2d(b.u, b.v);
      }
      const int n = cv::solvePnPGeneric(object, image, camera.matrix(), cv::noArray(), rvecs, tvecs, false,
                                        cv::SOLVEPNP_IPPE, cv::noArray(), cv::noArray(), errors);
      for (int s = 0; s < n; ++s) {
        const double rms = errors.at<double>(s);
        if (!(rms <= max_rms)) continue;
        const Eigen::Isometry3d eye_T_dev =
            to_isometry(rvecs[static_cast<std::size_t>(s)], tvecs[static_cast<std::size_t>(s)]);
        if (eye_T_dev.translation().z() <= 0) continue;
        if (PlateMarkers::facing(eye_T_dev.translation(), eye_T_dev.linear() * plate.dev_normal) < 0.05)
          continue;  // its back: lamps unseen
        fits.push_back(Fit{eye_T_dev, order, rms});
      }
    }
}

}  // namespace

std::optional<PlateFix> acquire_plate(const std::vector<Blob>& blobs, const PlateMarkers& plate,
                                      const CameraModel& camera,
                                      const std::function<double(const Eigen::Isometry3d&, double)>& cost,
                                      const AcquisitionSettings& settings) {
  const std::vector<int> idx = candidates(blobs, settings.max_candidates);
  const int n = static_cast<int>(idx.size());
  if (n < 4) return std::nullopt;
  std::vector<Fit> fits;
  for (int a = 0; a < n; ++a)
    for (int b = a + 1; b < n; ++b)
      for (int c = b + 1; c < n; ++c)
        for (int d = c + 1; d < n; ++d)
          fit_four(blobs,
                   {idx[static_cast<std::size_t>(a)], idx[static_cast<std::size_t>(b)],
                    idx[static_cast<std::size_t>(c)], idx[static_cast<std::size_t>(d)]},
                   plate, camera, settings.max_rms_px, fits);
  // A fit whose cost is infinite is impossible (the caller knows where the camera cannot be):
  // the near-equal ones are chosen among the rest.
  std::vector<double> costs(fits.size());
  double best_rms = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < fits.size(); ++i) {
    costs[i] = cost(fits[i].eye_T_dev, fits[i].rms);
    if (std::isfinite(costs[i])) best_rms = std::min(best_rms, fits[i].rms);
  }
  const Fit* chosen = nullptr;
  double chosen_cost = 0;
  int plausible = 0;
  for (std::size_t i = 0; i < fits.size(); ++i) {
    if (!std::isfinite(costs[i]) || fits[i].rms > best_rms + settings.ambiguity_px) continue;
    ++plausible;
    if (!chosen || costs[i] < chosen_cost) chosen = &fits[i], chosen_cost = costs[i];
  }
  if (!chosen) return std::nullopt;
  return PlateFix{chosen->eye_T_dev, chosen->blob_of_marker, chosen->rms, plausible};
}

}  // namespace wysiwyf::vision
