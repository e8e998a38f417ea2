#include "relief/roads/grade_separation.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>

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
  // Road 0 (bridge) crosses road 1 at (30, 0); road 2 (same layer as 1) crosses road 1 too, at
  // 24 degrees with no junction, their pavements overlapping: roads on one layer are never
  // separated.
  const RoadNetwork net =
      test::make_network({{{0, 0}, {100, 0}}, {{30, -50}, {30, 50}}, {{60, -50}, {20, 40}}}, {bridge});
  auto profiles = flat(net, 10.0);
  for (double& z : profiles[0].z) z = 16.5;
  std::vector<GradeSeparation> seps = find_grade_separations(net, profiles);
  // Beside each crossing, the deck's points over the street's pavement (within the two half
  // widths, 6 m, of its centreline) are separated too.
  for (const GradeSeparation& s : seps) {
    if (!s.alongside) continue;
    EXPECT_EQ(s.upper_road, 0);
    EXPECT_FALSE(s.ordering_only);
    // Road 2 crosses y = 0 at x = 60 - 40 * 50 / 90, at sin = 90 / hypot(40, 90) to the deck.
    const double at = s.lower_road == 1 ? 30.0 : 60.0 - 40.0 * 50.0 / 90.0;
    const double sine = s.lower_road == 1 ? 1.0 : 90.0 / std::hypot(40.0, 90.0);
    EXPECT_LT(std::abs(s.xy.x() - at) * sine, 6.0) << s.lower_road << " " << s.xy.x();
  }
  // Deck points every 5 m at x = 2.5, 7.5, ...: 27.5 and 32.5 over road 1, 32.5, 37.5, 42.5 over road 2.
  EXPECT_EQ(std::erase_if(seps, [](const GradeSeparation& s) { return s.alongside; }), 5u);
  ASSERT_EQ(seps.size(), 2u);  // 0 over 1 and 0 over 2
  EXPECT_EQ(seps[0].upper_road, 0);
  EXPECT_EQ(seps[0].lower_road, 1);
  EXPECT_NEAR(seps[0].s_upper, 30.0, 1e-9);
  EXPECT_NEAR(seps[0].s_lower, 50.0, 1e-9);
  EXPECT_NEAR(seps[0].clearance_m, 6.5, 1e-9);
  EXPECT_NEAR(seps[0].raw_clearance_m, 6.5, 1e-9);
  EXPECT_EQ(seps[1].lower_road, 2);
}

TEST(GradeSeparation, ACrossingIsKeptWhereADeckPointOverThePavementLiesOnIt) {
  WayAttributes bridge;
  bridge.bridge = true;
  // The deck's 5 m points fall at x = 2.5, 7.5, ...: one lies on the street at x = 32.5.
  const RoadNetwork net = test::make_network({{{0, 0}, {100, 0}}, {{32.5, -50}, {32.5, 50}}}, {bridge});
  const std::vector<GradeSeparation> seps = find_grade_separations(net, flat(net, 0.0));
  const auto crossings =
      std::count_if(seps.begin(), seps.end(), [](const GradeSeparation& s) { return !s.alongside; });
  EXPECT_EQ(crossings, 1);
  EXPECT_EQ(seps.size(), 4u);  // and the deck's points at x = 27.5, 32.5, 37.5 (within 3 + 3 m)
}

TEST(GradeSeparation, TwoBridgesOfOneLayerCrossingAreSeparatedTheHigherSpanAbove) {
  // Two bridges of layer 1 cross at (50, 0) without a node (a layer tag missing: Portland's
  // MLK viaduct and an I-84 ramp, both layer 2). Road 0's ends lie at 10 and 30 m (its straight
  // span at the crossing: 20 m), road 1's at 12 m: road 0 goes above, with the full clearance.
  // Two tunnels the same; a bridge over a street keeps its layer's order; a bridge drawn across
  // itself is no separation.
  WayAttributes bridge;
  bridge.bridge = true;
  WayAttributes tunnel;
  tunnel.tunnel = true;
  const RoadNetwork net = test::make_network({{{0, 0}, {100, 0}},
                                              {{50, -50}, {50, 50}},
                                              {{300, 0}, {400, 0}},
                                              {{350, -50}, {350, 50}},
                                              {{600, 0}, {700, 0}, {650, 40}, {650, -40}}},
                                             {bridge, bridge, tunnel, tunnel, bridge});
  std::vector<RoadProfile> profiles = flat(net, 12.0);
  for (std::size_t i = 0; i < profiles[0].z.size(); ++i) profiles[0].z[i] = 10.0 + 0.2 * profiles[0].s[i];
  for (double& z : profiles[3].z) z = -20.0;  // road 3's span lies lower: road 2 above
  const std::vector<GradeSeparation> seps = find_grade_separations(net, profiles);
  ASSERT_EQ(seps.size(), 2u);
  EXPECT_EQ(seps[0].upper_road, 0);
  EXPECT_EQ(seps[0].lower_road, 1);
  EXPECT_TRUE(seps[0].guessed_order);
  EXPECT_FALSE(seps[0].alongside);
  EXPECT_FALSE(seps[0].ordering_only);
  EXPECT_NEAR(seps[0].xy.x(), 50.0, 1e-9);
  EXPECT_NEAR(seps[0].clearance_m, 20.0 - 12.0, 1e-9);
  EXPECT_EQ(seps[1].upper_road, 2);
  EXPECT_EQ(seps[1].lower_road, 3);
  EXPECT_TRUE(seps[1].guessed_order);
  // Swapped heights swap the order: the guess follows the spans, not the road ids.
  for (std::size_t i = 0; i < profiles[0].z.size(); ++i) profiles[0].z[i] = 0.0;
  const std::vector<GradeSeparation> swapped = find_grade_separations(net, profiles);
  ASSERT_EQ(swapped.size(), 2u);
  EXPECT_EQ(swapped[0].upper_road, 1);
  EXPECT_EQ(swapped[0].lower_road, 0);
  // A bridge over a street: its layer says it, no guess.
  const RoadNetwork over = test::make_network({{{0, 0}, {100, 0}}, {{50, -50}, {50, 50}}}, {bridge});
  const std::vector<GradeSeparation> known = find_grade_separations(over, flat(over, 12.0));
  ASSERT_FALSE(known.empty());
  for (const GradeSeparation& s : known) EXPECT_FALSE(s.guessed_order);
}

TEST(GradeSeparation, ConnectedRoadsAreNotSeparations) {
  WayAttributes bridge;
  bridge.bridge = true;
  // A bridge that ends where the street ends: a junction, not a crossing.
  const RoadNetwork net = test::make_network({{{0, 0}, {50, 0}}, {{50, 0}, {100, 0}}}, {bridge});
  EXPECT_TRUE(find_grade_separations(net, flat(net, 0.0)).empty());
}

// A viaduct (road 0, 6 m wide) running 4 m beside a street (road 1, 6 m wide) for 200 m: their
// paved widths overlap, so a clearance is due every 5 m away from the ends (x in 22.5 .. 177.5),
// and nearer the ends the viaduct only has to stay above. A street 10 m off (road 2) is not
// under it. A street leaving the viaduct's end junction 3 m beside it (road 3, in the next grid
// cell) only has to stay under it, once the two have fanned out of that junction (beyond their
// half widths over sin 10 degrees, 34.6 m). Its first, slanted segment just reaches road 1's
// pavement: roads of one layer, not separated.
TEST(GradeSeparation, AViaductAlongAStreetIsSeparatedEveryFiveMetres) {
  WayAttributes bridge;
  bridge.bridge = true;
  const RoadNetwork net = test::make_network(
      {{{0, 0}, {200, 0}}, {{0, 4}, {200, 4}}, {{0, 10}, {200, 10}}, {{200, 0}, {190, -3}, {0, -3}}},
      {bridge});
  auto profiles = flat(net, 10.0);
  for (double& z : profiles[0].z) z = 15.0;
  std::vector<GradeSeparation> seps = find_grade_separations(net, profiles);
  std::map<std::pair<int, int>, int> ordered;
  for (const GradeSeparation& s : seps) {
    if (!s.ordering_only) continue;
    ++ordered[{s.upper_road, s.lower_road}];
    EXPECT_TRUE(s.alongside);
    const double x = s.xy.x();
    if (s.lower_road == 1) {
      EXPECT_TRUE(x < 20.0 || x > 180.0) << x;  // near the ends
    } else {
      EXPECT_GE(200.0 - x, 6.0 / std::sin(10.0 * std::numbers::pi / 180.0));  // fanned out
    }
    EXPECT_NEAR(s.clearance_m, 5.0, 1e-9);
  }
  const std::map<std::pair<int, int>, int> expected{{{0, 1}, 8}, {{0, 3}, 33}};
  EXPECT_EQ(ordered, expected);
  std::erase_if(seps, [](const GradeSeparation& s) { return s.ordering_only; });
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
