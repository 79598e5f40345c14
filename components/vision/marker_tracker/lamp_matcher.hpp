#pragma once
// Which blob is which lamp, given where the filter predicts the lamps: of the assignments that
// give each lamp at most one blob and each blob at most one lamp, every pair inside the
// chi-square gate, the one that names the most lamps and, among those, whose pixels lie nearest
// one pose (the smallest joint Mahalanobis distance). Lamp by lamp, an uncertain prediction lets
// an early lamp take a later lamp's blob (seen edge-on, the plate's lamps lie close in the
// image), and the filter believes the wrong correspondence; and overlapping search windows let
// several lamps take one blob. `ambiguous`: another assignment of as many lamps is nearly as
// good, so the blobs do not say which lamp they are.
#include <Eigen/Core>

#include <array>
#include <vector>

#include "bright_blobs/blob_detector.hpp"
#include "pose_ekf.hpp"

namespace wysiwyf::vision {

struct LampMatch {
  std::array<int, 4> blob_of_lamp{-1, -1, -1, -1};  // -1: no blob for that lamp
  int matched = 0;
  double d2 = 0;           // joint squared Mahalanobis distance of the matched pixels
  bool ambiguous = false;  // another assignment of as many lamps is within the margin of it
};

class LampMatcher {
 public:
  // Forgets the last image's blobs and predictions (keeps the memory).
  void clear();
  // A blob (image pixels) and where it is in ideal pixels; a blob already added (the same
  // pixels, found again in an overlapping search window) is not added twice. Its index.
  int add_blob(const Blob& blob, const Eigen::Vector2d& ideal);
  // Lamp `lamp` is predicted in view, at `prediction`.
  void predict(int lamp, const PoseEkf::Prediction& prediction);
  // The best assignment; gate: chi-square for one pixel (2 degrees of freedom); ambiguity: how
  // much larger another assignment's joint distance may be and still be as plausible.
  LampMatch solve(const PoseEkf& filter, double gate, double ambiguity);

  int blobs() const { return static_cast<int>(blobs_.size()); }
  const Blob& blob(int i) const { return blobs_[static_cast<std::size_t>(i)]; }
  const Eigen::Vector2d& ideal(int i) const { return ideal_[static_cast<std::size_t>(i)]; }
  const PoseEkf::Prediction& prediction(int lamp) const { return predictions_[static_cast<std::size_t>(lamp)]; }

 private:
  void search(const PoseEkf& filter, int lamp, LampMatch& current);

  std::vector<Blob> blobs_;
  std::vector<Eigen::Vector2d> ideal_;
  std::vector<bool> taken_;
  std::array<PoseEkf::Prediction, 4> predictions_{};
  std::array<bool, 4> predicted_{};
  std::array<std::vector<int>, 4> candidates_;  // blobs inside each lamp's gate
  LampMatch best_;
  double runner_up_d2_ = 0;
};

}  // namespace wysiwyf::vision
