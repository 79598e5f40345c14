// ContactSystem::build's A = J M^-1 J^T, summed body by body, against the dense product over
// every dynamic body's six columns: the same matrix (to round-off), exactly symmetric, with and
// without tangent rows, for contacts between dynamic bodies, with a static one, and an island
// that touches only some of the world's bodies.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "rigid_body/contact_system.hpp"

namespace wysiwyf::haptics {

namespace {

BodyModel box(const char* name, double mass, const Vec3& half, bool dynamic = true) {
  BodyModel b;
  b.name = name;
  b.dynamic = dynamic;
  b.half_extents = half;
  b.mass = mass;
  b.inertia_body = BodyModel::box_inertia(mass, half);
  return b;
}

// J (rows: each contact's normal, then its two tangents, as build orders them) over 6 columns
// per dynamic body, and M^-1 over the same columns, from the poses alone.
Eigen::MatrixXd dense_a(const WorldModel& model, const std::vector<ActiveContact>& contacts,
                        const std::vector<Pose>& poses, const std::vector<std::array<Vec3, 2>>& tangents,
                        bool with_tangents) {
  const auto m = static_cast<Eigen::Index>(contacts.size());
  const Eigen::Index rows = with_tangents ? 3 * m : m;
  const auto columns = static_cast<Eigen::Index>(6 * model.dynamic.size());
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(rows, columns), Minv = Eigen::MatrixXd::Zero(columns, columns);
  for (Eigen::Index r = 0; r < rows; ++r) {
    const auto i = static_cast<std::size_t>(r < m ? r : (r - m) / 2);
    const ActiveContact& c = contacts[i];
    const Vec3 d = r < m ? c.point.n : tangents[i][static_cast<std::size_t>((r - m) % 2)];
    for (int side = 0; side < 2; ++side) {
      const int body = side == 0 ? c.feature.a : c.feature.b;
      const int slot = model.slot[body];
      if (slot < 0) continue;
      const Vec3 on_body = side == 0 ? d : Vec3(-d);
      J.block<1, 3>(r, 6 * slot) += on_body.transpose();
      J.block<1, 3>(r, 6 * slot + 3) += (c.point.p - poses[body].x).cross(on_body).transpose();
    }
  }
  for (std::size_t k = 0; k < model.dynamic.size(); ++k) {
    const Pose& p = poses[model.dynamic[k]];
    const auto at = static_cast<Eigen::Index>(6 * k);
    Minv.block<3, 3>(at, at) = p.inv_mass * Eigen::Matrix3d::Identity();
    Minv.block<3, 3>(at + 3, at + 3) = p.inv_inertia;
  }
  return J * Minv * J.transpose();
}

}  // namespace

TEST(ContactSystem, BuildsJMinvJtBodyByBody) {
  // Five dynamic boxes of different masses and shapes, turned arbitrarily, and a static table.
  std::vector<BodyModel> bodies{box("table", 0, Vec3(1, 1, 0.05), false), box("a", 0.3, Vec3(0.05, 0.04, 0.03)),
                                box("b", 1.2, Vec3(0.08, 0.05, 0.06)),    box("c", 0.1, Vec3(0.02, 0.03, 0.04)),
                                box("d", 2.0, Vec3(0.1, 0.1, 0.1)),       box("e", 0.5, Vec3(0.03, 0.06, 0.05))};
  const WorldModel model(bodies, WorldParams{});
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Pose> poses;
  for (int i = 0; i < static_cast<int>(bodies.size()); ++i) {
    BodyState s;
    s.x = Vec3(u(rng), u(rng), u(rng));
    s.q = Eigen::Quaterniond(Eigen::AngleAxisd(3 * u(rng), Vec3(u(rng), u(rng), u(rng)).normalized()));
    poses.push_back(model.pose_of(i, s));
  }
  // Contacts between pairs of dynamic bodies, with the table, and twice on one pair; body "e"
  // (index 5) is in none of the island's contacts.
  const std::vector<std::pair<int, int>> pairs{{1, 0}, {1, 2}, {2, 1}, {3, 2}, {3, 0}, {4, 3}, {4, 0}, {2, 0}, {1, 4}};
  std::vector<ActiveContact> contacts;
  for (const auto& [a, b] : pairs) {
    ActiveContact c;
    c.feature.a = a, c.feature.b = b;
    c.point.p = Vec3(u(rng), u(rng), u(rng));
    c.point.n = Vec3(u(rng), u(rng), u(rng)).normalized();
    c.point.valid = true;
    contacts.push_back(c);
  }
  ContactSystem cs(model);
  for (const bool with_tangents : {false, true})
    for (const std::size_t count : {std::size_t{1}, std::size_t{4}, contacts.size()}) {
      SCOPED_TRACE(testing::Message() << "tangents " << with_tangents << ", " << count << " contacts");
      const std::vector<ActiveContact> some(contacts.begin(), contacts.begin() + static_cast<std::ptrdiff_t>(count));
      cs.build(some.data(), some.size(), poses, with_tangents);
      const Eigen::MatrixXd expected = dense_a(model, some, poses, cs.tangents, with_tangents);
      ASSERT_EQ(cs.A.rows(), expected.rows());
      ASSERT_EQ(cs.A.cols(), expected.cols());
      EXPECT_LE((cs.A - expected).cwiseAbs().maxCoeff(), 1e-12 * expected.cwiseAbs().maxCoeff());
      EXPECT_EQ(cs.A, cs.A.transpose());  // exactly: the solvers read one triangle
    }
}

}  // namespace wysiwyf::haptics
