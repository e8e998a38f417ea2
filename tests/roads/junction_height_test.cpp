// The junction height surface (roads/junction_height.h): a plane stays a plane, every road end
// is met with its own height, grade and roll (C1 across the junction's edge), the analytic
// gradient is the surface's derivative, and a road laid on it follows it.
#include "relief/roads/junction_height.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <numbers>
#include <optional>
#include <random>
#include <tuple>

#include "relief/core/errors.h"
#include "relief/geometry/cubic_profile.h"
#include "roads/junction_planes.h"

namespace relief::detail {
namespace {

// An end of a junction centred at the origin: its reference point at distance r in direction
// `bearing`, its cross-section 7 m wide across that direction, on the plane (z0, g).
EndPlane end_on(double bearing, double r, double z0, const Vec2& g) {
  const Vec2 out(std::cos(bearing), std::sin(bearing));
  const Vec2 across(-out.y(), out.x());
  EndPlane e;
  e.point = r * out;
  e.right = e.point - 3.5 * across;
  e.left = e.point + 3.5 * across;
  e.z = z0 + g.dot(e.point);
  e.gradient = g;
  return e;
}

// Three ends of a T junction on the plane z = 10 + 0.12 x - 0.05 y.
std::vector<EndPlane> t_on_a_plane() {
  const Vec2 g(0.12, -0.05);
  return {end_on(0.0, 8.0, 10.0, g), end_on(std::numbers::pi / 2, 8.0, 10.0, g),
          end_on(std::numbers::pi, 8.0, 10.0, g)};
}

// At `points` random points of [-extent, extent]^2 the surface's gradient is its derivative
// (central differences) within `tolerance`.
void expect_gradient_is_derivative(const JunctionHeight& s, unsigned seed, int points, double extent,
                                   double tolerance) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-extent, extent);
  const double h = 1e-6;
  for (int i = 0; i < points; ++i) {
    const Vec2 p(u(rng), u(rng));
    const Vec2 g = s.at(p).second;
    const double gx = (s.at(p + Vec2(h, 0.0)).first - s.at(p - Vec2(h, 0.0)).first) / (2.0 * h);
    const double gy = (s.at(p + Vec2(0.0, h)).first - s.at(p - Vec2(0.0, h)).first) / (2.0 * h);
    EXPECT_NEAR(g.x(), gx, tolerance) << p.transpose();
    EXPECT_NEAR(g.y(), gy, tolerance) << p.transpose();
  }
}

TEST(JunctionHeight, APlaneStaysThePlane) {
  const JunctionHeight s(t_on_a_plane());
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-7.0, 7.0);
  for (int i = 0; i < 200; ++i) {
    const Vec2 p(u(rng), u(rng));
    const auto [z, g] = s.at(p);
    EXPECT_NEAR(z, 10.0 + 0.12 * p.x() - 0.05 * p.y(), 1e-9);
    EXPECT_NEAR((g - Vec2(0.12, -0.05)).norm(), 0.0, 1e-9);
  }
}

// Ends whose planes disagree (heights 0.6 m apart, grades and rolls of their own): on an end's
// cross-section the surface is that end's plane, and just inside it its gradient too.
TEST(JunctionHeight, EveryEndIsMetWithItsOwnHeightGradeAndRoll) {
  std::vector<EndPlane> ends{end_on(0.0, 8.0, 10.0, Vec2(0.10, 0.02)),
                             end_on(std::numbers::pi / 2, 8.0, 10.6, Vec2(-0.03, 0.15)),
                             end_on(std::numbers::pi, 9.0, 10.2, Vec2(0.04, -0.01))};
  const JunctionHeight s(ends);
  for (const EndPlane& e : ends) {
    for (const double f : {0.0, 0.3, 0.5, 1.0}) {
      const Vec2 p = e.right + f * (e.left - e.right);
      const auto [z, g] = s.at(p);
      EXPECT_NEAR(z, e.z + e.gradient.dot(p - e.point), 1e-12);
      // 1 mm inside the junction: the height within the plane's, the gradient within 1e-3.
      const Vec2 inside = p - 1e-3 * e.point.normalized();
      const auto [zi, gi] = s.at(inside);
      EXPECT_NEAR(zi, e.z + e.gradient.dot(inside - e.point), 1e-5);
      EXPECT_LT((gi - e.gradient).norm(), 1e-3);
    }
  }
}

TEST(JunctionHeight, TheGradientIsTheSurfacesDerivative) {
  const JunctionHeight s({end_on(0.3, 8.0, 10.0, Vec2(0.10, 0.02)), end_on(1.9, 7.0, 11.0, Vec2(-0.2, 0.05)),
                          end_on(3.5, 9.0, 10.2, Vec2(0.04, -0.01)), end_on(4.9, 6.0, 9.5, Vec2(0.0, 0.3))});
  expect_gradient_is_derivative(s, 11, 200, 5.0, 1e-6);
}

TEST(JunctionHeight, NoEndIsRefused) {
  EXPECT_THROW(JunctionHeight({}), InvalidInput);
}

// A quarter turn of radius 8 m across the plane of the T: its elevation follows the plane within
// the fit's 1 mm, its roll lays the cross-section on it within 1e-4 rad, and its steepest chord
// is the plane's slope along the arc.
TEST(JunctionHeight, ARoadLaidOnTheSurfaceFollowsIt) {
  const JunctionHeight s(t_on_a_plane());
  PlanGeometry arc;
  arc.kind = PlanGeometry::Kind::arc;
  arc.start = Vec2(-8.0, -3.0);
  arc.heading = 0.0;
  arc.length = 8.0 * std::numbers::pi / 2;
  arc.curvature = 1.0 / 8.0;
  const PlanView plan({arc});
  const SurfaceProfiles on = surface_profiles(plan, s);
  double steepest = 0.0;
  for (double t = 0.0; t <= plan.length(); t += 0.1) {
    const Pose2 pose = plan.at(t);
    const Vec2 g(0.12, -0.05);
    EXPECT_NEAR(on.elevation.value(t), 10.0 + g.dot(pose.position), 1e-3) << t;
    EXPECT_NEAR(on.superelevation.value(t), plane_roll(g, pose.heading), 1e-4) << t;
    steepest = std::max(steepest, std::abs(g.dot(Vec2(std::cos(pose.heading), std::sin(pose.heading)))));
  }
  EXPECT_LE(on.max_grade, steepest + 1e-9);
  EXPECT_GT(on.max_grade, steepest - 0.01);
}

// A road across a T junction whose side end lies 2 m over the plane of the other two: the
// surface bulges towards it, steeper along the road than the plane's 12 %. Under a grade limit
// between the two the road keeps the limit, leaves the surface only around the bulge (by less
// than the cubic between its ends would), and keeps its ends' heights and grades exactly.
TEST(JunctionHeight, ARoadTooSteepOnTheSurfaceLeavesItOnlyWhereItMust) {
  const Vec2 g(0.12, 0.0);
  std::vector<EndPlane> ends = {end_on(0.0, 8.0, 10.0, g), end_on(std::numbers::pi / 2, 8.0, 12.0, g),
                                end_on(std::numbers::pi, 8.0, 10.0, g)};
  const JunctionHeight s(ends);
  PlanGeometry line;
  line.kind = PlanGeometry::Kind::line;
  line.start = Vec2(-8.0, -2.0);
  line.heading = 0.0;
  line.length = 16.0;
  const PlanView plan({line});
  const SurfaceProfiles free = surface_profiles(plan, s);
  EXPECT_EQ(free.max_departure_m, 0.0);
  ASSERT_GT(free.max_grade, 0.14);  // the bulge's flank
  const double limit = 0.135;
  const SurfaceProfiles on = surface_profiles(plan, s, limit);
  EXPECT_EQ(on.max_grade, free.max_grade);
  EXPECT_GT(on.max_departure_m, 0.0);
  double steepest = 0.0, departure = 0.0, cubic_departure = 0.0;
  const CubicProfile cubic = hermite_profile(16.0, 10.0 - 0.96, 0.12, 10.0 + 0.96, 0.12);
  for (double t = 0.0; t <= 16.0; t += 0.05) {
    const double surface = s.at(plan.at(t).position).first;
    steepest = std::max(steepest, std::abs(on.elevation.derivative(t)));
    departure = std::max(departure, std::abs(on.elevation.value(t) - surface));
    cubic_departure = std::max(cubic_departure, std::abs(cubic.value(t) - surface));
  }
  EXPECT_LE(steepest, limit + 0.002);  // the cubics' grade, over the samples' chords
  EXPECT_NEAR(departure, on.max_departure_m, 2e-3);
  EXPECT_LT(departure, 0.5 * cubic_departure);
  EXPECT_NEAR(on.elevation.value(0.0), free.elevation.value(0.0), 1e-12);
  EXPECT_NEAR(on.elevation.value(16.0), free.elevation.value(16.0), 1e-9);
  EXPECT_NEAR(on.elevation.derivative(0.0), 0.12, 1e-9);
  EXPECT_NEAR(on.elevation.derivative(16.0), 0.12, 1e-9);
  std::cout << "  surface grade " << free.max_grade << ", limited " << steepest << ", departure " << departure
            << " m (the cubic between the ends: " << cubic_departure << " m)\n";
  // A limit under the ends' own 12 %: the straight line between them.
  const SurfaceProfiles straight = surface_profiles(plan, s, 0.1);
  for (double t = 0.0; t <= 16.0; t += 0.5)
    EXPECT_NEAR(straight.elevation.value(t), 9.04 + 0.12 * t, 1e-6) << t;
}

// A line of departures (linear along it) across the junction of EveryEndIsMet...: on every end's
// cross-section the surface and its gradient stay the end's plane; on the line, more than 1 m
// from the ends, it is the surface plus the line's departure; 4 m from the line it is the surface
// alone; and the gradient is the derivative of it all.
TEST(JunctionHeight, DeparturesAreTakenOnTheirLineAndFadeAway) {
  std::vector<EndPlane> ends{end_on(0.0, 8.0, 10.0, Vec2(0.10, 0.02)),
                             end_on(std::numbers::pi / 2, 8.0, 10.6, Vec2(-0.03, 0.15)),
                             end_on(std::numbers::pi, 9.0, 10.2, Vec2(0.04, -0.01))};
  const JunctionHeight s(ends);
  std::vector<Vec3> line;
  for (double x = -4.0; x <= 4.0; x += 0.5) line.emplace_back(x, -1.0, 0.2 + 0.05 * x);
  const JunctionHeight moved = s.with_departures({line});
  EXPECT_TRUE(moved.has_departures());
  EXPECT_FALSE(s.has_departures());
  for (const EndPlane& e : ends) {
    for (const double f : {0.0, 0.3, 0.5, 1.0}) {
      const Vec2 p = e.right + f * (e.left - e.right);
      const auto [z, g] = moved.at(p);
      EXPECT_NEAR(z, e.z + e.gradient.dot(p - e.point), 1e-12);
      EXPECT_LT((g - e.gradient).norm(), 1e-12);
    }
  }
  for (double x = -4.0; x <= 4.0; x += 0.25) {
    const Vec2 p(x, -1.0);
    EXPECT_NEAR(moved.at(p).first - s.at(p).first, 0.2 + 0.05 * x, 1e-9) << x;
    EXPECT_NEAR(moved.base_at(p).first, s.at(p).first, 1e-15) << x;
    const Vec2 far(x, -5.0);
    EXPECT_EQ(moved.at(far).first, s.at(far).first) << x;
  }
  expect_gradient_is_derivative(moved, 5, 300, 6.0, 1e-5);
}

// The road of ARoadTooSteep... leaves the surface around its bulge; a road crossing it where it
// leaves the surface most, laid on the surface alone, passes a step above it. Laid on the surface
// with the first road's departures, the two meet within the fits' millimetres, and the first road
// still keeps its limit and its ends.
TEST(JunctionHeight, ARoadCrossingOneThatLeftTheSurfaceMeetsItThere) {
  const Vec2 g(0.12, 0.0);
  const JunctionHeight s({end_on(0.0, 8.0, 10.0, g), end_on(std::numbers::pi / 2, 8.0, 12.0, g),
                          end_on(std::numbers::pi, 8.0, 10.0, g)});
  const auto straight = [](const Vec2& start, double heading, double length) {
    PlanGeometry line;
    line.kind = PlanGeometry::Kind::line;
    line.start = start;
    line.heading = heading;
    line.length = length;
    return PlanView({line});
  };
  const PlanView across = straight(Vec2(-8.0, -2.0), 0.0, 16.0);
  const double limit = 0.135;
  const SurfaceProfiles left = surface_profiles(across, s, limit);
  ASSERT_FALSE(left.left.empty());
  double t_most = 0.0, most = 0.0;
  for (double t = 0.0; t <= 16.0; t += 0.05) {
    const double d = std::abs(left.elevation.value(t) - s.at(across.at(t).position).first);
    if (d > most) std::tie(most, t_most) = std::make_pair(d, t);
  }
  const PlanView crossing = straight(Vec2(-8.0 + t_most, 7.0), -std::numbers::pi / 2, 14.0);
  const double t_crossing = 9.0;  // where it crosses y = -2
  const double step_before =
      std::abs(surface_profiles(crossing, s).elevation.value(t_crossing) - left.elevation.value(t_most));
  const JunctionHeight moved = s.with_departures({left.left});
  const SurfaceProfiles again = surface_profiles(across, moved, limit);
  const double step_after =
      std::abs(surface_profiles(crossing, moved).elevation.value(t_crossing) - again.elevation.value(t_most));
  std::cout << "  departure " << most << " m at s = " << t_most << "; step where a road crosses it "
            << step_before << " m on the surface alone, " << step_after << " m with its departures\n";
  EXPECT_GT(step_before, 0.015);
  EXPECT_LT(step_after, 0.002);
  double steepest = 0.0;
  for (double t = 0.0; t <= 16.0; t += 0.05)
    steepest = std::max(steepest, std::abs(again.elevation.derivative(t)));
  EXPECT_LE(steepest, limit + 0.002);
  EXPECT_NEAR(again.elevation.value(0.0), left.elevation.value(0.0), 1e-12);
  EXPECT_NEAR(again.elevation.value(16.0), left.elevation.value(16.0), 1e-9);
  EXPECT_NEAR(again.elevation.derivative(0.0), 0.12, 1e-9);
  EXPECT_NEAR(again.elevation.derivative(16.0), 0.12, 1e-9);
}

// A road's ends take their junction planes' rolls, eased to level within 50 m. A dead end meets
// no plane: it keeps what the other end's ease has left there (1 m stubs off junctions rolled
// 0.18 and 0.33 rad twisted to level within their metre in the fuzzer's seeds 19 and 17 with
// OSM errors, and SUMO's lanes stepped onto them).
TEST(JunctionPlanes, ADeadEndKeepsTheRollItsStubCannotEaseOff) {
  const auto ease = [](double r, double d) {
    const double v = std::min(d / 50.0, 1.0);
    return r * (1.0 - 3.0 * v * v + 2.0 * v * v * v);
  };
  const CubicProfile stub = end_rolls(1.0, 0.325, std::nullopt);
  EXPECT_NEAR(stub.value(0.0), 0.325, 1e-12);
  EXPECT_NEAR(stub.value(1.0), ease(0.325, 1.0), 1e-12);           // 0.32461
  EXPECT_NEAR(end_rolls(1.0, 0.325, 0.0).value(1.0), 0.0, 1e-12);  // between two planes it must turn
  const CubicProfile back = end_rolls(1.0, std::nullopt, 0.325);
  EXPECT_NEAR(back.value(0.0), ease(0.325, 1.0), 1e-12);
  EXPECT_NEAR(back.value(1.0), 0.325, 1e-12);
  // Up to the ease's length the dead end's roll is the ease itself, cut; beyond it, level.
  for (const double length : {1.0, 12.0, 30.0, 49.0}) {
    const CubicProfile road = end_rolls(length, 0.2, std::nullopt);
    const CubicProfile reversed = end_rolls(length, std::nullopt, 0.2);
    for (int k = 0; k <= 20; ++k) {
      const double s = length * k / 20.0;
      EXPECT_NEAR(road.value(s), ease(0.2, s), 1e-12) << length << " " << s;
      EXPECT_NEAR(reversed.value(s), ease(0.2, length - s), 1e-12) << length << " " << s;
    }
  }
  const CubicProfile long_road = end_rolls(120.0, 0.2, std::nullopt);
  for (int k = 0; k <= 24; ++k) {
    EXPECT_NEAR(long_road.value(5.0 * k), end_rolls(120.0, 0.2, 0.0).value(5.0 * k), 1e-12) << k;
  }
  EXPECT_EQ(end_rolls(10.0, std::nullopt, std::nullopt).value(5.0), 0.0);
}

// Two roads that left the surface in opposite directions, 1 m apart (one 1 m above it, one 1 m
// under): between them the surface falls 2 m within a metre, and a road crossing from one to the
// other lay across it at up to tan(roll) 5.6 (Fuzz seed 31). Across, a road now lies no steeper
// than its grade limit (or its ends' rolls, which it keeps exactly); the lane centre stays on
// the surface. Without a limit, the surface's own roll.
TEST(JunctionHeight, ARoadLiesAcrossTheSurfaceNoSteeperThanItsLimit) {
  const Vec2 g(0.05, 0.0);
  const JunctionHeight s({end_on(0.0, 8.0, 10.0, g), end_on(std::numbers::pi / 2, 8.0, 10.0, g),
                          end_on(std::numbers::pi, 8.0, 10.0, g)});
  std::vector<Vec3> up, down;
  for (double y = -4.0; y <= 4.0; y += 0.5) {
    up.emplace_back(-0.5, y, 1.0);
    down.emplace_back(0.5, y, -1.0);
  }
  const JunctionHeight moved = s.with_departures({up, down});
  PlanGeometry line;
  line.kind = PlanGeometry::Kind::line;
  line.start = Vec2(0.0, -12.0);
  line.heading = std::numbers::pi / 2;
  line.length = 24.0;
  const PlanView along(PlanView({line}));
  const double limit = 0.35;
  const SurfaceProfiles bounded = surface_profiles(along, moved, limit);
  const SurfaceProfiles free = surface_profiles(along, moved);
  double most_bounded = 0.0, most_free = 0.0;
  for (double t = 0.0; t <= 24.0; t += 0.05) {
    most_bounded = std::max(most_bounded, std::abs(std::tan(bounded.superelevation.value(t))));
    most_free = std::max(most_free, std::abs(std::tan(free.superelevation.value(t))));
    EXPECT_NEAR(bounded.elevation.value(t), free.elevation.value(t), 1e-12) << t;
  }
  std::cout << "  largest tan(roll) across two opposite departures: " << most_free << " on the surface, "
            << most_bounded << " within the limit " << limit << "\n";
  EXPECT_GT(most_free, 1.0);
  EXPECT_LE(most_bounded, limit + 0.01);  // the roll's cubics between its 0.5 m samples: 0.357
  for (const double t : {0.0, 24.0}) {
    EXPECT_NEAR(bounded.superelevation.value(t), free.superelevation.value(t), 1e-9) << t;
  }
}

}  // namespace
}  // namespace relief::detail
