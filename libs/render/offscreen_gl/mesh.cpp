#include "offscreen_gl/mesh.hpp"

#include <cmath>

namespace wysiwyf::render {

namespace {
void quad(Mesh& m, const Eigen::Vector3f& a, const Eigen::Vector3f& b, const Eigen::Vector3f& c,
          const Eigen::Vector3f& d, const Eigen::Vector3f& n) {
  for (const auto* p : {&a, &b, &c, &a, &c, &d}) {
    m.positions.push_back(*p);
    m.normals.push_back(n);
  }
}
}  // namespace

Mesh Mesh::box(const Eigen::Vector3f& h) {
  Mesh m;
  for (int axis = 0; axis < 3; ++axis)
    for (float s : {-1.f, 1.f}) {
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      Eigen::Vector3f n = Eigen::Vector3f::Zero(), du = Eigen::Vector3f::Zero(), dv = Eigen::Vector3f::Zero();
      n[axis] = s;
      du[u] = h[u];
      dv[v] = h[v];
      const Eigen::Vector3f c = n * h[axis];
      quad(m, c - du - dv, c + du - dv, c + du + dv, c - du + dv, n);
    }
  return m;
}

Mesh Mesh::plane(float hx, float hy) {
  Mesh m;
  quad(m, {-hx, -hy, 0}, {hx, -hy, 0}, {hx, hy, 0}, {-hx, hy, 0}, {0, 0, 1});
  return m;
}

// A sphere split at z = 0 and pulled apart by 2 * half_length gives a capsule (0: a sphere).
static Mesh rounded(float r, float half_length, int slices, int stacks) {
  Mesh m;
  auto point = [&](int i, int j) {
    const float phi = static_cast<float>(M_PI) * j / stacks - static_cast<float>(M_PI) / 2;  // -pi/2 .. pi/2
    const float theta = 2 * static_cast<float>(M_PI) * i / slices;
    const Eigen::Vector3f n(std::cos(phi) * std::cos(theta), std::cos(phi) * std::sin(theta), std::sin(phi));
    return std::make_pair(n, n);
  };
  for (int j = 0; j < stacks; ++j)
    for (int i = 0; i < slices; ++i) {
      const int corners[6][2] = {{i, j}, {i + 1, j}, {i + 1, j + 1}, {i, j}, {i + 1, j + 1}, {i, j + 1}};
      for (const auto& c : corners) {
        const Eigen::Vector3f n = point(c[0], c[1]).first;
        // The lower half-sphere moves down, the upper up; the seam row belongs to the stack below it.
        const float shift = (2 * c[1] < stacks || (2 * c[1] == stacks && 2 * j < stacks)) ? -half_length : half_length;
        m.positions.push_back(r * n + Eigen::Vector3f(0, 0, shift));
        m.normals.push_back(n);
      }
    }
  if (half_length > 0) {  // the cylinder between the two halves
    for (int i = 0; i < slices; ++i) {
      const float t0 = 2 * static_cast<float>(M_PI) * i / slices, t1 = 2 * static_cast<float>(M_PI) * (i + 1) / slices;
      const Eigen::Vector3f n0(std::cos(t0), std::sin(t0), 0), n1(std::cos(t1), std::sin(t1), 0);
      const Eigen::Vector3f lo(0, 0, -half_length), hi(0, 0, half_length);
      using V = Eigen::Vector3f;
      const std::pair<V, V> strip[] = {{V(r * n0 + lo), n0}, {V(r * n1 + lo), n1}, {V(r * n1 + hi), n1},
                                       {V(r * n0 + lo), n0}, {V(r * n1 + hi), n1}, {V(r * n0 + hi), n0}};
      for (const auto& [p, n] : strip) {
        m.positions.push_back(p);
        m.normals.push_back(n);
      }
    }
  }
  return m;
}

Mesh Mesh::sphere(float radius, int slices, int stacks) { return rounded(radius, 0, slices, stacks); }
Mesh Mesh::capsule(float radius, float half_length, int slices, int stacks) {
  return rounded(radius, half_length, slices, stacks);
}

Mesh Mesh::cylinder(float r, float h, int slices) {
  Mesh m;
  for (int i = 0; i < slices; ++i) {
    const float t0 = 2 * static_cast<float>(M_PI) * i / slices, t1 = 2 * static_cast<float>(M_PI) * (i + 1) / slices;
    const Eigen::Vector3f n0(std::cos(t0), std::sin(t0), 0), n1(std::cos(t1), std::sin(t1), 0);
    quad(m, r * n0 - Eigen::Vector3f(0, 0, h), r * n1 - Eigen::Vector3f(0, 0, h), r * n1 + Eigen::Vector3f(0, 0, h),
         r * n0 + Eigen::Vector3f(0, 0, h), (n0 + n1).normalized());
    for (float s : {-1.f, 1.f}) {  // caps
      const Eigen::Vector3f c(0, 0, s * h);
      for (const Eigen::Vector3f& p : {c, Eigen::Vector3f(c + r * n0), Eigen::Vector3f(c + r * n1)}) {
        m.positions.push_back(p);
        m.normals.push_back(Eigen::Vector3f(0, 0, s));
      }
    }
  }
  return m;
}

}  // namespace wysiwyf::render
