#include "relief/geometry/plane.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

namespace relief {
namespace {

constexpr double kPi = std::numbers::pi;

TEST(Plane, WrapAngleIntoMinusPiToPi) {
  EXPECT_NEAR(wrap_angle(1.5 * kPi), -0.5 * kPi, 1e-12);
  EXPECT_NEAR(wrap_angle(-1.5 * kPi), 0.5 * kPi, 1e-12);
  EXPECT_NEAR(wrap_angle(0.25 * kPi + 6.0 * kPi), 0.25 * kPi, 1e-12);
  EXPECT_NEAR(wrap_angle(-0.25 * kPi - 40.0 * kPi), -0.25 * kPi, 1e-12);
  EXPECT_EQ(wrap_angle(0.3), 0.3);
  // The interval is open below and closed above: -pi wraps to pi, pi stays.
  EXPECT_EQ(wrap_angle(kPi), kPi);
  EXPECT_EQ(wrap_angle(-kPi), kPi);
  EXPECT_EQ(wrap_angle(3.0 * kPi), kPi);
  EXPECT_TRUE(std::isnan(wrap_angle(std::numeric_limits<double>::infinity())));
}

// Subtracting 2 pi until the angle is in range (the road model's former copy) rounds nothing for
// angles within 22 pi: both give the same double.
TEST(Plane, WrapAngleMatchesRepeatedSubtractionWithinElevenTurns) {
  const auto by_steps = [](double a) {
    while (a > kPi) a -= 2.0 * kPi;
    while (a <= -kPi) a += 2.0 * kPi;
    return a;
  };
  for (int k = -220000; k <= 220000; ++k) {
    const double a = k * 1e-4 * kPi + 1e-7 * k;  // not a multiple of pi
    ASSERT_EQ(wrap_angle(a), by_steps(a)) << a;
  }
}

TEST(Plane, CrossIsPositiveTurningLeft) {
  EXPECT_EQ(cross(Vec2(1, 0), Vec2(0, 1)), 1.0);
  EXPECT_EQ(cross(Vec2(0, 1), Vec2(1, 0)), -1.0);
  EXPECT_EQ(cross(Vec2(2, 3), Vec2(4, 6)), 0.0);  // parallel
  EXPECT_EQ(cross(Vec2(3, 0), Vec2(1, 2)), 6.0);  // |a| |b| sin
  EXPECT_EQ(cross(Vec2(1, 2), Vec2(3, 0)), -6.0);
}

TEST(Plane, PointSegmentDistanceBeforeAlongAndAfter) {
  const Vec2 a(0, 0), b(10, 0);
  EXPECT_DOUBLE_EQ(point_segment_distance(Vec2(-3, 4), a, b), 5.0);  // before a: to a
  EXPECT_DOUBLE_EQ(point_segment_distance(Vec2(4, -2), a, b), 2.0);  // along: perpendicular
  EXPECT_DOUBLE_EQ(point_segment_distance(Vec2(13, 4), a, b), 5.0);  // after b: to b
  EXPECT_DOUBLE_EQ(point_segment_distance(Vec2(6, 0), a, b), 0.0);   // on it
  EXPECT_DOUBLE_EQ(point_segment_distance(Vec2(3, 4), a, a), 5.0);   // a point
  EXPECT_DOUBLE_EQ(segment_parameter(Vec2(-3, 4), a, b), 0.0);
  EXPECT_DOUBLE_EQ(segment_parameter(Vec2(4, -2), a, b), 0.4);
  EXPECT_DOUBLE_EQ(segment_parameter(Vec2(13, 4), a, b), 1.0);
}

TEST(Plane, PointSegmentDistanceInSpace) {
  const Vec3 a(0, 0, 0), b(0, 0, 10);
  EXPECT_DOUBLE_EQ(point_segment_distance(Vec3(3, 4, 5), a, b), 5.0);   // along
  EXPECT_DOUBLE_EQ(point_segment_distance(Vec3(0, 3, -4), a, b), 5.0);  // before a
  EXPECT_DOUBLE_EQ(point_segment_distance(Vec3(0, 0, 12), a, b), 2.0);  // after b
}

}  // namespace
}  // namespace relief
