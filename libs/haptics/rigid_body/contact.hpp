#pragma once
// Contacts between boxes, as features that can be re-evaluated at any state: a vertex of one box
// against a face of another, or an edge against an edge. The normal points from body b to body a
// (outward from b's surface, as in the paper's section 4.1); the gap is the signed distance along
// it (negative: penetration).
#include <cstdint>
#include <vector>

#include "scene/body.hpp"

namespace wysiwyf::haptics {

enum class ContactKind { kVertexFace, kEdgeEdge };

struct ContactFeature {
  ContactKind kind = ContactKind::kVertexFace;
  int a = 0, b = 0;   // body indices
  int feature_a = 0;  // vertex (vertex-face) or edge (edge-edge) of a
  int feature_b = 0;  // face 0..5 = -x, +x, -y, +y, -z, +z (vertex-face) or edge of b
  double sign = 1;    // edge-edge: orientation of e_a x e_b that points out of b
  bool operator==(const ContactFeature& o) const {
    return kind == o.kind && a == o.a && b == o.b && feature_a == o.feature_a && feature_b == o.feature_b;
  }
};

// slot: body -> its place among the dynamic bodies, or -1 for a static one (WorldModel::slot).
// A feature's dynamic body (a, unless a is static; no feature joins two static bodies), which
// names the island or integration group the feature belongs to.
inline int dynamic_body(const ContactFeature& f, const std::vector<int>& slot) { return slot[f.a] >= 0 ? f.a : f.b; }
// Whether the feature joins two dynamic bodies into one island or group (a static one joins none).
inline bool joins_dynamic_bodies(const ContactFeature& f, const std::vector<int>& slot) {
  return slot[f.a] >= 0 && slot[f.b] >= 0;
}

// A feature's identity (ContactFeature's operator==) in one sortable number.
inline std::uint64_t feature_key(const ContactFeature& f) {
  return (static_cast<std::uint64_t>(f.kind) << 60) | (static_cast<std::uint64_t>(f.a & 0xFFFFF) << 40) |
         (static_cast<std::uint64_t>(f.b & 0xFFFFF) << 20) | (static_cast<std::uint64_t>(f.feature_a & 0x3FF) << 10) |
         static_cast<std::uint64_t>(f.feature_b & 0x3FF);
}

struct ContactPoint {
  Vec3 p = Vec3::Zero();     // world point where the forces act
  Vec3 n = Vec3::UnitZ();    // unit normal, from b to a
  Vec3 ndot = Vec3::Zero();  // dn/dt
  double gap = 0;
  bool valid = false;  // the features still face each other
};

// The world pose of each body, enough to evaluate features.
struct Pose {
  Vec3 x;
  Mat3 R;
  Vec3 v, omega;
  double inv_mass = 0;              // 0 for static bodies
  Mat3 inv_inertia = Mat3::Zero();  // world frame; 0 for static bodies
};

ContactPoint evaluate(const ContactFeature& f, const std::vector<BodyModel>& models, const std::vector<Pose>& poses,
                      double slack = 1e-9);

// Whether feature f's normal at c separates the boxes: for an edge-edge feature, each edge is its
// box's extreme point along it, within `cone` (a direction cosine); a vertex-face feature always
// does. Nearly parallel edges lying on each other (equal boxes side by side, their top edges
// together) have a normal of round-off, sideways or up, which would press the boxes together
// along it: their contact is the faces', held by vertex-face ones. Edges that cross
// (kCrossingEdges) separate within kFaceEdgeCone whatever `cone`: one lies on a face beside the
// other, which rests on it where the face ends.
bool separates(const ContactFeature& f, const ContactPoint& c, const std::vector<Pose>& poses, double cone);
// A contact's cone: its normal must separate.
constexpr double kContactCone = 1e-6;
// Edges that cross at least this sine apart while one lies on a face beside the other: within
// this cone of the face's normal they still separate (separates()).
constexpr double kCrossingEdges = 0.1;
constexpr double kFaceEdgeCone = 0.02;
// A feature watched while the boxes are apart: they turn within a step, and an edge pair outside
// its cone at the step's start can be inside it, and crossing, by the step's end (in landing
// piles, from outside the cone to a millimetre deep within 1 ms). 0.2 watches every such pair of
// test_many_bodies' random piles (docs/design/contact-watching.md). Its gap closing counts as an
// impact only inside kContactCone.
constexpr double kWatchedCone = 0.2;

// Every feature pair between body a (dynamic) and body b closer than `margin`. A corner within
// `rim` of a face's edge counts as over the face (evaluate's slack: the same rim). An edge pair is
// one if its normal is in kWatchedCone now or, turning as it does, `horizon` seconds on.
void find_candidates(int a, int b, const std::vector<BodyModel>& models, const std::vector<Pose>& poses, double margin,
                     double rim, double horizon, std::vector<ContactFeature>& out);

}  // namespace wysiwyf::haptics
