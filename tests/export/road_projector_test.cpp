#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "export/sumo_lane_locator.h"

namespace relief {
namespace {

// A road of arcs (curvature) and lines (curvature 0) of the given lengths from (x, y) heading
// `heading`.
ModelRoad road_of(double x, double y, double heading, const std::vector<std::pair<double, double>>& pieces) {
  std::vector<PlanGeometry> records;
  Pose2 at{Vec2(x, y), heading, 0.0};
  double s = 0.0;
  for (const auto& [length, curvature] : pieces) {
    PlanGeometry g;
    g.kind = curvature == 0.0 ? PlanGeometry::Kind::line : PlanGeometry::Kind::arc;
    g.s = s;
    g.start = at.position;
    g.heading = at.heading;
    g.length = length;
    g.curvature = curvature;
    records.push_back(g);
    at = PlanView({g}).at(s + length);
    s += length;
  }
  ModelRoad road;
  road.id = 1;
  road.plan = PlanView(std::move(records));
  return road;
}

// The nearest point of the road to p by brute force (every millimetre).
double nearest_station(const ModelRoad& road, const Vec2& p) {
  double best = 0.0, best_d = 1e300;
  for (double s = 0.0; s <= road.length(); s += 1e-3) {
    const double d = (road.plan.at(s).position - p).norm();
    if (d < best_d) {
      best_d = d;
      best = s;
    }
  }
  return best;
}

// NE's connection 779:1 -> 755:-3 at J465, from a parking lane back onto Bush Street: it turns
// 148 degrees right on a 1.7 m radius, then runs 0.57 m straight. A car centred 0.89 m right of
// its start (station 0), facing north across the turn: its front right wheel, 1.35 m ahead, lies
// past the turn's centre seen from station 0, 0.1 m past the road's end. Newton from the
// centre's station stopped at the start, 0.28 m behind it, and the cosim measured that wheel on
// the parking lane, 0.5 m under the street it stands on.
TEST(RoadProjector, AHintedProjectionPastATightTurnsCentreFindsTheRoadsEnd) {
  const ModelRoad road =
      road_of(0.0, 0.0, 2.753032360, {{4.401078140, -0.5879880034935566}, {0.568692950, 0.0}});
  const detail::RoadProjector projector(road);
  const Vec2 wheel(773.241 - 772.024070382, -56.795 + 59.016467384);
  for (const std::optional<double> hint : {std::optional<double>(), std::optional<double>(0.0)}) {
    const detail::Projection at = projector.project(wheel, hint);
    EXPECT_NEAR(at.s, road.length(), 1e-9);
    EXPECT_NEAR(at.beyond, 0.1026, 1e-4);
  }
}

// Liechtenstein's Bergstrasse 3377 at s = 596: a hairpin of 3.75 m arcs and short lines. A car
// centred on the right lane at s = 596.1 heading down it: its rear right wheel's nearest point
// is 1.9 m further along, 2.5 m to the right. Newton from the centre's station ran off to the
// hairpin's other leg (s = 616.5, 11.9 m away), and the cosim measured that wheel 3 m too low.
TEST(RoadProjector, AHintedProjectionOnAHairpinStaysOnItsLeg) {
  const ModelRoad road = road_of(-675.786474814, -4786.925782320, -0.826425355,
                                 {{1.468657497, -0.18403567108860888},
                                  {5.822086579, 0.0},
                                  {1.447790543, -0.26666666666666666},
                                  {4.511020086, 0.0},
                                  {2.181273131, -0.26666666666666666},
                                  {3.798165982, 0.0},
                                  {2.202866928, -0.26666666666666666},
                                  {1.130679344, 0.0},
                                  {2.220224546, 0.0006231201782413413},
                                  {0.224297975, 0.0},
                                  {1.739738543, -0.26666666666666666},
                                  {5.017639279, 0.0},
                                  {1.337114027, -0.26666666666666666},
                                  {4.235690072, 0.0}});
  const detail::RoadProjector projector(road);
  const double centre = 596.116 - 587.887062513;
  const Vec2 wheel(-674.256, -4796.276);
  const double expected = nearest_station(road, wheel);
  EXPECT_NEAR(expected, 597.999 - 587.887062513, 2e-3);
  for (const std::optional<double> hint : {std::optional<double>(), std::optional<double>(centre)}) {
    const detail::Projection at = projector.project(wheel, hint);
    EXPECT_NEAR(at.s, expected, 2e-3);
    EXPECT_NEAR(at.t, -2.495, 2e-3);
    EXPECT_EQ(at.beyond, 0.0);
  }
}

// Every point within 3 m of the hairpin, hinted from a station whose point lies within 1.5 m of
// it, projects to its nearest point on the road, as the search of the whole road does.
TEST(RoadProjector, HintedProjectionsNearTheRoadMatchTheBruteForceNearestPoint) {
  const ModelRoad road = road_of(0.0, 0.0, 0.0, {{6.0, 0.0}, {11.78, -0.26666666666666666}, {6.0, 0.0}});
  const detail::RoadProjector projector(road);
  int checked = 0;
  for (double s = 0.5; s < road.length() - 0.5; s += 0.7) {
    const Pose2 pose = road.plan.at(s);
    const Vec2 left(-std::sin(pose.heading), std::cos(pose.heading));
    const Vec2 ahead(std::cos(pose.heading), std::sin(pose.heading));
    for (const double t : {-2.5, -1.0, 1.0, 2.5}) {
      const Vec2 p = pose.position + t * left + 0.8 * ahead;
      const double expected = nearest_station(road, p);
      if ((road.plan.at(expected).position - p).norm() < std::abs(t) - 0.5) continue;  // the other leg's
      const detail::Projection at = projector.project(p, s);
      EXPECT_NEAR(at.s, expected, 2e-3) << "s " << s << " t " << t;
      ++checked;
    }
  }
  EXPECT_GT(checked, 100);
}

}  // namespace
}  // namespace relief
