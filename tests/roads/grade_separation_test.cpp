#include "relief/roads/grade_separation.h"

#include <gtest/gtest.h>

#include "support/synthetic.h"

namespace relief {
namespace {

std::vector<RoadProfile> flat(const RoadNetwork& net, double z) {
  std::vector<RoadProfile> out;
  for (const Road& road : net.roads) {
    RoadProfile p = make_stations(road, 1.0);
    std::fill(p.z.begin(), p.z.end(), z);
    out.push_back(p);
  }
  return out;
}

TEST(GradeSeparation, EffectiveLayer) {
  WayAttributes a;
  EXPECT_EQ(effective_layer(a), 0);
  a.bridge = true;
  EXPECT_EQ(effective_layer(a), 1);
  a.layer = 2;
  EXPECT_EQ(effective_layer(a), 2);
  WayAttributes t;
  t.tunnel = true;
  EXPECT_EQ(effective_layer(t), -1);
}

TEST(GradeSeparation, FindsTheCrossingOfDifferentLayersOnly) {
  WayAttributes bridge;
  bridge.bridge = true;
  // Road 0 (bridge) crosses road 1 at (30, 0); road 2 (same layer as 1) crosses road 1 too.
  const RoadNetwork net =
      test::make_network({{{0, 0}, {100, 0}}, {{30, -50}, {30, 50}}, {{60, -50}, {20, 40}}}, {bridge});
  auto profiles = flat(net, 10.0);
  for (double& z : profiles[0].z) z = 16.5;
  const auto seps = find_grade_separations(net, profiles);
  ASSERT_EQ(seps.size(), 2u);  // 0 over 1 and 0 over 2; 1 and 2 are on the same layer
  EXPECT_EQ(seps[0].upper_road, 0);
  EXPECT_EQ(seps[0].lower_road, 1);
  EXPECT_NEAR(seps[0].s_upper, 30.0, 1e-9);
  EXPECT_NEAR(seps[0].s_lower, 50.0, 1e-9);
  EXPECT_NEAR(seps[0].clearance_m, 6.5, 1e-9);
  EXPECT_NEAR(seps[0].raw_clearance_m, 6.5, 1e-9);
  EXPECT_EQ(seps[1].lower_road, 2);
}

TEST(GradeSeparation, ConnectedRoadsAreNotSeparations) {
  WayAttributes bridge;
  bridge.bridge = true;
  // A bridge that ends where the street ends: a junction, not a crossing.
  const RoadNetwork net = test::make_network({{{0, 0}, {50, 0}}, {{50, 0}, {100, 0}}}, {bridge});
  EXPECT_TRUE(find_grade_separations(net, flat(net, 0.0)).empty());
}

// A viaduct (road 0, 6 m wide) running 4 m beside a street (road 1, 6 m wide) for 200 m: their
// paved widths overlap, so a clearance is due every 5 m away from the ends (x in 22.5 .. 177.5);
// a street 10 m off (road 2) and one leaving the viaduct's end junction (road 3) are not under it.
TEST(GradeSeparation, AViaductAlongAStreetIsSeparatedEveryFiveMetres) {
  WayAttributes bridge;
  bridge.bridge = true;
  const RoadNetwork net = test::make_network(
      {{{0, 0}, {200, 0}}, {{0, 4}, {200, 4}}, {{0, 10}, {200, 10}}, {{200, 0}, {190, -3}, {0, -3}}},
      {bridge});
  auto profiles = flat(net, 10.0);
  for (double& z : profiles[0].z) z = 15.0;
  const auto seps = find_grade_separations(net, profiles);
  ASSERT_EQ(seps.size(), 32u);
  for (std::size_t k = 0; k < seps.size(); ++k) {
    EXPECT_TRUE(seps[k].alongside);
    EXPECT_EQ(seps[k].upper_road, 0);
    EXPECT_EQ(seps[k].lower_road, 1);
    EXPECT_NEAR(seps[k].s_upper, 22.5 + 5.0 * static_cast<double>(k), 1e-9);
    EXPECT_NEAR(seps[k].s_lower, seps[k].s_upper, 1e-9);
    EXPECT_NEAR(seps[k].clearance_m, 5.0, 1e-9);
  }
}

}  // namespace
}  // namespace relief
