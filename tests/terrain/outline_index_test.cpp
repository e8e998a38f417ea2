#include "terrain/outline_index.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <random>
#include <vector>

namespace relief {
namespace {

using terrain_detail::OutlineHit;
using terrain_detail::OutlineIndex;

// A 10 m square whose corners rise 0, 10, 20, 30 m anticlockwise from the origin: the bottom
// edge has z = x, the closing edge (0, 10) -> (0, 0) z = 3 * y.
Polyline3 square() {
  return {{0, 0, 0}, {10, 0, 10}, {10, 10, 20}, {0, 10, 30}};
}

TEST(OutlineIndex, NoLoopsFindNothing) {
  const OutlineIndex index({}, 5.0);
  EXPECT_FALSE(index.nearest({0, 0}).has_value());
  const OutlineIndex empty_loop({Polyline3{}}, 5.0);
  EXPECT_FALSE(empty_loop.nearest({0, 0}).has_value());
}

TEST(OutlineIndex, NearestPointOfAnEdgeWithItsInterpolatedHeight) {
  const OutlineIndex index({square()}, 5.0);
  // (4, -3): 3 m below the bottom edge, at x = 4 where it is 4 m high.
  const std::optional<OutlineHit> below = index.nearest({4, -3});
  ASSERT_TRUE(below.has_value());
  EXPECT_NEAR(below->distance_m, 3.0, 1e-12);
  EXPECT_NEAR(below->z, 4.0, 1e-12);
  // (4, 2) inside: 2 m from the bottom edge, nearer than the others.
  const std::optional<OutlineHit> inside = index.nearest({4, 2});
  ASSERT_TRUE(inside.has_value());
  EXPECT_NEAR(inside->distance_m, 2.0, 1e-12);
  EXPECT_NEAR(inside->z, 4.0, 1e-12);
  // (13, 14): nearest the corner (10, 10) at 5 m, z 20.
  const std::optional<OutlineHit> corner = index.nearest({13, 14});
  ASSERT_TRUE(corner.has_value());
  EXPECT_NEAR(corner->distance_m, 5.0, 1e-12);
  EXPECT_NEAR(corner->z, 20.0, 1e-12);
}

TEST(OutlineIndex, TheLoopIsClosedFromItsLastPointToItsFirst) {
  // (-1, 5) is 1 m from the closing edge (0, 10, 30) -> (0, 0, 0), halfway along it: z 15.
  const OutlineIndex index({square()}, 5.0);
  const std::optional<OutlineHit> hit = index.nearest({-1, 5});
  ASSERT_TRUE(hit.has_value());
  EXPECT_NEAR(hit->distance_m, 1.0, 1e-12);
  EXPECT_NEAR(hit->z, 15.0, 1e-12);
}

TEST(OutlineIndex, NothingBeyondTheRadiusWhichIsInclusive) {
  // (4, -3) is exactly 3 m from the square.
  EXPECT_TRUE(OutlineIndex({square()}, 3.0).nearest({4, -3}).has_value());
  EXPECT_FALSE(OutlineIndex({square()}, 2.999).nearest({4, -3}).has_value());
  // Far outside the grid, and inside the square farther than the radius from every edge.
  EXPECT_FALSE(OutlineIndex({square()}, 3.0).nearest({500, -200}).has_value());
  EXPECT_FALSE(OutlineIndex({square()}, 3.0).nearest({5, 5}).has_value());
  const std::optional<OutlineHit> centre = OutlineIndex({square()}, 5.0).nearest({5, 5});
  ASSERT_TRUE(centre.has_value());
  EXPECT_NEAR(centre->distance_m, 5.0, 1e-12);
}

TEST(OutlineIndex, ALoopOfOnePointIsThatPoint) {
  const OutlineIndex index({Polyline3{{5, 5, 7}}}, 10.0);
  const std::optional<OutlineHit> hit = index.nearest({8, 9});
  ASSERT_TRUE(hit.has_value());
  EXPECT_NEAR(hit->distance_m, 5.0, 1e-12);
  EXPECT_NEAR(hit->z, 7.0, 1e-12);
}

TEST(OutlineIndex, TheNearestOfSeveralLoops) {
  // A second square 100 m to the right, 50 m up: a point 2 m left of its left edge (x = 98)
  // finds it, not the first square 88 m away.
  Polyline3 far = square();
  for (Vec3& v : far) v += Vec3(100, 0, 50);
  const OutlineIndex index({square(), far}, 5.0);
  const std::optional<OutlineHit> hit = index.nearest({98, 5});
  ASSERT_TRUE(hit.has_value());
  EXPECT_NEAR(hit->distance_m, 2.0, 1e-12);
  EXPECT_NEAR(hit->z, 50.0 + 15.0, 1e-12);           // the closing edge halfway: 50 + 30 / 2
  EXPECT_FALSE(index.nearest({55, 5}).has_value());  // 45 m from both
}

// Brute force over every segment, for comparison.
std::optional<OutlineHit> brute_nearest(const std::vector<Polyline3>& loops, double radius, const Vec2& p) {
  double best = std::numeric_limits<double>::infinity(), best_z = 0.0;
  for (const Polyline3& loop : loops) {
    for (std::size_t i = 0; i < loop.size(); ++i) {
      const Vec3& a = loop[i];
      const Vec3& b = loop[(i + 1) % loop.size()];
      const Vec2 ab = (b - a).head<2>();
      const double len2 = ab.squaredNorm();
      const double t = len2 > 0.0 ? std::clamp((p - a.head<2>()).dot(ab) / len2, 0.0, 1.0) : 0.0;
      const double d = (a.head<2>() + t * ab - p).norm();
      if (d < best) {
        best = d;
        best_z = a.z() + t * (b.z() - a.z());
      }
    }
  }
  if (best > radius) return std::nullopt;
  return OutlineHit{best, best_z};
}

TEST(OutlineIndex, AgreesWithBruteForceOnManySegments) {
  // Twenty random wobbly loops over 400 m, with segments from a few cm to tens of metres long,
  // queried at 2000 random points with several radii: the grid must find what a scan of all
  // segments finds (the same distance; heights agree when the nearest point is unique).
  std::mt19937 rng(15);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  std::vector<Polyline3> loops;
  for (int l = 0; l < 20; ++l) {
    const Vec2 c(400.0 * u01(rng), 400.0 * u01(rng));
    const double r0 = 2.0 + 40.0 * u01(rng);
    const int n = 3 + static_cast<int>(60 * u01(rng));
    Polyline3 loop;
    for (int k = 0; k < n; ++k) {
      const double a = 2.0 * std::numbers::pi * k / n;
      const double r = r0 * (0.6 + 0.4 * u01(rng));
      loop.emplace_back(c.x() + r * std::cos(a), c.y() + r * std::sin(a), 100.0 * u01(rng));
    }
    loops.push_back(loop);
  }
  for (const double radius : {0.5, 3.0, 12.0, 60.0}) {
    const OutlineIndex index(loops, radius);
    int hits = 0;
    for (int q = 0; q < 2000; ++q) {
      const Vec2 p(-80.0 + 560.0 * u01(rng), -80.0 + 560.0 * u01(rng));
      const std::optional<OutlineHit> got = index.nearest(p);
      const std::optional<OutlineHit> want = brute_nearest(loops, radius, p);
      ASSERT_EQ(got.has_value(), want.has_value()) << radius << " at " << p.transpose();
      if (!want) continue;
      ++hits;
      EXPECT_NEAR(got->distance_m, want->distance_m, 1e-9) << radius << " at " << p.transpose();
    }
    EXPECT_GT(hits, 20) << radius;  // the comparison is not vacuous
  }
}

}  // namespace
}  // namespace relief
