#include "roads/stray_ends.h"

#include <gtest/gtest.h>

#include <array>
#include <vector>

#include "support/synthetic.h"

namespace relief {
namespace {

// Road 0: a street along the x axis from x = -100 to 100 (vertex at 0), half width 3.5 m, so its
// pavement is |y| <= 3.5. Road 1: a side road of half width 2 m along x = `x` from y = `y_end`
// (its dead end, on or near the street) to y = 40 (reversed: from 40 to y_end). Heights: the
// street is flat at 0, the side road flat at `side_z`.
struct World {
  RoadNetwork net;
  std::vector<RoadProfile> profiles;
  std::vector<double> half_width{3.5, 2.0};
  std::vector<std::array<double, 2>> trim{{0.0, 0.0}, {0.0, 0.0}};
};

World street_and_side_road(double y_end, double x = 0.0, bool reversed = false, double side_z = 0.0) {
  const Polyline2 side = reversed ? Polyline2{{x, 40}, {x, y_end}} : Polyline2{{x, y_end}, {x, 40}};
  World w;
  w.net = test::make_network({{{-100, 0}, {0, 0}, {100, 0}}, side});
  w.profiles = test::drape(w.net, [](const Vec2&) { return 0.0; });
  for (double& z : w.profiles[1].z) z = side_z;
  return w;
}

std::vector<detail::StrayEnd> clear(World& w, const detail::StrayEndOptions& options = {}) {
  return detail::clear_stray_ends(w.net, w.profiles, w.half_width, w.trim, options);
}

TEST(StrayEnds, EmptyNetworkHasNoStrayEnds) {
  const RoadNetwork net;
  std::vector<std::array<double, 2>> trim;
  EXPECT_TRUE(detail::clear_stray_ends(net, {}, {}, trim, {}).empty());
}

TEST(StrayEnds, ADeadEndOnAnotherRoadIsTrimmedUntilItsCrossSectionClearsThePavementByTheGap) {
  // The side road ends at y = 1, inside the street's pavement. Its end cross-section at trim t
  // lies at y = 1 + t, 1 + t - 3.5 from the pavement: it clears the 0.5 m gap at 1 + t >= 4,
  // t = 3 (six 0.5 m steps).
  World w = street_and_side_road(1.0);
  const std::vector<detail::StrayEnd> stray = clear(w);
  ASSERT_EQ(stray.size(), 1u);
  EXPECT_EQ(stray[0].road, 1);
  EXPECT_TRUE(stray[0].at_start);
  EXPECT_EQ(stray[0].other_road, 0);
  EXPECT_NEAR(stray[0].trimmed_m, 3.0, 1e-9);
  EXPECT_TRUE(stray[0].cleared);
  EXPECT_NEAR(w.trim[1][0], 3.0, 1e-9);
  EXPECT_EQ(w.trim[1][1], 0.0);
  // The street's own dead ends (x = +-100) lie on nothing: untouched.
  EXPECT_EQ(w.trim[0][0], 0.0);
  EXPECT_EQ(w.trim[0][1], 0.0);
}

TEST(StrayEnds, TheGapIsAStrictBound) {
  // An end 4 m from the street's centreline is exactly the 0.5 m gap from its pavement: clear.
  World at_gap = street_and_side_road(4.0);
  EXPECT_TRUE(clear(at_gap).empty());
  EXPECT_EQ(at_gap.trim[1][0], 0.0);
  // 3.99 m: 0.49 m from the pavement, one step of 0.5 m clears it.
  World inside = street_and_side_road(3.99);
  const std::vector<detail::StrayEnd> stray = clear(inside);
  ASSERT_EQ(stray.size(), 1u);
  EXPECT_NEAR(stray[0].trimmed_m, 0.5, 1e-9);
  EXPECT_TRUE(stray[0].cleared);
  // A wider gap asks for more: gap 2 m clears at 1 + t - 3.5 >= 2, t = 4.5.
  World wide = street_and_side_road(1.0);
  detail::StrayEndOptions options;
  options.gap_m = 2.0;
  ASSERT_EQ(clear(wide, options).size(), 1u);
  EXPECT_NEAR(wide.trim[1][0], 4.5, 1e-9);
}

TEST(StrayEnds, ADeadEndAtTheRoadsEndIsTrimmedAtItsEnd) {
  World w = street_and_side_road(1.0, 0.0, true);
  const std::vector<detail::StrayEnd> stray = clear(w);
  ASSERT_EQ(stray.size(), 1u);
  EXPECT_FALSE(stray[0].at_start);
  EXPECT_NEAR(w.trim[1][1], 3.0, 1e-9);
  EXPECT_EQ(w.trim[1][0], 0.0);
}

TEST(StrayEnds, TrimGrowsFromTheTrimAlreadyThere) {
  // Already trimmed 1 m: grows to 3 m, 2 m more.
  World w = street_and_side_road(1.0);
  w.trim[1][0] = 1.0;
  const std::vector<detail::StrayEnd> stray = clear(w);
  ASSERT_EQ(stray.size(), 1u);
  EXPECT_NEAR(stray[0].trimmed_m, 2.0, 1e-9);
  EXPECT_NEAR(w.trim[1][0], 3.0, 1e-9);
}

TEST(StrayEnds, TrimStopsAtTheRoadsLeastLengthAndReportsNotCleared) {
  // The side road is 39 m long; with 37.5 m trimmed at its other end and 1 m to keep, its start
  // may be trimmed 0.5 m at most: still on the street.
  // Its far end, trimmed back to y = 2.5, now lies on the street too, and may not grow at all
  // (39 - 0.5 - 1 = 37.5): reported, not cleared, trimmed 0 m more.
  World w = street_and_side_road(1.0);
  w.trim[1][1] = 37.5;
  const std::vector<detail::StrayEnd> stray = clear(w);
  ASSERT_EQ(stray.size(), 2u);
  EXPECT_TRUE(stray[0].at_start);
  EXPECT_FALSE(stray[0].cleared);
  EXPECT_EQ(stray[0].other_road, 0);
  EXPECT_NEAR(stray[0].trimmed_m, 0.5, 1e-9);
  EXPECT_FALSE(stray[1].at_start);
  EXPECT_FALSE(stray[1].cleared);
  EXPECT_EQ(stray[1].other_road, 0);
  EXPECT_EQ(stray[1].trimmed_m, 0.0);
  EXPECT_NEAR(w.trim[1][0], 0.5, 1e-9);
  EXPECT_EQ(w.trim[1][1], 37.5);
  // Far from the street (its far end at y = 40 - 30 = 10), only the start is reported.
  World single = street_and_side_road(1.0);
  single.trim[1][1] = 30.0;
  const std::vector<detail::StrayEnd> one = clear(single);
  ASSERT_EQ(one.size(), 1u);
  EXPECT_TRUE(one[0].cleared);  // cap 39 - 30 - 1 = 8 m, more than the 3 m needed
  EXPECT_NEAR(single.trim[1][0], 3.0, 1e-9);
}

TEST(StrayEnds, ARoadOnAnotherLevelIsNoObstacle) {
  // At x = 60 (another grid cell than the street's middle). A side road 2 m above the street
  // is trimmed (the bound is inclusive); beyond 2 m it passes over or under.
  World level = street_and_side_road(1.0, 60.0, false, 2.0);
  ASSERT_EQ(clear(level).size(), 1u);
  EXPECT_NEAR(level.trim[1][0], 3.0, 1e-9);
  World above = street_and_side_road(1.0, 60.0, false, 2.01);
  EXPECT_TRUE(clear(above).empty());
  EXPECT_EQ(above.trim[1][0], 0.0);
  World below = street_and_side_road(1.0, 60.0, false, -2.01);
  EXPECT_TRUE(clear(below).empty());
}

TEST(StrayEnds, RoadsWithoutHeightAreLeftAlone) {
  World side_flat = street_and_side_road(1.0);
  side_flat.profiles[1].has_height = false;
  EXPECT_TRUE(clear(side_flat).empty());
  EXPECT_EQ(side_flat.trim[1][0], 0.0);
  World street_flat = street_and_side_road(1.0);
  street_flat.profiles[0].has_height = false;
  EXPECT_TRUE(clear(street_flat).empty());
  EXPECT_EQ(street_flat.trim[1][0], 0.0);
}

TEST(StrayEnds, AnEndSharingAJunctionIsNoDeadEnd) {
  // The side road ends at the street's vertex node (0, 0)... made a junction: the street split
  // there, three road ends. Not a dead end, not trimmed.
  World w;
  w.net = test::make_network({{{-100, 0}, {0, 0}}, {{0, 0}, {100, 0}}, {{0, 0}, {0, 40}}});
  w.profiles = test::drape(w.net, [](const Vec2&) { return 0.0; });
  w.half_width = {3.5, 3.5, 2.0};
  w.trim.assign(3, {0.0, 0.0});
  EXPECT_TRUE(clear(w).empty());
  for (const auto& t : w.trim) EXPECT_EQ(t, (std::array<double, 2>{0.0, 0.0}));
}

TEST(StrayEnds, AnEndInAnotherGridCellThanTheRoadItLiesNearIsFound) {
  // The segment grid has 25 m cells. A street along y = 21 (half width 3.5 m) is filed under
  // the cells of y in [17.5, 24.5] only; a side road ending at y = 25.2 lies in the next row
  // of cells, 25.2 - 21 - 3.5 = 0.7 m from the street's pavement. With a 2 m gap it must be
  // found there and trimmed until 4.2 + t - 3.5 >= 2, t >= 1.3: 1.5 m in 0.5 m steps.
  World w;
  w.net = test::make_network({{{-100, 21}, {100, 21}}, {{0, 25.2}, {0, 60}}});
  w.profiles = test::drape(w.net, [](const Vec2&) { return 0.0; });
  detail::StrayEndOptions options;
  options.gap_m = 2.0;
  const std::vector<detail::StrayEnd> stray = clear(w, options);
  ASSERT_EQ(stray.size(), 1u);
  EXPECT_EQ(stray[0].other_road, 0);
  EXPECT_NEAR(stray[0].trimmed_m, 1.5, 1e-9);
  EXPECT_TRUE(stray[0].cleared);
}

TEST(StrayEnds, AnEndCrossingTheStreetIsTrimmedBackToClearItsFarSide) {
  // The side road runs down through the street to y = -2: its end cross-section at y = -2 + t
  // clears the pavement (|y| >= 4) only at y = 4 on the near side: t = 6.
  World w = street_and_side_road(-2.0);
  const std::vector<detail::StrayEnd> stray = clear(w);
  ASSERT_EQ(stray.size(), 1u);
  EXPECT_NEAR(stray[0].trimmed_m, 6.0, 1e-9);
  EXPECT_TRUE(stray[0].cleared);
}

}  // namespace
}  // namespace relief
