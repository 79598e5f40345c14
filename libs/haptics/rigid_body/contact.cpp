#include "rigid_body/contact.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace wysiwyf::haptics {

namespace {

Vec3 corner_world(const BodyModel& m, const Pose& s, int i) {
  return s.x + s.R * BoxTopology::corner(m.half_extents, i);
}

// All eight, from the three half-edge vectors (corner_world's order: x fastest, then y, z).
std::array<Vec3, 8> corners_world(const BodyModel& m, const Pose& s) {
  const Vec3 hx = m.half_extents.x() * s.R.col(0), hy = m.half_extents.y() * s.R.col(1),
             hz = m.half_extents.z() * s.R.col(2);
  std::array<Vec3, 8> c;
  for (int i = 0; i < 8; ++i)
    c[i] = s.x + ((i & 1) ? hx : Vec3(-hx)) + ((i & 2) ? hy : Vec3(-hy)) + ((i & 4) ? hz : Vec3(-hz));
  return c;
}

ContactPoint vertex_face(const ContactFeature& f, const BodyModel& ma, const Pose& sa, const BodyModel& mb,
                         const Pose& sb, double slack) {
  ContactPoint c;
  const int axis = f.feature_b / 2;
  const double side = (f.feature_b % 2) ? 1.0 : -1.0;
  c.p = corner_world(ma, sa, f.feature_a);
  c.n = side * sb.R.col(axis);
  c.ndot = sb.omega.cross(c.n);
  const Vec3 local = sb.R.transpose() * (c.p - sb.x);
  c.gap = side * local[axis] - mb.half_extents[axis];
  c.valid = true;
  for (int j = 0; j < 3; ++j)
    if (j != axis && std::abs(local[j]) > mb.half_extents[j] + slack) c.valid = false;
  return c;
}

// The closest points of two edges (a0 + s da, b0 + t db) and the contact there, normal
// f_sign e_a x e_b; s and t are left for the caller to judge (within the edges, by how much).
struct EdgePair {
  ContactPoint c;
  double s = 0, t = 0;
  double unit = 0;        // the parameter of 1 m along the shorter edge
  bool crossing = false;  // false: parallel, no normal (vertex-face contacts cover it)
};

EdgePair edge_pair(int sign, const Vec3& a0, const Vec3& da, const Vec3& b0, const Vec3& db, const Vec3& omega_a,
                   const Vec3& omega_b) {
  EdgePair e;
  const Vec3 u = da.cross(db);
  const double un = u.norm();
  const double aa = da.dot(da), bb = db.dot(db);
  if (un < 1e-9 * std::sqrt(aa * bb)) return e;
  e.crossing = true;
  const Vec3 w = a0 - b0;
  const double ab = da.dot(db), aw = da.dot(w), bw = db.dot(w);
  const double den = aa * bb - ab * ab;
  e.s = (ab * bw - bb * aw) / den, e.t = (aa * bw - ab * aw) / den;
  e.unit = 1 / std::sqrt(std::min(aa, bb));
  const Vec3 pa = a0 + e.s * da, pb = b0 + e.t * db;
  ContactPoint& c = e.c;
  c.n = sign * u / un;
  c.gap = c.n.dot(pa - pb);
  c.p = 0.5 * (pa + pb);
  const Vec3 udot = omega_a.cross(da).cross(db) + da.cross(omega_b.cross(db));
  const Vec3 nu = u / un;
  c.ndot = sign * (udot - nu * nu.dot(udot)) / un;
  return e;
}

// Whether the closest points lie within both edges, to slack (m; negative: strictly inside).
bool within_edges(const EdgePair& e, double slack) {
  const double rel = slack * e.unit;
  return e.crossing && e.s >= -rel && e.s <= 1 + rel && e.t >= -rel && e.t <= 1 + rel;
}

ContactPoint edge_edge(const ContactFeature& f, const BodyModel& ma, const Pose& sa, const BodyModel& mb,
                       const Pose& sb, double slack) {
  const auto& ea = BoxTopology::edges()[f.feature_a];
  const auto& eb = BoxTopology::edges()[f.feature_b];
  const Vec3 a0 = corner_world(ma, sa, ea[0]), b0 = corner_world(mb, sb, eb[0]);
  EdgePair e =
      edge_pair(f.sign, a0, corner_world(ma, sa, ea[1]) - a0, b0, corner_world(mb, sb, eb[1]) - b0, sa.omega, sb.omega);
  e.c.valid = within_edges(e, slack);
  return e.c;
}

// Whether direction d (world) lies in the quadrant of the outward normals of the two faces that
// meet at `edge` of a box with rotation R: the edge is then the box's support (extreme point)
// along d, within tol.
bool edge_supports(const Mat3& R, const std::array<int, 2>& edge, const Vec3& d, double tol) {
  const Vec3& s0 = BoxTopology::corner_signs()[edge[0]];
  const Vec3& s1 = BoxTopology::corner_signs()[edge[1]];
  for (int axis = 0; axis < 3; ++axis)
    if (s0[axis] == s1[axis] && s0[axis] * R.col(axis).dot(d) < -tol) return false;
  return true;
}

// The direction of `edge` of a box with rotation R, up to its sign: the body axis along which
// its two corners differ.
Vec3 edge_axis(const Mat3& R, const std::array<int, 2>& edge) {
  Eigen::Index axis = 0;
  (BoxTopology::corner_signs()[edge[1]] - BoxTopology::corner_signs()[edge[0]]).cwiseAbs().maxCoeff(&axis);
  return R.col(axis);
}

}  // namespace

bool separates(const ContactFeature& f, const ContactPoint& c, const std::vector<Pose>& poses, double cone) {
  if (f.kind != ContactKind::kEdgeEdge) return true;
  const auto& edges = BoxTopology::edges();
  const auto supported = [&](double within) {
    return edge_supports(poses[f.b].R, edges[f.feature_b], c.n, within) &&
           edge_supports(poses[f.a].R, edges[f.feature_a], -c.n, within);
  };
  if (supported(cone)) return true;
  // Edges that cross at an angle, one lying on a face beside the other (a box flat on a table and
  // over its edge: the table's edge under the box's bottom face, crossing the face's own edges):
  // a tilt of round-off or of the step puts the face, not its edge, at the support, yet where the
  // face ends is where it rests on the other edge. (Nearly parallel edges keep the narrow cone:
  // their normal is round-off.)
  const double crossing =
      edge_axis(poses[f.a].R, edges[f.feature_a]).cross(edge_axis(poses[f.b].R, edges[f.feature_b])).norm();
  return crossing >= kCrossingEdges && supported(std::max(cone, kFaceEdgeCone));
}

ContactPoint evaluate(const ContactFeature& f, const std::vector<BodyModel>& models, const std::vector<Pose>& poses,
                      double slack) {
  const auto& ma = models[f.a];
  const auto& mb = models[f.b];
  return f.kind == ContactKind::kVertexFace ? vertex_face(f, ma, poses[f.a], mb, poses[f.b], slack)
                                            : edge_edge(f, ma, poses[f.a], mb, poses[f.b], slack);
}

void find_candidates(int a, int b, const std::vector<BodyModel>& models, const std::vector<Pose>& poses, double margin,
                     double rim, double horizon, std::vector<ContactFeature>& out) {
  const auto& ma = models[a];
  const auto& mb = models[b];
  const double reach = ma.half_extents.norm() + mb.half_extents.norm() + margin;
  if ((poses[a].x - poses[b].x).squaredNorm() > reach * reach) return;  // bounding spheres apart
  // Deeper than this is the far side of the other box, not a contact.
  const double depth = 0.5 * std::min(ma.half_extents.minCoeff(), mb.half_extents.minCoeff());
  const std::array<Vec3, 8> ca = corners_world(ma, poses[a]), cb = corners_world(mb, poses[b]);
  // Corners of one box against the faces of the other, in the other's frame.
  auto vertex_faces = [&](int va, int vb, const std::array<Vec3, 8>& corners) {
    const Vec3& h = models[vb].half_extents;
    const Pose& pose = poses[vb];
    const Vec3 toward = pose.R.transpose() * (poses[va].x - pose.x);  // this box's centre, other's frame
    for (int v = 0; v < 8; ++v) {
      const Vec3 local = pose.R.transpose() * (corners[v] - pose.x);
      // Inside the other box (or on it): only its nearest face is a contact (the others would
      // push the corner out through the far side, against the true one). Outside: the face the
      // corner is over, if within the margin. Round-off and integration error put a corner that
      // lies on an edge of the other box (equal boxes stacked, or side by side on one table) a
      // hair outside one of the faces that meet there: within the rim, on them; of faces as near
      // within it, the one that looks toward this box's centre: the one the boxes meet at.
      const bool inside = (local.cwiseAbs().array() <= h.array() + rim).all();
      int best = -1;
      double best_gap = -1e300, best_facing = -1e300;
      for (int face = 0; face < 6; ++face) {
        const int axis = face / 2, j = (axis + 1) % 3, k = (axis + 2) % 3;
        if (!inside && (std::abs(local[j]) > h[j] + rim || std::abs(local[k]) > h[k] + rim)) continue;
        const double side = (face % 2) ? 1.0 : -1.0;
        const double gap = side * local[axis] - h[axis];
        const double facing = side * toward[axis] / h[axis];
        if (gap > best_gap + rim || (gap > best_gap - rim && facing > best_facing))
          best = face, best_gap = std::max(gap, best_gap), best_facing = facing;
      }
      if (best >= 0 && best_gap < margin && best_gap > -depth)
        out.push_back(ContactFeature{ContactKind::kVertexFace, va, vb, v, best, 1});
      if (best >= 0 || inside) continue;
      // Over no face: beside an edge or corner of the other box, above the planes of the faces
      // that meet there. Within a step it can come over one of them and into it, so those within
      // the margin are watched too (World: an impact only once the corner is
      // over the face); unwatched, a corner moving in from here would sink into it unseen.
      for (int face = 0; face < 6; ++face) {
        const int axis = face / 2, j = (axis + 1) % 3, k = (axis + 2) % 3;
        const double side = (face % 2) ? 1.0 : -1.0;
        const double gap = side * local[axis] - h[axis];
        const double beside = std::max(std::abs(local[j]) - h[j], std::abs(local[k]) - h[k]);
        if (gap > 0 && gap < margin && beside < margin)
          out.push_back(ContactFeature{ContactKind::kVertexFace, va, vb, v, face, 1});
      }
    }
  };
  vertex_faces(a, b, ca);
  vertex_faces(b, a, cb);  // corners of b on faces of a (a table corner under the cube)
  const auto& edges = BoxTopology::edges();
  // An edge in contact with the other box passes within the other's bounding sphere (a table's
  // far edges, metres away, are not looked at again).
  struct NearEdges {
    std::array<int, 12> index;
    int count = 0;
  };
  auto near_edges = [&](const std::array<Vec3, 8>& corners, const Vec3& centre, double radius) {
    NearEdges near;
    for (int e = 0; e < 12; ++e) {
      const Vec3 e0 = corners[edges[e][0]], de = corners[edges[e][1]] - e0;
      const double s = std::clamp((centre - e0).dot(de) / de.squaredNorm(), 0.0, 1.0);
      if ((e0 + s * de - centre).squaredNorm() <= radius * radius) near.index[near.count++] = e;
    }
    return near;
  };
  const NearEdges near_b = near_edges(cb, poses[a].x, ma.half_extents.norm() + margin);
  const NearEdges near_a = near_b.count ? near_edges(ca, poses[b].x, mb.half_extents.norm() + margin) : NearEdges{};
  for (int i = 0; i < near_a.count; ++i) {
    const int ea = near_a.index[i];
    const Vec3 a0 = ca[edges[ea][0]], da = ca[edges[ea][1]] - a0;
    for (int j = 0; j < near_b.count; ++j) {
      const int eb = near_b.index[j];
      const Vec3 b0 = cb[edges[eb][0]], db = cb[edges[eb][1]] - b0;
      // Cheap rejection: the edges' bounding spheres.
      const double r = 0.5 * (da.norm() + db.norm()) + margin;
      if (((a0 + 0.5 * da) - (b0 + 0.5 * db)).squaredNorm() > r * r) continue;
      ContactFeature f{ContactKind::kEdgeEdge, a, b, ea, eb, 1};
      // Strictly inside both edges: a contact at an edge's end is a vertex-face contact. Apart,
      // the lines' closest points may still be beyond an end by up to the margin and come inside
      // within the step, and then deep (unseen unless watched): watched, an impact only once inside (World).
      const EdgePair pair = edge_pair(f.sign, a0, da, b0, db, poses[a].omega, poses[b].omega);
      ContactPoint c = pair.c;
      c.valid = within_edges(pair, -1e-6);
      if (!c.valid) {
        c.valid = within_edges(pair, margin);
        if (!c.valid || std::abs(c.gap) <= rim) continue;
      }
      if (std::abs(c.gap) > margin) continue;
      if (c.n.dot(c.p - poses[b].x) < 0) f.sign = -1, c.n = -c.n, c.ndot = -c.ndot, c.gap = -c.gap;  // out of b
      // (the watched cone: whether it may become a contact is World's call, in kContactCone)
      if (!separates(f, c, poses, kWatchedCone)) {
        // The normal e_a x e_b / |e_a x e_b| turns 1/sin faster than the edges: for edges crossing
        // at a small sine on a spinning box it can turn from outside the cone to a crossing within
        // one step. Watched as well: a pair whose normal, as it turns now, is in the cone a horizon on.
        ContactPoint ahead = c;
        ahead.n = (c.n + horizon * c.ndot).normalized();
        if (!separates(f, ahead, poses, kWatchedCone)) continue;
      }
      if (c.gap > -depth) out.push_back(f);
    }
  }
}

}  // namespace wysiwyf::haptics
