#include "relief/geometry/polygon.h"

#include <cmath>

#include <gtest/gtest.h>

namespace relief {
namespace {

TEST(ConvexHull, KeepsTheCornersCounterClockwiseAndDropsInnerCollinearAndRepeatedPoints) {
  // A 4 x 3 rectangle with a point inside, a point on each of two sides and a repeated corner.
  const Polyline2 hull = convex_hull({{4, 3}, {1, 1}, {0, 0}, {2, 0}, {4, 0}, {0, 3}, {4, 1.5}, {0, 0}});
  EXPECT_EQ(hull, (Polyline2{{0, 0}, {4, 0}, {4, 3}, {0, 3}}));
}

TEST(ConvexHull, DegenerateSetsGiveTheirDistinctOrExtremePoints) {
  EXPECT_TRUE(convex_hull({}).empty());
  EXPECT_EQ(convex_hull({{1, 2}, {1, 2}}), (Polyline2{{1, 2}}));
  EXPECT_EQ(convex_hull({{2, 2}, {0, 0}, {1, 1}, {3, 3}}), (Polyline2{{0, 0}, {3, 3}}));
}

TEST(ConvexHull, AreaOfManyPointsOnACircleApproachesTheCircle) {
  Polyline2 points;
  for (int k = 0; k < 360; ++k) {
    const double a = k * 3.14159265358979323846 / 180.0;
    points.emplace_back(10.0 * std::cos(a), 10.0 * std::sin(a));
    points.emplace_back(5.0 * std::cos(a), 5.0 * std::sin(a));  // inside
  }
  const Polyline2 hull = convex_hull(points);
  ASSERT_EQ(hull.size(), 360u);
  double area = 0.0;
  for (std::size_t i = 0, j = hull.size() - 1; i < hull.size(); j = i++)
    area += hull[j].x() * hull[i].y() - hull[i].x() * hull[j].y();
  EXPECT_NEAR(0.5 * area, 360.0 / 2.0 * 100.0 * std::sin(2.0 * 3.14159265358979323846 / 360.0), 1e-9);
}

}  // namespace
}  // namespace relief
