#include "rigid_body/broad_phase.hpp"

#include <algorithm>

namespace wysiwyf::haptics {

namespace {

// A box's world-axis bounding box: centre +- |R| h, grown by the margin.
BodyExtent extent_of(const BodyModel& m, const Pose& p, double margin) {
  const Vec3 reach = p.R.cwiseAbs() * m.half_extents + Vec3::Constant(margin);
  return BodyExtent{p.x - reach, p.x + reach};
}

bool overlap(const BodyExtent& a, const BodyExtent& b) {
  return (a.lo.array() <= b.hi.array()).all() && (b.lo.array() <= a.hi.array()).all();
}

// (a, b) in the contacts' order, or false for two static bodies.
bool ordered(const WorldModel& model, int i, int j, BodyPair& pair) {
  const bool di = model.bodies[i].dynamic, dj = model.bodies[j].dynamic;
  if (!di && !dj) return false;
  if (di && dj)
    pair = {std::min(i, j), std::max(i, j)};
  else
    pair = di ? BodyPair{i, j} : BodyPair{j, i};
  return true;
}

}  // namespace

void SweepAndPrune::pairs(const WorldModel& model, const std::vector<Pose>& poses, double margin,
                          std::vector<BodyPair>& out) {
  out.clear();
  const int n = model.body_count();
  boxes_.resize(static_cast<std::size_t>(n));
  Vec3 sum = Vec3::Zero(), sum2 = Vec3::Zero();
  for (int i = 0; i < n; ++i) {
    boxes_[static_cast<std::size_t>(i)] = extent_of(model.bodies[i], poses[i], margin);
    sum += poses[i].x;
    sum2 += poses[i].x.cwiseAbs2();
  }
  // Sweep along the axis of the largest spread of the centres: the fewest intervals overlap there.
  (sum2 - sum.cwiseAbs2() / n).maxCoeff(&axis_);
  if (order_.size() != static_cast<std::size_t>(n)) {
    order_.resize(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) order_[static_cast<std::size_t>(i)] = i;
  }
  const auto lo = [&](int i) { return boxes_[static_cast<std::size_t>(i)].lo[axis_]; };
  for (std::size_t k = 1; k < order_.size(); ++k)  // insertion sort: last call's order is nearly right
    for (std::size_t j = k; j > 0 && lo(order_[j - 1]) > lo(order_[j]); --j) std::swap(order_[j - 1], order_[j]);
  open_.clear();
  for (const int i : order_) {
    const BodyExtent& bi = boxes_[static_cast<std::size_t>(i)];
    // Close the intervals that end before this one starts.
    open_.erase(std::remove_if(open_.begin(), open_.end(),
                               [&](int j) { return boxes_[static_cast<std::size_t>(j)].hi[axis_] < bi.lo[axis_]; }),
                open_.end());
    for (const int j : open_) {
      BodyPair pair;
      if (overlap(bi, boxes_[static_cast<std::size_t>(j)]) && ordered(model, i, j, pair)) out.push_back(pair);
    }
    open_.push_back(i);
  }
  std::sort(out.begin(), out.end());
}

void all_pairs(const WorldModel& model, const std::vector<Pose>& poses, double margin, std::vector<BodyPair>& out) {
  out.clear();
  const int n = model.body_count();
  std::vector<BodyExtent> boxes;
  for (int i = 0; i < n; ++i) boxes.push_back(extent_of(model.bodies[i], poses[i], margin));
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j) {
      BodyPair pair;
      if (overlap(boxes[static_cast<std::size_t>(i)], boxes[static_cast<std::size_t>(j)]) && ordered(model, i, j, pair))
        out.push_back(pair);
    }
  std::sort(out.begin(), out.end());
}

}  // namespace wysiwyf::haptics
