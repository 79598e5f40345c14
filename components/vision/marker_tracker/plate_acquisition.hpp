#pragma once
// First fix of the plate from bright blobs alone (at start and after loss): which blob is which
// lamp, and eye_T_dev, by OpenCV's IPPE (the lamps are coplanar). Every choice of four blobs (up
// to 8 candidates), every cyclic order of them around their centre (both directions), and both
// of IPPE's solutions for a planar target are evaluated; those that reproject within max_rms_px and
// show the plate's front to the camera remain. The square's four-fold symmetry and IPPE's
// two-fold ambiguity leave several near-equal fits; `cost` picks among those whose reprojection
// error is within `ambiguity_px` of the best (continuity with the last estimate, or which way
// is up). An infinite cost rules a fit out before that (a camera pose that cannot be).
#include <Eigen/Geometry>

#include <array>
#include <functional>
#include <optional>
#include <vector>

#include "camera_model.hpp"
#include "bright_blobs/blob_detector.hpp"
#include "plate_markers.hpp"

namespace wysiwyf::vision {

struct PlateFix {
  Eigen::Isometry3d eye_T_dev = Eigen::Isometry3d::Identity();
  std::array<int, 4> blob_of_marker{};  // index into the blobs given
  double rms_px = 0;                    // reprojection error of the chosen solution
  int hypotheses = 0;                   // fits that were good enough to choose from
};

struct AcquisitionSettings {
  double max_rms_px = 2.0;    // a fit worse than this is no plate
  double ambiguity_px = 0.5;  // fits within this of the best are equally plausible
  int max_candidates = 8;     // blobs considered (those nearest the median size)
};

// blobs: centroids in ideal (undistorted) pixels. Empty when no choice fits.
std::optional<PlateFix> acquire_plate(
    const std::vector<Blob>& blobs, const PlateMarkers& plate, const CameraModel& camera,
    const std::function<double(const Eigen::Isometry3d& eye_T_dev, double rms_px)>& cost,
    const AcquisitionSettings& settings = {});

}  // namespace wysiwyf::vision
