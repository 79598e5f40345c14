#include "lamp_matcher.hpp"

#include <algorithm>
#include <limits>

namespace wysiwyf::vision {

void LampMatcher::clear() {
  blobs_.clear(), ideal_.clear();
  predicted_.fill(false);
}

int LampMatcher::add_blob(const Blob& blob, const Eigen::Vector2d& ideal) {
  for (std::size_t i = 0; i < blobs_.size(); ++i)
    if (blobs_[i].box == blob.box && blobs_[i].area == blob.area) return static_cast<int>(i);
  blobs_.push_back(blob);
  ideal_.push_back(ideal);
  return static_cast<int>(blobs_.size()) - 1;
}

void LampMatcher::predict(int lamp, const PoseEkf::Prediction& prediction) {
  predictions_[static_cast<std::size_t>(lamp)] = prediction;
  predicted_[static_cast<std::size_t>(lamp)] = true;
}

LampMatch LampMatcher::solve(const PoseEkf& filter, double gate, double ambiguity) {
  for (std::size_t lamp = 0; lamp < 4; ++lamp) {
    candidates_[lamp].clear();
    if (!predicted_[lamp]) continue;
    for (std::size_t b = 0; b < blobs_.size(); ++b)
      if (PoseEkf::mahalanobis2(predictions_[lamp], ideal_[b]) <= gate)
        candidates_[lamp].push_back(static_cast<int>(b));
  }
  taken_.assign(blobs_.size(), false);
  best_ = LampMatch{};
  runner_up_d2_ = std::numeric_limits<double>::infinity();
  LampMatch current;
  search(filter, 0, current);
  best_.ambiguous = best_.matched > 0 && runner_up_d2_ <= best_.d2 + ambiguity;
  return best_;
}

void LampMatcher::search(const PoseEkf& filter, int lamp, LampMatch& current) {
  if (lamp == 4) {
    if (current.matched == 0) return;
    const PoseEkf::Prediction* predictions[4];
    Eigen::Vector2d pixels[4];
    int n = 0;
    for (std::size_t i = 0; i < 4; ++i) {
      const int b = current.blob_of_lamp[i];
      if (b < 0) continue;
      predictions[n] = &predictions_[i];
      pixels[n++] = ideal_[static_cast<std::size_t>(b)];
    }
    current.d2 = filter.joint_mahalanobis2(predictions, pixels, n);
    if (current.matched > best_.matched) {
      runner_up_d2_ = std::numeric_limits<double>::infinity();  // every earlier one named fewer lamps
      best_ = current;
    } else if (current.matched == best_.matched) {
      if (current.d2 < best_.d2) {
        runner_up_d2_ = best_.d2;
        best_ = current;
      } else {
        runner_up_d2_ = std::min(runner_up_d2_, current.d2);
      }
    }
    return;
  }
  const auto l = static_cast<std::size_t>(lamp);
  search(filter, lamp + 1, current);  // this lamp unseen
  for (const int b : candidates_[l]) {
    if (taken_[static_cast<std::size_t>(b)]) continue;
    taken_[static_cast<std::size_t>(b)] = true;
    current.blob_of_lamp[l] = b, ++current.matched;
    search(filter, lamp + 1, current);
    current.blob_of_lamp[l] = -1, --current.matched;
    taken_[static_cast<std::size_t>(b)] = false;
  }
}

}  // namespace wysiwyf::vision
