#include "relief/geometry/polyline.h"

#include <gtest/gtest.h>

#include "relief/core/errors.h"

namespace relief {
namespace {

TEST(Polyline, CumulativeLengthOfAnLShape) {
  const Polyline2 line{{0, 0}, {3, 0}, {3, 4}};
  const auto s = cumulative_length(line);
  ASSERT_EQ(s.size(), 3u);
  EXPECT_DOUBLE_EQ(s[1], 3.0);
  EXPECT_DOUBLE_EQ(s[2], 7.0);
  EXPECT_DOUBLE_EQ(length_m(line), 7.0);
}

TEST(Polyline, PointAtInterpolatesAndClamps) {
  const Polyline2 line{{0, 0}, {3, 0}, {3, 4}};
  const auto s = cumulative_length(line);
  EXPECT_TRUE(point_at(line, s, 1.5).isApprox(Vec2(1.5, 0)));
  EXPECT_TRUE(point_at(line, s, 5.0).isApprox(Vec2(3, 2)));
  EXPECT_TRUE(point_at(line, s, -1.0).isApprox(Vec2(0, 0)));
  EXPECT_TRUE(point_at(line, s, 99.0).isApprox(Vec2(3, 4)));
  EXPECT_THROW((void)point_at({}, {}, 0.0), InvalidInput);
}

TEST(Polyline, StraightHundredMetreRoadHas101StationsAtOneMetre) {
  const auto st = sample_stations(100.0, 1.0, {0.0, 100.0});
  ASSERT_EQ(st.size(), 101u);
  for (std::size_t i = 0; i < st.size(); ++i) EXPECT_NEAR(st[i], static_cast<double>(i), 1e-12);
}

TEST(Polyline, StationsIncludeVerticesAndEnd) {
  const auto st = sample_stations(10.5, 2.0, {0.0, 3.3, 4.0, 10.5});
  const std::vector<double> expected{0.0, 2.0, 3.3, 4.0, 6.0, 8.0, 10.0, 10.5};
  ASSERT_EQ(st.size(), expected.size());
  for (std::size_t i = 0; i < st.size(); ++i) EXPECT_NEAR(st[i], expected[i], 1e-12);
  EXPECT_THROW((void)sample_stations(10.0, 0.0, {}), InvalidInput);
}

// Both ends stay, whatever the tolerance: a road 0.16 m long between two junctions (two ways
// crossing another without shared nodes, 0.16 m apart) had one station, and so gave both its
// junctions one height (a 3 m gap at one of them, in the fuzzer with OSM's data errors).
TEST(Polyline, ARoadShorterThanTheMergeToleranceKeepsBothEnds) {
  EXPECT_EQ(sample_stations(0.16, 1.0, {0.0, 0.16}, 0.25), (std::vector<double>{0.0, 0.16}));
  EXPECT_EQ(sample_stations(0.16, 1.0, {}, 0.25), (std::vector<double>{0.0, 0.16}));
  // A vertex within the tolerance of the end gives way to the end.
  EXPECT_EQ(sample_stations(3.0, 1.0, {2.9}, 0.25), (std::vector<double>{0.0, 1.0, 2.0, 3.0}));
  EXPECT_EQ(sample_stations(0.0, 1.0, {}, 0.25), (std::vector<double>{0.0}));
}

TEST(Polyline, DedupeDropsRepeatedVertices) {
  const Polyline2 line{{0, 0}, {0, 0}, {1, 0}, {1, 1e-9}, {2, 0}};
  const auto kept = dedupe_vertices(line, 1e-6);
  EXPECT_EQ(kept, (std::vector<std::size_t>{0, 2, 4}));
}

TEST(DouglasPeucker, KeepsWhatLiesBeyondTheToleranceAndSplitsWhereAsked) {
  // Heights over x = 0..8: flat but for a 1 m bump at x = 4 and a 0.05 m ripple at x = 6.
  const std::vector<double> z{0, 0, 0, 0, 1, 0, 0.05, 0, 0};
  const auto deviation = [&](std::size_t i, std::size_t k, std::size_t j) {
    const double t = static_cast<double>(k - i) / static_cast<double>(j - i);
    return std::abs(z[k] - (z[i] + t * (z[j] - z[i])));
  };
  EXPECT_EQ(douglas_peucker(z.size(), 0.1, deviation),
            (std::vector<std::uint8_t>{1, 0, 0, 1, 1, 1, 0, 0, 1}));
  EXPECT_EQ(douglas_peucker(z.size(), 0.01, deviation),
            (std::vector<std::uint8_t>{1, 0, 0, 1, 1, 1, 1, 1, 1}));
  // Chords longer than 4 points are split even where straight enough (at their middle).
  const auto long_chord = [](std::size_t i, std::size_t j) { return j - i > 4; };
  EXPECT_EQ(douglas_peucker(z.size(), 2.0, deviation, long_chord),
            (std::vector<std::uint8_t>{1, 0, 0, 0, 1, 0, 0, 0, 1}));
  EXPECT_TRUE(douglas_peucker(0, 1.0, deviation).empty());
  EXPECT_EQ(douglas_peucker(2, 1.0, deviation), (std::vector<std::uint8_t>{1, 1}));
}

// The foot on an L: on each leg, at the corner, past the end only when asked; a degenerate line
// has none.
TEST(NearestOnPolyline, FindsTheFootOnEachLegAndPastTheEndWhenAsked) {
  const Polyline2 l = {Vec2(0, 0), Vec2(10, 0), Vec2(10, 10)};
  PolylineFoot f = nearest_on_polyline(l, Vec2(4, 3));
  ASSERT_TRUE(f.found);
  EXPECT_EQ(f.segment, 0u);
  EXPECT_TRUE(f.point.isApprox(Vec2(4, 0)));
  EXPECT_TRUE(f.direction.isApprox(Vec2(1, 0)));
  f = nearest_on_polyline(l, Vec2(12, 7));
  EXPECT_EQ(f.segment, 1u);
  EXPECT_TRUE(f.point.isApprox(Vec2(10, 7)));
  EXPECT_TRUE(nearest_on_polyline(l, Vec2(11, 15)).point.isApprox(Vec2(10, 10)));
  EXPECT_TRUE(nearest_on_polyline(l, Vec2(11, 15), true).point.isApprox(Vec2(10, 15)));
  EXPECT_TRUE(
      nearest_on_polyline(l, Vec2(-3, 1), true).point.isApprox(Vec2(0, 0)));  // the start is not extended
  EXPECT_FALSE(nearest_on_polyline({Vec2(1, 1), Vec2(1, 1)}, Vec2(0, 0)).found);
  EXPECT_FALSE(nearest_on_polyline({}, Vec2(0, 0)).found);
}

}  // namespace
}  // namespace relief
