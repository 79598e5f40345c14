#include "contact.hpp"

#include <cmath>

namespace wysiwyf::haptics {

namespace {

Vec3 corner_world(const BodyModel& m, const Pose& s, int i) { return s.x + s.R * BoxTopology::corner(m.half_extents, i); }

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

ContactPoint edge_edge(const ContactFeature& f, const BodyModel& ma, const Pose& sa, const BodyModel& mb,
                       const Pose& sb, double slack) {
  ContactPoint c;
  const auto& ea = BoxTopology::edges()[f.feature_a];
  const auto& eb = BoxTopology::edges()[f.feature_b];
  const Vec3 a0 = corner_world(ma, sa, ea[0]), da = corner_world(ma, sa, ea[1]) - a0;
  const Vec3 b0 = corner_world(mb, sb, eb[0]), db = corner_world(mb, sb, eb[1]) - b0;
  const Vec3 u = da.cross(db);
  const double un = u.norm();
  if (un < 1e-9 * da.norm() * db.norm()) return c;  // parallel: vertex-face contacts cover it
  // Closest points of the two lines.
  const Vec3 w = a0 - b0;
  const double aa = da.dot(da), ab = da.dot(db), bb = db.dot(db), aw = da.dot(w), bw = db.dot(w);
  const double den = aa * bb - ab * ab;
  const double s = (ab * bw - bb * aw) / den, t = (aa * bw - ab * aw) / den;
  const double rel = slack / std::sqrt(std::min(aa, bb));
  c.valid = s >= -rel && s <= 1 + rel && t >= -rel && t <= 1 + rel;
  const Vec3 pa = a0 + s * da, pb = b0 + t * db;
  c.n = f.sign * u / un;
  c.gap = c.n.dot(pa - pb);
  c.p = 0.5 * (pa + pb);
  const Vec3 udot = sa.omega.cross(da).cross(db) + da.cross(sb.omega.cross(db));
  const Vec3 nu = u / un;
  c.ndot = f.sign * (udot - nu * nu.dot(udot)) / un;
  return c;
}

}  // namespace

ContactPoint evaluate(const ContactFeature& f, const std::vector<BodyModel>& models, const std::vector<Pose>& poses,
                      double slack) {
  const auto& ma = models[f.a];
  const auto& mb = models[f.b];
  return f.kind == ContactKind::kVertexFace ? vertex_face(f, ma, poses[f.a], mb, poses[f.b], slack)
                                            : edge_edge(f, ma, poses[f.a], mb, poses[f.b], slack);
}

void find_candidates(int a, int b, const std::vector<BodyModel>& models, const std::vector<Pose>& poses,
                     double margin, std::vector<ContactFeature>& out) {
  const auto& ma = models[a];
  const auto& mb = models[b];
  const double reach = ma.half_extents.norm() + mb.half_extents.norm() + margin;
  if ((poses[a].x - poses[b].x).squaredNorm() > reach * reach) return;  // bounding spheres apart
  // Deeper than this is the far side of the other box, not a contact.
  const double depth = 0.5 * std::min(ma.half_extents.minCoeff(), mb.half_extents.minCoeff());
  auto add_vertex_faces = [&](int va, int vb) {
    for (int v = 0; v < 8; ++v)
      for (int face = 0; face < 6; ++face) {
        ContactFeature f{ContactKind::kVertexFace, va, vb, v, face, 1};
        const ContactPoint c = evaluate(f, models, poses);
        if (c.valid && c.gap < margin && c.gap > -depth) out.push_back(f);
      }
  };
  add_vertex_faces(a, b);
  add_vertex_faces(b, a);  // corners of b on faces of a (a table corner under the cube)
  for (int ea = 0; ea < 12; ++ea)
    for (int eb = 0; eb < 12; ++eb) {
      ContactFeature f{ContactKind::kEdgeEdge, a, b, ea, eb, 1};
      ContactPoint c = evaluate(f, models, poses, -1e-6);
      if (!c.valid || std::abs(c.gap) > margin) continue;
      // Strictly inside both edges: a contact at an edge's end is a vertex-face contact.
      const Vec3 pb_out = c.p - poses[b].x;
      if (c.n.dot(pb_out) < 0) f.sign = -1;  // point the normal out of b
      c = evaluate(f, models, poses, -1e-6);
      if (c.gap > -depth) out.push_back(f);
    }
}

}  // namespace wysiwyf::haptics
