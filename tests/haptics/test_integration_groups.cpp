// IntegrationGroups: which bodies a World integrates together. Bodies joined by a resting contact
// or a watched feature, directly or through others, are one group (a static body joins none);
// the groups that watch nothing are one calm group; each island and watched feature belongs to
// its bodies' group, or, where they all sleep, to none.
#include <gtest/gtest.h>

#include <vector>

#include "rigid_body/integration_groups.hpp"

namespace wysiwyf::haptics {

namespace {

BodyModel box(const char* name, bool dynamic = true) {
  BodyModel b;
  b.name = name;
  b.dynamic = dynamic;
  b.half_extents = Vec3::Constant(0.05);
  b.mass = 1;
  b.inertia_body = BodyModel::box_inertia(1, b.half_extents);
  return b;
}

ContactFeature feature(int a, int b) {
  ContactFeature f;
  f.a = a, f.b = b;
  return f;
}

ActiveContact contact(int a, int b) {
  ActiveContact c;
  c.feature = feature(a, b);
  return c;
}

ContactIsland island(std::size_t begin, std::size_t end) {
  ContactIsland i;
  i.begin = begin, i.end = end, i.live = end - begin;
  return i;
}

// The groups' bodies, in order.
std::vector<std::vector<int>> bodies_of(IntegrationGroups& groups) {
  std::vector<std::vector<int>> out;
  for (std::size_t k = 0; k < groups.size(); ++k) out.push_back(groups.groups()[k].bodies);
  return out;
}

}  // namespace

TEST(IntegrationGroups, JoinsBodiesByContactsAndWatchedFeaturesAndMergesTheCalmOnes) {
  // 0: table (static); 1-8 boxes.
  std::vector<BodyModel> models{box("table", false)};
  for (const char* name : {"b1", "b2", "b3", "b4", "b5", "b6", "b7", "b8"}) models.push_back(box(name));
  const WorldModel model(models, WorldParams{});
  WorldState state(model, std::vector<BodyState>(models.size()));
  // Islands: {1 on the table, 2 on 1}, {3 on the table}, {5 on the table, 6 on 5}, {7 on the table}.
  state.resting = {contact(1, 0), contact(2, 1), contact(3, 0), contact(5, 0), contact(6, 5), contact(7, 0)};
  state.islands = {island(0, 2), island(2, 3), island(3, 5), island(5, 6)};
  // 3 may hit 4 (joins them); 2 watches the table (joins nothing, but its group watches); 8 falls alone.
  state.watched = {feature(3, 4), feature(2, 0)};
  // 5 and 6 sleep (their island, watching nothing, is calm, merged with the calm 7 and 8).
  state.asleep[5] = state.asleep[6] = 1;
  IntegrationGroups groups;
  int made = 0;
  groups.form(model, state, [&](int) {
    ++made;
    return std::unique_ptr<OdeIntegrator>();
  });
  EXPECT_EQ(bodies_of(groups), (std::vector<std::vector<int>>{{1, 2}, {3, 4}, {5, 6, 7, 8}}));
  EXPECT_EQ(made, 3);
  EXPECT_EQ(groups.place()[0], -1);  // (static)
  EXPECT_EQ(groups.place()[2], 1);
  EXPECT_EQ(groups.place()[7], 2);
  groups.assign(model, state);
  const auto& g = groups.groups();
  EXPECT_EQ(g[0].islands, (std::vector<std::size_t>{0}));
  EXPECT_EQ(g[0].watched, (std::vector<std::size_t>{1}));
  EXPECT_EQ(g[1].islands, (std::vector<std::size_t>{1}));
  EXPECT_EQ(g[1].watched, (std::vector<std::size_t>{0}));
  EXPECT_EQ(g[2].islands, (std::vector<std::size_t>{2, 3}));
  EXPECT_TRUE(g[0].awake && g[1].awake && g[2].awake);  // (7 and 8 are awake)
  EXPECT_TRUE(groups.asleep_islands().empty());

  // Everything of the calm group asleep: it is not integrated, its island listed as sleeping.
  state.asleep[7] = state.asleep[8] = 1;
  groups.assign(model, state);
  EXPECT_FALSE(groups.groups()[2].awake);
  EXPECT_EQ(groups.asleep_islands(), (std::vector<std::size_t>{2, 3}));
  EXPECT_TRUE(groups.groups()[2].islands.empty());
}

}  // namespace wysiwyf::haptics
