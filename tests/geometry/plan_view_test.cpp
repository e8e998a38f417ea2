#include "relief/geometry/plan_view.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "relief/core/errors.h"
#include "support/plan_records.h"

namespace relief {
namespace {

constexpr double kPi = std::numbers::pi;

using test::arc_record;
using test::line_record;

PlanGeometry spiral(double length, double k0, double k1) {
  PlanGeometry g = line_record(0.0, Vec2::Zero(), 0.0, length);
  g.kind = PlanGeometry::Kind::spiral;
  g.curvature_start = k0;
  g.curvature_end = k1;
  return g;
}

// Fresnel-type integrals of a clothoid starting with curvature 0, heading 0: heading(σ) = a σ²,
// by their power series ∫ cos(a σ²) = Σ (-1)^n a^{2n} L^{4n+1} / ((2n)! (4n+1)), same for sin.
Vec2 clothoid_end(double a, double length) {
  double x = 0.0;
  double y = 0.0;
  const double phase = a * length * length;
  double term = length;  // phase^k / k! * length
  for (int k = 0; k < 80; ++k) {
    const double value = term / (2.0 * k + 1.0);
    switch (k % 4) {
      case 0:
        x += value;
        break;
      case 1:
        y += value;
        break;
      case 2:
        x -= value;
        break;
      case 3:
        y -= value;
        break;
    }
    term *= phase / (k + 1.0);
  }
  return {x, y};
}

TEST(PlanView, LineMovesAlongItsHeading) {
  const auto g = line_record(0.0, {1.0, 2.0}, kPi / 6.0, 10.0);
  const Pose2 p = evaluate(g, 4.0);
  EXPECT_NEAR(p.position.x(), 1.0 + 4.0 * std::cos(kPi / 6.0), 1e-12);
  EXPECT_NEAR(p.position.y(), 2.0 + 4.0 * std::sin(kPi / 6.0), 1e-12);
  EXPECT_NEAR(p.heading, kPi / 6.0, 1e-15);
  EXPECT_EQ(p.curvature, 0.0);
}

TEST(PlanView, QuarterArcsTurnLeftAndRight) {
  const double r = 10.0;
  const auto left = evaluate(arc_record(0.0, Vec2::Zero(), 0.0, 0.5 * kPi * r, 1.0 / r), 0.5 * kPi * r);
  EXPECT_NEAR(left.position.x(), 10.0, 1e-12);
  EXPECT_NEAR(left.position.y(), 10.0, 1e-12);
  EXPECT_NEAR(left.heading, 0.5 * kPi, 1e-15);
  EXPECT_NEAR(left.curvature, 0.1, 1e-15);

  const auto right = evaluate(arc_record(0.0, Vec2::Zero(), 0.0, 0.5 * kPi * r, -1.0 / r), 0.5 * kPi * r);
  EXPECT_NEAR(right.position.x(), 10.0, 1e-12);
  EXPECT_NEAR(right.position.y(), -10.0, 1e-12);
  EXPECT_NEAR(right.heading, -0.5 * kPi, 1e-15);

  // A point at an arbitrary ds lies on the circle centred at (0, r).
  const auto mid = evaluate(arc_record(0.0, Vec2::Zero(), 0.0, 50.0, 1.0 / r), 13.7);
  EXPECT_NEAR((mid.position - Vec2(0.0, r)).norm(), r, 1e-12);
  EXPECT_NEAR(mid.heading, 1.37, 1e-15);
}

TEST(PlanView, TinyArcCurvatureMatchesLine) {
  const auto p = evaluate(arc_record(0.0, Vec2::Zero(), 0.3, 100.0, 1e-12), 100.0);
  EXPECT_NEAR(p.position.x(), 100.0 * std::cos(0.3), 1e-8);
  EXPECT_NEAR(p.position.y(), 100.0 * std::sin(0.3), 1e-8);
}

TEST(PlanView, ClothoidMatchesFresnelSeriesWithinNanometre) {
  // Curvature 0 -> 0.004 over 1 km: heading = c σ² / 2, total turn 2 rad.
  const double length = 1000.0;
  const double k1 = 0.004;
  const auto g = spiral(length, 0.0, k1);
  const double a = 0.5 * k1 / length;
  for (double ds : {0.0, 1.0, 123.4, 500.0, 999.0, 1000.0}) {
    const Pose2 p = evaluate(g, ds);
    const Vec2 expected = clothoid_end(a, ds);
    EXPECT_NEAR(p.position.x(), expected.x(), 1e-9) << ds;
    EXPECT_NEAR(p.position.y(), expected.y(), 1e-9) << ds;
    EXPECT_NEAR(p.heading, a * ds * ds, 1e-12);
    EXPECT_NEAR(p.curvature, k1 * ds / length, 1e-15);
  }
}

TEST(PlanView, SpiralWithConstantCurvatureIsAnArc) {
  const auto s = spiral(800.0, -0.02, -0.02);
  const auto a = arc_record(0.0, Vec2::Zero(), 0.0, 800.0, -0.02);
  for (double ds : {10.0, 400.0, 800.0}) {
    EXPECT_LT((evaluate(s, ds).position - evaluate(a, ds).position).norm(), 1e-9) << ds;
    EXPECT_NEAR(evaluate(s, ds).heading, evaluate(a, ds).heading, 1e-12);
  }
}

TEST(PlanView, ReversedClothoidIsTheMirroredForwardOne) {
  // A spiral 0.01 -> 0 ending at heading h: walking it backwards is the 0 -> 0.01 spiral mirrored.
  const double length = 300.0;
  const auto fwd = spiral(length, 0.0, 0.01);
  const Pose2 end = evaluate(fwd, length);
  PlanGeometry back = spiral(length, -0.01, 0.0);
  back.start = end.position;
  back.heading = end.heading + kPi;
  const Pose2 p = evaluate(back, length);
  EXPECT_LT(p.position.norm(), 1e-9);
  EXPECT_NEAR(std::remainder(p.heading - kPi, 2.0 * kPi), 0.0, 1e-12);
}

// u = 10 p, v = 5 p^2: the parabola y = x^2 / 20 for x in [0, 10].
double parabola_length(double x) {
  const double q = x / 10.0;
  return 0.5 * x * std::sqrt(1.0 + q * q) + 5.0 * std::asinh(q);
}

TEST(PlanView, ParamPoly3LengthOfAParabola) {
  const Poly3 u{0.0, 10.0, 0.0, 0.0};
  const Poly3 v{0.0, 0.0, 5.0, 0.0};
  EXPECT_NEAR(param_poly3_length(u, v, 1.0), parabola_length(10.0), 1e-9);
  EXPECT_NEAR(param_poly3_length(u, v, 0.37), parabola_length(3.7), 1e-9);
  EXPECT_EQ(param_poly3_length(u, v, 0.0), 0.0);
}

TEST(PlanView, ParamPoly3EvaluatesByArcLength) {
  PlanGeometry g = line_record(0.0, {100.0, 50.0}, kPi / 2.0, 0.0);
  g.kind = PlanGeometry::Kind::param_poly3;
  g.u = Poly3{0.0, 10.0, 0.0, 0.0};
  g.v = Poly3{0.0, 0.0, 5.0, 0.0};
  g.length = param_poly3_length(g.u, g.v, 1.0);
  for (double x : {0.0, 1.0, 4.2, 7.77, 10.0}) {
    const Pose2 p = evaluate(g, parabola_length(x));
    // Local (x, x^2/20) rotated by 90 degrees: (-y, x).
    EXPECT_NEAR(p.position.x(), 100.0 - x * x / 20.0, 1e-6) << x;
    EXPECT_NEAR(p.position.y(), 50.0 + x, 1e-6) << x;
    EXPECT_NEAR(p.heading, kPi / 2.0 + std::atan(x / 10.0), 1e-6) << x;
    EXPECT_NEAR(p.curvature, 0.1 / std::pow(1.0 + x * x / 100.0, 1.5), 1e-6) << x;
  }
}

TEST(PlanView, ParamPoly3WithArcLengthRange) {
  PlanGeometry g = line_record(0.0, Vec2::Zero(), 0.0, 7.0);
  g.kind = PlanGeometry::Kind::param_poly3;
  g.normalized = false;
  g.u = Poly3{0.0, 1.0, 0.0, 0.0};
  const Pose2 p = evaluate(g, 3.0);
  EXPECT_NEAR(p.position.x(), 3.0, 1e-9);
  EXPECT_NEAR(p.position.y(), 0.0, 1e-12);
  EXPECT_NEAR(evaluate(g, 7.0).position.x(), 7.0, 1e-12);
}

TEST(PlanView, EvaluateClampsDs) {
  const auto g = line_record(0.0, Vec2::Zero(), 0.0, 5.0);
  EXPECT_NEAR(evaluate(g, -1.0).position.x(), 0.0, 1e-15);
  EXPECT_NEAR(evaluate(g, 9.0).position.x(), 5.0, 1e-15);
}

PlanView line_then_arc() {
  const double r = 20.0;
  return PlanView({line_record(0.0, Vec2::Zero(), 0.0, 10.0),
                   arc_record(10.0, {10.0, 0.0}, 0.0, 0.5 * kPi * r, 1.0 / r)});
}

TEST(PlanView, TotalTurnIntegratesAbsoluteCurvature) {
  // Line (no turn), quarter arc of radius 20 (pi/2), spiral from -0.1 to 0.3 1/m over 20 m
  // (crosses zero at 5 m: triangles of 0.25 and 2.25 rad), then the parabola u = 10 p,
  // v = 5 p^2 whose heading turns by atan(1) over its length.
  const double r = 20.0;
  PlanGeometry s = spiral(20.0, -0.1, 0.3);
  s.s = 10.0 + 0.5 * kPi * r;
  PlanGeometry p = line_record(s.s + 20.0, Vec2::Zero(), 0.0, 0.0);
  p.kind = PlanGeometry::Kind::param_poly3;
  p.u = Poly3{0.0, 10.0, 0.0, 0.0};
  p.v = Poly3{0.0, 0.0, 5.0, 0.0};
  p.length = param_poly3_length(p.u, p.v, 1.0);
  const PlanView plan({line_record(0.0, Vec2::Zero(), 0.0, 10.0),
                       arc_record(10.0, {10.0, 0.0}, 0.0, 0.5 * kPi * r, 1.0 / r), s, p});
  EXPECT_EQ(plan.total_turn(0.0, 10.0), 0.0);
  EXPECT_NEAR(plan.total_turn(0.0, s.s), 0.5 * kPi, 1e-12);
  EXPECT_NEAR(plan.total_turn(10.0 + 0.25 * kPi * r, s.s), 0.25 * kPi, 1e-12);  // half the arc
  EXPECT_NEAR(plan.total_turn(s.s, s.s + 20.0), 0.25 + 2.25, 1e-12);
  EXPECT_NEAR(plan.total_turn(s.s, s.s + 5.0), 0.25, 1e-12);
  EXPECT_NEAR(plan.total_turn(s.s + 5.0, s.s + 10.0), 0.25, 1e-12);        // 0 to 0.1 over 5 m
  EXPECT_NEAR(plan.total_turn(p.s, plan.length()), std::atan(1.0), 1e-4);  // midpoint sums
  EXPECT_NEAR(plan.total_turn(-5.0, 1e9), 0.5 * kPi + 2.5 + std::atan(1.0), 1e-4);
  EXPECT_EQ(plan.total_turn(30.0, 20.0), 0.0);
  EXPECT_EQ(PlanView().total_turn(0.0, 1.0), 0.0);
}

TEST(PlanView, LengthRecordAtAndClampedPoses) {
  const PlanView plan = line_then_arc();
  EXPECT_NEAR(plan.length(), 10.0 + 10.0 * kPi, 1e-12);
  EXPECT_EQ(plan.record_at(-3.0), 0u);
  EXPECT_EQ(plan.record_at(0.0), 0u);
  EXPECT_EQ(plan.record_at(9.999), 0u);
  EXPECT_EQ(plan.record_at(10.0), 1u);
  EXPECT_EQ(plan.record_at(1e6), 1u);

  EXPECT_NEAR(plan.at(5.0).position.x(), 5.0, 1e-12);
  const Pose2 end = plan.at(plan.length());
  EXPECT_NEAR(end.position.x(), 30.0, 1e-12);
  EXPECT_NEAR(end.position.y(), 20.0, 1e-12);
  EXPECT_NEAR(end.heading, 0.5 * kPi, 1e-12);
  const Pose2 beyond = plan.at(plan.length() + 50.0);
  EXPECT_NEAR(beyond.position.x(), 30.0, 1e-12);
  EXPECT_NEAR(beyond.position.y(), 20.0, 1e-12);
  const Pose2 before = plan.at(-50.0);
  EXPECT_NEAR(before.position.norm(), 0.0, 1e-15);
  EXPECT_EQ(PlanView().length(), 0.0);
}

TEST(PlanView, RecordAtOnManyRecordsIsBinarySearch) {
  std::vector<PlanGeometry> records;
  for (int i = 0; i < 1000; ++i) records.push_back(line_record(2.0 * i, {2.0 * i, 0.0}, 0.0, 2.0));
  const PlanView plan(records);
  EXPECT_EQ(plan.record_at(0.5), 0u);
  EXPECT_EQ(plan.record_at(1001.0), 500u);
  EXPECT_EQ(plan.record_at(1999.9), 999u);
  EXPECT_NEAR(plan.at(1234.5).position.x(), 1234.5, 1e-12);
}

TEST(PlanView, ConstructorRejectsBadRecords) {
  EXPECT_THROW(PlanView({line_record(0.0, Vec2::Zero(), 0.0, 0.0)}), InvalidInput);
  EXPECT_THROW(PlanView({line_record(0.0, Vec2::Zero(), 0.0, -1.0)}), InvalidInput);
  EXPECT_THROW(PlanView({line_record(0.0, Vec2::Zero(), 0.0, std::numeric_limits<double>::infinity())}),
               InvalidInput);
  EXPECT_THROW(PlanView({line_record(0.0, Vec2::Zero(), 0.0, std::nan(""))}), InvalidInput);
  EXPECT_THROW(PlanView({line_record(0.0, Vec2(std::nan(""), 0.0), 0.0, 1.0)}), InvalidInput);
  EXPECT_THROW(PlanView({line_record(5.0, Vec2::Zero(), 0.0, 1.0), line_record(1.0, Vec2::Zero(), 0.0, 1.0)}),
               InvalidInput);
  EXPECT_THROW(PlanView({line_record(0.0, Vec2::Zero(), 0.0, 1.0), line_record(0.0, Vec2::Zero(), 0.0, 1.0)}),
               InvalidInput);
  EXPECT_NO_THROW(
      PlanView({line_record(0.0, Vec2::Zero(), 0.0, 1.0), line_record(1.0, {1.0, 0.0}, 0.0, 1.0)}));
}

TEST(PlanView, EmptyPlanViewCannotBeEvaluated) {
  const PlanView empty;
  EXPECT_THROW((void)empty.at(0.0), InvalidInput);
  EXPECT_THROW((void)empty.record_at(0.0), InvalidInput);
}

}  // namespace
}  // namespace relief
