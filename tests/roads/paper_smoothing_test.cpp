#include "relief/roads/paper_smoothing.h"

#include <gtest/gtest.h>

#include "support/synthetic.h"

namespace relief {
namespace {

RoadProfile profile_of(const Road& road, const std::function<double(double)>& z_of_x) {
  RoadProfile p = make_stations(road, 1.0);
  for (std::size_t i = 0; i < p.size(); ++i) p.z[i] = z_of_x(p.xy[i].x());
  return p;
}

TEST(PaperSmoothing, ALocalSpikeIsAveragedAwayAndEndsStay) {
  const RoadNetwork net = test::make_network({{{0, 0}, {100, 0}}});
  // A flat street with a 1 m spike at x = 50 (100 % grades on both sides of it).
  const RoadProfile raw = profile_of(net.roads[0], [](double x) { return x == 50.0 ? 11.0 : 10.0; });
  const PaperSmoothingResult r = smooth_paper(net, {raw});
  EXPECT_TRUE(r.not_converged_roads.empty());
  EXPECT_GT(r.iterations[0], 0);
  const auto g = segment_grades_percent(r.profiles[0]);
  EXPECT_LE(*std::max_element(g.begin(), g.end()), 15.0 + 1e-9);
  EXPECT_DOUBLE_EQ(r.profiles[0].z.front(), 10.0);
  EXPECT_DOUBLE_EQ(r.profiles[0].z.back(), 10.0);
  EXPECT_NEAR(r.max_shift_m, 11.0 - r.profiles[0].z[50], 1e-12);  // the spike itself moved most
}

TEST(PaperSmoothing, AStreetSteeperEndToEndThanItsLimitCannotConverge) {
  // A residential block rising 20 % end to end: the limit is 15 % and the ends are fixed.
  const RoadNetwork net = test::make_network({{{0, 0}, {100, 0}}});
  const RoadProfile raw = profile_of(net.roads[0], [](double x) { return 0.2 * x; });
  PaperSmoothingOptions o;
  o.max_iterations = 200;
  const PaperSmoothingResult r = smooth_paper(net, {raw}, o);
  ASSERT_EQ(r.not_converged_roads.size(), 1u);
  EXPECT_EQ(r.iterations[0], 200);
  // A straight ramp is a fixed point of the moving average: nothing moved.
  EXPECT_NEAR(r.max_shift_m, 0.0, 1e-9);
}

}  // namespace
}  // namespace relief
