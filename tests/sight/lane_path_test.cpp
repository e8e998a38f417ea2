// A lane followed ahead through its links (sight/lane_path.h): to the next road, and through a
// junction on the straightest connecting road.

#include "sight/lane_path.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "support/road_models.h"

namespace relief::detail {
namespace {

// Road 1 east from (0, 0), 100 m, into junction 10; out of it road 2 on east (from (20, 0)) and
// road 3 north (from (10, 10)); connecting roads 4 (1 -> 2, straight) and 5 (1 -> 3, a left
// turn drawn as a line to keep it simple).
RoadModel t_junction() {
  RoadModel m;
  m.roads.push_back(test::straight_road(1, Vec2(-100.0, 0.0), 0.0, 100.0, 0.0, 0.0));
  m.roads.push_back(test::straight_road(2, Vec2(20.0, 0.0), 0.0, 80.0, 0.0, 0.0));
  m.roads.push_back(test::straight_road(3, Vec2(10.0, 10.0), std::numbers::pi / 2.0, 80.0, 0.0, 0.0));
  m.roads.push_back(test::straight_road(4, Vec2(0.0, 0.0), 0.0, 20.0, 0.0, 0.0));
  m.roads.push_back(
      test::straight_road(5, Vec2(0.0, 0.0), std::atan2(10.0, 10.0), std::hypot(10.0, 10.0), 0.0, 0.0));
  m.roads[0].successor = RoadLink{RoadLink::Element::junction, 10, RoadLink::Contact::start};
  for (const int k : {3, 4}) {
    m.roads[static_cast<std::size_t>(k)].junction = 10;
    m.roads[static_cast<std::size_t>(k)].predecessor =
        RoadLink{RoadLink::Element::road, 1, RoadLink::Contact::end};
    m.roads[static_cast<std::size_t>(k)].successor =
        RoadLink{RoadLink::Element::road, k == 3 ? 2 : 3, RoadLink::Contact::start};
  }
  JunctionModel j;
  j.id = 10;
  // The turn is listed first: the straight one must still win.
  j.connections.push_back({1, 1, 5, RoadLink::Contact::start, {{-1, -1}}});
  j.connections.push_back({2, 1, 4, RoadLink::Contact::start, {{-1, -1}}});
  m.junctions.push_back(j);
  return m;
}

TEST(LanePath, ThroughAJunctionTheStraightestConnectingRoadIsTaken) {
  const RoadModel m = t_junction();
  const std::optional<LaneRef> in_junction = next_lane(m, {0, -1});
  ASSERT_TRUE(in_junction);
  EXPECT_EQ(in_junction->road, 3);  // road 4
  EXPECT_EQ(in_junction->lane, -1);
  const std::optional<LaneRef> after = next_lane(m, *in_junction);
  ASSERT_TRUE(after);
  EXPECT_EQ(after->road, 1);  // road 2, entered at its start: along it
  EXPECT_EQ(after->lane, -1);
  EXPECT_FALSE(next_lane(m, {1, -1}));  // road 2 ends nowhere
  EXPECT_FALSE(next_lane(m, {0, 1}));   // road 1's left lane runs back to its start: no link
}

TEST(LanePath, AheadRunsOnAcrossTheRoadsWithItsDistances) {
  const RoadModel m = t_junction();
  bool ended = false;
  const LanePoints p = lane_ahead(m, {0, -1}, 2.0, 150.0, ended);
  EXPECT_FALSE(ended);
  ASSERT_GE(p.distance.back(), 150.0);
  // Points every 2 m, on the lane centre 1.75 m right of the line y = 0, with no point repeated.
  for (std::size_t i = 1; i < p.size(); ++i) {
    EXPECT_NEAR(p.distance[i] - p.distance[i - 1], 2.0, 1e-9) << i;
    EXPECT_NEAR(p.points[i].y(), -1.75, 1e-9);
  }
  EXPECT_EQ(std::isnan(p.s[50]), false);  // s = 100: the end of road 1
  EXPECT_NEAR(p.s[50], 100.0, 1e-9);
  EXPECT_TRUE(std::isnan(p.s[51]));
  const LanePoints all = lane_ahead(m, {0, -1}, 2.0, 1000.0, ended);
  EXPECT_TRUE(ended);
  EXPECT_NEAR(all.distance.back(), 200.0, 1e-9);
}

}  // namespace
}  // namespace relief::detail
