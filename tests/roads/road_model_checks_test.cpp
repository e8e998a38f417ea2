#include "relief/roads/road_model_checks.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "support/road_models.h"

namespace relief {
namespace {

// Two connecting roads of one junction crossing at right angles at (10, 0): one level at 0.0,
// the other climbing 5 % from 0.2 (at the crossing 0.7 m); lanes 1 (3 m) and -1 (3.5 m) each.
// Their lane centres cross at four points, where the heights differ by what the profiles say.
TEST(ConnectingRoadCrossings, FindsTheHeightStepWhereLaneCentresCross) {
  RoadModel model;
  model.roads.push_back(test::straight_road(1, Vec2(0.0, 0.0), 0.0, 20.0, 0.0, 0.0));
  model.roads.push_back(test::straight_road(2, Vec2(10.0, -10.0), std::numbers::pi / 2, 20.0, 0.2, 0.05));
  for (ModelRoad& r : model.roads) r.junction = 7;
  const ConnectingRoadCrossings c = check_connecting_road_crossings(model);
  EXPECT_EQ(c.worst_junction, 7);
  EXPECT_EQ(c.junctions_over, 1u);
  EXPECT_GE(c.crossings, 8u);  // each of 4 crossings measured from both roads
  // Road 2's lane centres lie at x = 10 -+ 1.5 / 1.75; road 1's at y = +1.5 and -1.75: road 2's
  // height there 0.2 + 0.05 (10 + y), largest at y = 1.5: 0.775 m above road 1.
  EXPECT_NEAR(c.max_step_m, 0.2 + 0.05 * 11.5, 0.05 * 0.05 + 1e-9);
  // The same profiles apart in height only where they cross: level roads agree.
  model.roads[1] = test::straight_road(2, Vec2(10.0, -10.0), std::numbers::pi / 2, 20.0, 0.0, 0.0);
  model.roads[1].junction = 7;
  const ConnectingRoadCrossings level = check_connecting_road_crossings(model);
  EXPECT_LT(level.max_step_m, 1e-12);
  EXPECT_EQ(level.junctions_over, 0u);
  // Roads outside junctions are not connecting roads: nothing to measure.
  for (ModelRoad& r : model.roads) r.junction = -1;
  EXPECT_EQ(check_connecting_road_crossings(model).crossings, 0u);
}

// Road 1 leaves junction 7 east, climbing 10 % from 1.0 m (lanes 1 of 3 m and -1 of 3.5 m: its
// pavement y in [-3.5, 3]); connecting road 2 of junction 7 crosses it northwards at x = 5, level
// at 1.5 m, its lane centres at x = 5 + 1.75 (lane -1) and 5 - 1.5 (lane 1), where road 1 lies at
// 1.675 and 1.35 m.
TEST(ConnectingRoadsOverRoads, MeasuresAConnectingRoadAgainstTheRoadItCrosses) {
  RoadModel model;
  model.roads.push_back(test::straight_road(1, Vec2(0.0, 0.0), 0.0, 40.0, 1.0, 0.1));
  model.roads[0].predecessor = RoadLink{RoadLink::Element::junction, 7, RoadLink::Contact::start};
  model.roads.push_back(test::straight_road(2, Vec2(5.0, -10.0), std::numbers::pi / 2, 20.0, 1.5, 0.0));
  model.roads[1].junction = 7;
  const ConnectingRoadsOverRoads c = check_connecting_roads_over_roads(model);
  EXPECT_NEAR(c.max_step_m, 0.175, 1e-9);
  EXPECT_EQ(c.worst_road, 1);
  EXPECT_EQ(c.worst_junction, 7);
  EXPECT_EQ(c.junctions_over, 1u);
  EXPECT_NEAR(c.worst_xy.x(), 6.75, 1e-9);
  // 6.5 m of pavement under each lane centre, sampled every 0.25 m: 26 or 27 samples each.
  EXPECT_GE(c.samples, 52u);
  EXPECT_LE(c.samples, 56u);
  // Road 1 ends at another junction: not this one's to measure.
  model.roads[0].predecessor->id = 8;
  EXPECT_EQ(check_connecting_roads_over_roads(model).samples, 0u);
  // Beyond the reach from the junction (crossing at x = 35, 30 m reach) nothing is measured.
  model.roads[0].predecessor->id = 7;
  model.roads[1] = test::straight_road(2, Vec2(35.0, -10.0), std::numbers::pi / 2, 20.0, 1.5, 0.0);
  model.roads[1].junction = 7;
  EXPECT_EQ(check_connecting_roads_over_roads(model).samples, 0u);
}

// Three 40 m roads east, level: road 1 rolled from 0.3 rad (tan: 30.9 %) to 0 by a cubic with
// level ends, road 2 not at all, and a connecting road rolled 0.5 rad (left out: it lies on its
// junction's surface). Road 1's roll falls through atan(0.08) where 0.3 (1 - x)^2 (1 + 2x) =
// 0.0798, x = s / 40: at s = 26.46 m, so 26.46 m of it lie over 8 %.
TEST(ModelGrades, MeasuresTheRoadsCrossSlopes) {
  RoadModel model;
  model.roads.push_back(test::straight_road(1, Vec2(0.0, 0.0), 0.0, 40.0, 0.0, 0.0));
  model.roads.push_back(test::straight_road(2, Vec2(0.0, 10.0), 0.0, 40.0, 0.0, 0.0));
  model.roads.push_back(test::straight_road(3, Vec2(0.0, 20.0), 0.0, 40.0, 0.0, 0.0));
  model.roads[0].superelevation = hermite_profile(40.0, 0.3, 0.0, 0.0, 0.0);
  model.roads[2].superelevation = CubicProfile::constant(0.5);
  model.roads[2].junction = 4;
  const ModelGrades g = check_grades(model, {0.1, 0.1, -1.0});
  const CrossSlopeCheck& c = g.cross_slopes;
  EXPECT_NEAR(c.max_percent, 100.0 * std::tan(0.3), 0.1);  // the first chord's middle, s = 0.25 m
  EXPECT_EQ(c.worst_road, 1);
  EXPECT_NEAR(c.worst_s, 0.25, 1e-9);
  EXPECT_NEAR(c.length_m, 80.0, 1e-9);
  EXPECT_NEAR(c.length_over_m, 26.46, 0.5);  // sampled every 0.5 m
  EXPECT_EQ(c.roads_over, 1u);
  // At 35 % nothing is over.
  EXPECT_EQ(check_grades(model, {0.1, 0.1, -1.0}, 0.0, 0.5, 0.35).cross_slopes.roads_over, 0u);
}

}  // namespace
}  // namespace relief
