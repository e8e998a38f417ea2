#include "roads/close_roads.h"

#include <gtest/gtest.h>

#include <string>

#include "relief/core/diagnostic_codes.h"
#include "support/synthetic.h"

namespace relief {
namespace {

// A one-way of `lanes` lanes of `width_m`, named `name`.
WayAttributes carriageway(const std::string& name, int lanes = 2, double width_m = 3.5) {
  WayAttributes a;
  a.highway = HighwayClass::primary;
  a.oneway = true;
  a.lanes_forward = lanes;
  a.lanes_backward = 0;
  a.lane_width_m = width_m;
  a.name = name;
  return a;
}

TEST(CloseRoads, CarriagewaysDrawnCloserThanTheirWidthsAreNarrowedToMeet) {
  // Naito Parkway in small: two 7 m carriageways 6 m apart, running against each other for 300 m.
  RoadNetwork net = test::make_network({{{0, 0}, {300, 0}}, {{300, 6}, {0, 6}}},
                                       {carriageway("Naito Parkway"), carriageway("Naito Parkway")});
  Diagnostics d;
  EXPECT_EQ(detail::narrow_close_roads(net, d), 2u);
  // Both scaled by (6 - 0.2) / 7: their pavements (half widths 2.9 m) meet 0.2 m apart.
  for (const Road& road : net.roads) EXPECT_NEAR(road.attributes.lane_width_m, 3.5 * 5.8 / 7.0, 1e-9);
  EXPECT_EQ(d.count(std::string(codes::kNetworkRoadsNarrowed.code)), 2u);
  ASSERT_FALSE(d.kept().empty());
  EXPECT_NE(d.kept().front().message.find("drawn 6 m from road 1"), std::string::npos)
      << d.kept().front().message;
}

TEST(CloseRoads, APairTooCloseToShareDoesNotStopAnotherPairOfTheSameRoad) {
  // Road 0 has road 1 6 m to one side (narrowed to meet) and road 2 2.5 m to the other (lanes of
  // 1.15 m would be needed: left alone). Roads 0 and 1 are narrowed alike, road 2 keeps its lanes.
  RoadNetwork net = test::make_network({{{0, 0}, {300, 0}}, {{300, 6}, {0, 6}}, {{300, -2.5}, {0, -2.5}}},
                                       {carriageway("A"), carriageway("A"), carriageway("A")});
  Diagnostics d;
  EXPECT_EQ(detail::narrow_close_roads(net, d), 2u);
  EXPECT_NEAR(net.roads[0].attributes.lane_width_m, 2.9, 1e-9);
  EXPECT_NEAR(net.roads[1].attributes.lane_width_m, 2.9, 1e-9);
  EXPECT_EQ(net.roads[2].attributes.lane_width_m, 3.5);
}

TEST(CloseRoads, CarriagewaysFarEnoughApartOrNotCarriagewaysKeepTheirWidths) {
  Diagnostics d;
  // 7.5 m apart: their 7 m of pavement fits.
  RoadNetwork apart =
      test::make_network({{{0, 0}, {300, 0}}, {{300, 7.5}, {0, 7.5}}}, {carriageway("A"), carriageway("A")});
  EXPECT_EQ(detail::narrow_close_roads(apart, d), 0u);
  // Different names (a service road beside a boulevard), the same direction (a ramp beside a
  // freeway), one a bridge, a different layer, a two-way road: no carriageways of one road.
  WayAttributes bridge = carriageway("A");
  bridge.bridge = true;
  WayAttributes upper = carriageway("A");
  upper.layer = 1;
  WayAttributes two_way = carriageway("A");
  two_way.oneway = false;
  two_way.lanes_backward = 1;
  two_way.lanes_forward = 1;
  for (const auto& [second, reversed] : std::vector<std::pair<WayAttributes, bool>>{{carriageway("B"), true},
                                                                                    {carriageway("A"), false},
                                                                                    {bridge, true},
                                                                                    {upper, true},
                                                                                    {two_way, true}}) {
    const Polyline2 line = reversed ? Polyline2{{300, 6}, {0, 6}} : Polyline2{{0, 6}, {300, 6}};
    RoadNetwork net = test::make_network({{{0, 0}, {300, 0}}, line}, {carriageway("A"), second});
    EXPECT_EQ(detail::narrow_close_roads(net, d), 0u);
    for (const Road& road : net.roads)
      EXPECT_EQ(road.attributes.lane_width_m, road.id == 0 ? 3.5 : second.lane_width_m);
  }
  EXPECT_EQ(d.count(std::string(codes::kNetworkRoadsNarrowed.code)), 0u);
}

TEST(CloseRoads, WhereCarriagewaysMeetIsTheJunctionsToTrim) {
  // Carriageways 6 m apart that taper over their last 40 m into one junction at (300, 3): only
  // the parallel part counts (its 6 m, not the taper's closer points, which would ask for lanes
  // narrower than 2.5 m and leave them whole).
  Diagnostics d;
  RoadNetwork net = test::make_network({{{0, 0}, {259, 0}, {300, 3}}, {{300, 3}, {259, 6}, {0, 6}}},
                                       {carriageway("A"), carriageway("A")});
  ASSERT_EQ(net.junctions.size(), 3u);
  EXPECT_EQ(detail::narrow_close_roads(net, d), 2u);
  // 2.9 m lanes, but for the taper's first metre past the junction's reach (5.98 m apart there).
  for (const Road& road : net.roads) EXPECT_NEAR(road.attributes.lane_width_m, 3.5 * 5.8 / 7.0, 0.01);
}

TEST(CloseRoads, TooCloseBrieflyOrByFarIsLeftAlone) {
  Diagnostics d;
  // 3 m apart: lanes of 1.4 m would be needed; 1 m apart: one road drawn twice.
  for (const double gap : {3.0, 1.0}) {
    RoadNetwork net = test::make_network({{{0, 0}, {300, 0}}, {{300, gap}, {0, gap}}},
                                         {carriageway("A"), carriageway("A")});
    EXPECT_EQ(detail::narrow_close_roads(net, d), 0u) << gap;
  }
  // 8 m apart but for a bump drawn 1.5 m toward the other over 8 m, too close over under 3 m
  // of either (a kink, not a carriageway beside another): left to the mesh checks.
  RoadNetwork kink =
      test::make_network({{{0, 0}, {100, 0}, {104, 1.5}, {108, 0}, {300, 0}}, {{300, 8}, {0, 8}}},
                         {carriageway("A"), carriageway("A")});
  EXPECT_EQ(detail::narrow_close_roads(kink, d), 0u);
  EXPECT_EQ(d.count(std::string(codes::kNetworkRoadsNarrowed.code)), 0u);
}

}  // namespace
}  // namespace relief
