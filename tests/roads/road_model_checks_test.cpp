#include "relief/roads/road_model_checks.h"

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace relief
