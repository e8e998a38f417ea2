#include "roads/road_separation.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "relief/core/diagnostic_codes.h"
#include "roads/lane_layout.h"
#include "support/synthetic.h"

namespace relief {
namespace {

WayAttributes road_of(HighwayClass cls, bool oneway, int lanes, double width_m = 3.5) {
  WayAttributes a;
  a.highway = cls;
  a.oneway = oneway;
  a.lanes_forward = lanes;
  a.lanes_backward = oneway ? 0 : lanes;
  a.lane_width_m = width_m;
  return a;
}

// The distance from p to the polyline.
double distance_to(const Polyline2& line, const Vec2& p) {
  double best = 1e300;
  for (std::size_t i = 0; i + 1 < line.size(); ++i) {
    const Vec2& a = line[i];
    const Vec2& b = line[i + 1];
    const double t = std::clamp((p - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
    best = std::min(best, (a + (b - a) * t - p).norm());
  }
  return best;
}

std::size_t moved_count(const Diagnostics& d) {
  return d.count(std::string(codes::kNetworkRoadsMoved.code));
}

TEST(RoadSeparation, ALinkDrawnOverATrunkIsMovedAsideUntilTheirPavementsMeet) {
  // Portland's McLoughlin Boulevard in small: a two-way trunk of 2 + 2 lanes and a one-lane link
  // beside it, 7 m apart over 300 m (their pavements reach 8.75 m).
  RoadNetwork net = test::make_network(
      {{{0, 0}, {400, 0}}, {{50, 7}, {350, 7}}},
      {road_of(HighwayClass::trunk, false, 2), road_of(HighwayClass::trunk_link, true, 1)});
  const double needed = detail::half_width(net.roads[0]) + detail::half_width(net.roads[1]);
  ASSERT_NEAR(needed, 8.75, 1e-9);
  const Polyline2 trunk = net.roads[0].points;
  Diagnostics d;
  EXPECT_EQ(detail::separate_close_roads(net, d), 1u);
  EXPECT_EQ(net.roads[0].points, trunk);  // the trunk keeps its line
  const Road& link = net.roads[1];
  // The ends stay (they are the junctions'); between the end tapers (30 m) and the shift's own
  // taper, the link lies the half widths' sum + 0.2 m from the trunk, on its side, within 1 cm.
  EXPECT_EQ(link.points.front(), Vec2(50, 7));
  EXPECT_EQ(link.points.back(), Vec2(350, 7));
  EXPECT_EQ(link.points.size(), link.osm_node_ids.size());
  double lowest = 1e300, highest = 0.0, step = 0.0;
  for (std::size_t i = 0; i < link.points.size(); ++i) {
    const Vec2& p = link.points[i];
    EXPECT_GT(p.y(), 7 - 1e-9);
    if (i > 0)
      step = std::max(step, std::abs(p.y() - link.points[i - 1].y()) / (p.x() - link.points[i - 1].x()));
    if (p.x() < 50 + 30 + 2 || p.x() > 350 - 30 - 2) continue;
    lowest = std::min(lowest, distance_to(trunk, p));
    highest = std::max(highest, distance_to(trunk, p));
  }
  EXPECT_NEAR(lowest, needed + 0.2, 0.01);
  EXPECT_NEAR(highest, needed + 0.2, 0.01);
  // The link bends no steeper than its taper: 1.95 m over 30 m with a cosine is at most
  // pi / 2 * 1.95 / 30 = 0.10 of slope across.
  EXPECT_LT(step, 0.11);
  ASSERT_EQ(moved_count(d), 1u);
  const std::string& text = d.kept().front().message;
  EXPECT_NE(text.find("road 1 (OSM way"), std::string::npos) << text;
  EXPECT_NE(text.find("is drawn 7 m from road 0"), std::string::npos) << text;
}

TEST(RoadSeparation, TheLesserRoadGivesWayWhicheverWayItRuns) {
  // A residential street beside a primary, 8.5 m apart for 10.5 m of pavement, drawn either way
  // along: the street moves. Of two equal classes the narrower moves.
  for (const bool reversed : {false, true}) {
    const Polyline2 street =
        reversed ? Polyline2{{350, -8.5}, {50, -8.5}} : Polyline2{{50, -8.5}, {350, -8.5}};
    RoadNetwork net = test::make_network(
        {{{0, 0}, {400, 0}}, street},
        {road_of(HighwayClass::primary, false, 2), road_of(HighwayClass::residential, false, 1)});
    Diagnostics d;
    EXPECT_EQ(detail::separate_close_roads(net, d), 1u) << reversed;
    EXPECT_EQ(net.roads[0].points.size(), 2u);
    EXPECT_NEAR(net.roads[1].points[net.roads[1].points.size() / 2].y(), -10.7, 0.01) << reversed;
  }
  RoadNetwork equal =
      test::make_network({{{50, 4}, {350, 4}}, {{0, 0}, {400, 0}}},
                         {road_of(HighwayClass::primary, true, 1), road_of(HighwayClass::primary, true, 2)});
  Diagnostics d;
  EXPECT_EQ(detail::separate_close_roads(equal, d), 1u);
  EXPECT_GT(equal.roads[0].points.size(), 2u);
  EXPECT_EQ(equal.roads[1].points.size(), 2u);
}

TEST(RoadSeparation, RoadsApartOnOtherLevelsDrawnTwiceOrBrieflyCloseAreLeftAlone) {
  const WayAttributes trunk = road_of(HighwayClass::trunk, false, 2);
  WayAttributes link = road_of(HighwayClass::trunk_link, true, 1);
  WayAttributes upper = link;
  upper.layer = 1;
  WayAttributes tunnel = link;
  tunnel.tunnel = true;
  Diagnostics d;
  for (const auto& [gap, attributes] :
       std::vector<std::pair<double, WayAttributes>>{
           {9.5, link},     // apart: their 8.75 m of pavement fit
           {1.0, link},     // one road drawn twice
           {5.5, link},     // 3.45 m over the other: more than the 3 m a road is moved
           {7.0, upper},    // a bridge's level
           {7.0, tunnel}})  // a tunnel beside
  {
    RoadNetwork net = test::make_network({{{0, 0}, {400, 0}}, {{50, gap}, {350, gap}}}, {trunk, attributes});
    EXPECT_EQ(detail::separate_close_roads(net, d), 0u) << gap;
    EXPECT_EQ(net.roads[1].points.size(), 2u) << gap;
  }
  // A link 9.5 m away but for a kink drawn 2.5 m toward the trunk over 4 m: too close over
  // under 6 m of road (a kink, not a road beside another), left to the mesh checks.
  RoadNetwork kink = test::make_network(
      {{{0, 0}, {400, 0}}, {{50, 9.5}, {198, 9.5}, {200, 7}, {202, 9.5}, {350, 9.5}}}, {trunk, link});
  EXPECT_EQ(detail::separate_close_roads(kink, d), 0u);
  // A link between two trunks 16 m apart, 8 m from each (8.75 m of pavement): pushed both ways,
  // left alone.
  RoadNetwork squeezed = test::make_network({{{0, 0}, {400, 0}}, {{0, 16}, {400, 16}}, {{50, 8}, {350, 8}}},
                                            {trunk, trunk, link});
  EXPECT_EQ(detail::separate_close_roads(squeezed, d), 0u);
  EXPECT_EQ(moved_count(d), 0u);
}

TEST(RoadSeparation, ARampLeavingItsRoadAtAJunctionIsTheJunctionsToTrim) {
  // A link that leaves the trunk at a junction at (0, 0) at 12 degrees: the part near the
  // junction (within the half widths' sum over sin 10 degrees) is the junction's; beyond it the
  // link is already clear.
  const double run = 400.0, rise = run * std::tan(12.0 * 3.14159265358979 / 180.0);
  RoadNetwork net = test::make_network(
      {{{-100, 0}, {0, 0}, {400, 0}}, {{0, 0}, {run, rise}}},
      {road_of(HighwayClass::trunk, false, 2), road_of(HighwayClass::trunk_link, true, 1)});
  Diagnostics d;
  EXPECT_EQ(detail::separate_close_roads(net, d), 0u);
}

}  // namespace
}  // namespace relief
