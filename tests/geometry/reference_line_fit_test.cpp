#include "relief/geometry/reference_line_fit.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "relief/core/errors.h"
#include "relief/geometry/plan_view.h"

namespace relief {
namespace {

constexpr double kPi = std::numbers::pi;

double angle_gap(double a, double b) {
  return std::abs(std::remainder(a - b, 2.0 * kPi));
}

double distance_to_polyline(const Polyline2& line, const Vec2& q) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i + 1 < line.size(); ++i) {
    const Vec2 d = line[i + 1] - line[i];
    const double len2 = d.squaredNorm();
    const double t = len2 > 0.0 ? std::clamp((q - line[i]).dot(d) / len2, 0.0, 1.0) : 0.0;
    best = std::min(best, (line[i] + t * d - q).norm());
  }
  return best;
}

// Every property the fit promises: within tolerance, G1, no NaN, no short or curvature-0
// records, ends on the polyline's ends with its end headings.
void expect_valid_fit(const Polyline2& polyline, const PlanView& plan, const ReferenceLineOptions& options) {
  const auto& records = plan.records();
  ASSERT_FALSE(records.empty());
  for (std::size_t i = 0; i < records.size(); ++i) {
    const PlanGeometry& g = records[i];
    ASSERT_TRUE(std::isfinite(g.length) && g.start.allFinite() && std::isfinite(g.heading)) << i;
    if (g.kind == PlanGeometry::Kind::arc) {
      EXPECT_NE(g.curvature, 0.0) << i;
      EXPECT_TRUE(std::isfinite(g.curvature)) << i;
    } else {
      EXPECT_EQ(g.kind, PlanGeometry::Kind::line) << i;
      // Shorter only on a polyline segment that is itself shorter than min_length.
      double shortest = std::numeric_limits<double>::infinity();
      for (std::size_t k = 0; k + 1 < polyline.size(); ++k) {
        const double len = (polyline[k + 1] - polyline[k]).norm();
        if (len > 1e-3) shortest = std::min(shortest, len);
      }
      EXPECT_GE(g.length, std::min(options.min_length_m, shortest)) << i;
    }
    if (i == 0) {
      EXPECT_EQ(g.s, 0.0);
      continue;
    }
    const PlanGeometry& prev = records[i - 1];
    const Pose2 end = evaluate(prev, prev.length);
    EXPECT_LT((end.position - g.start).norm(), 1e-9) << i;
    EXPECT_LT(angle_gap(end.heading, g.heading), 1e-9) << i;
    EXPECT_NEAR(g.s, prev.s + prev.length, 1e-9) << i;
  }
  double worst = 0.0;
  const double length = plan.length();
  const auto steps = static_cast<int>(std::ceil(length / 0.1));
  for (int k = 0; k <= steps; ++k) {
    const double s = std::min(length, 0.1 * k);
    worst = std::max(worst, distance_to_polyline(polyline, plan.at(s).position));
  }
  EXPECT_LE(worst, options.tolerance_m + 1e-9);

  const Pose2 start = plan.at(0.0);
  const Pose2 end = plan.at(length);
  EXPECT_LT((start.position - polyline.front()).norm(), 1e-9);
  EXPECT_LT((end.position - polyline.back()).norm(), 1e-9);
  const Vec2 d0 = polyline[1] - polyline[0];
  const Vec2 d1 = polyline.back() - polyline[polyline.size() - 2];
  EXPECT_LT(angle_gap(start.heading, std::atan2(d0.y(), d0.x())), 1e-9);
  EXPECT_LT(angle_gap(end.heading, std::atan2(d1.y(), d1.x())), 1e-9);
}

TEST(ReferenceLineFit, StraightPolylineGivesOneLine) {
  const Polyline2 line{{0, 0}, {10, 5}, {10, 5}, {20, 10}, {40, 20}};
  std::vector<double> stations;
  const ReferenceLineOptions options;
  const PlanView plan = fit_reference_line(line, options, &stations);
  ASSERT_EQ(plan.records().size(), 1u);
  EXPECT_EQ(plan.records()[0].kind, PlanGeometry::Kind::line);
  EXPECT_NEAR(plan.length(), std::hypot(40.0, 20.0), 1e-12);
  expect_valid_fit(line, plan, options);
  ASSERT_EQ(stations.size(), line.size());
  const double unit = std::hypot(10.0, 5.0);
  EXPECT_NEAR(stations[0], 0.0, 1e-12);
  EXPECT_NEAR(stations[1], unit, 1e-9);
  EXPECT_NEAR(stations[2], unit, 1e-9);
  EXPECT_NEAR(stations[3], 2.0 * unit, 1e-9);
  EXPECT_NEAR(stations[4], plan.length(), 1e-12);
}

TEST(ReferenceLineFit, TwoPointsGiveOneLine) {
  const Polyline2 line{{3, 4}, {3, -6}};
  const PlanView plan = fit_reference_line(line, {});
  ASSERT_EQ(plan.records().size(), 1u);
  EXPECT_NEAR(plan.length(), 10.0, 1e-12);
  EXPECT_NEAR(plan.records()[0].heading, -0.5 * kPi, 1e-15);
  expect_valid_fit(line, plan, {});
}

TEST(ReferenceLineFit, RightAngleCornerIsRoundedWithinTolerance) {
  const Polyline2 line{{0, 0}, {100, 0}, {100, 100}};
  const ReferenceLineOptions options{0.05, 1e-3};
  std::vector<double> stations;
  const PlanView plan = fit_reference_line(line, options, &stations);
  ASSERT_EQ(plan.records().size(), 3u);
  const PlanGeometry& a = plan.records()[1];
  ASSERT_EQ(a.kind, PlanGeometry::Kind::arc);
  // R_tol = tol / (1/cos(45°) - 1) is far below R_fit = 50 m.
  const double r = 0.05 / (std::sqrt(2.0) - 1.0);
  EXPECT_NEAR(1.0 / a.curvature, r, 1e-12);
  EXPECT_NEAR(a.length, 0.5 * kPi * r, 1e-12);
  EXPECT_NEAR(plan.records()[0].length, 100.0 - r, 1e-12);
  EXPECT_NEAR(plan.length(), 200.0 - 2.0 * r + 0.5 * kPi * r, 1e-12);
  expect_valid_fit(line, plan, options);
  // The arc's midpoint is exactly `tolerance` from the vertex.
  EXPECT_NEAR((plan.at(stations[1]).position - line[1]).norm(), 0.05, 1e-9);
  EXPECT_NEAR(stations[1], a.s + 0.5 * a.length, 1e-12);
  EXPECT_NEAR(stations[2], plan.length(), 1e-12);
}

// Every arc of a fit made with a minimum radius, G1 and with the polyline's end positions.
void expect_no_arc_below(const Polyline2& polyline, const PlanView& plan, double min_radius_m) {
  const auto& records = plan.records();
  for (std::size_t i = 0; i < records.size(); ++i) {
    if (records[i].kind == PlanGeometry::Kind::arc) {
      EXPECT_GE(1.0 / std::abs(records[i].curvature), min_radius_m - 1e-9) << i;
    }
    if (i == 0) continue;
    const Pose2 end = evaluate(records[i - 1], records[i - 1].length);
    EXPECT_LT((end.position - records[i].start).norm(), 1e-9) << i;
    EXPECT_LT(angle_gap(end.heading, records[i].heading), 1e-9) << i;
  }
  EXPECT_LT((plan.at(0.0).position - polyline.front()).norm(), 1e-9);
  EXPECT_LT((plan.at(plan.length()).position - polyline.back()).norm(), 1e-9);
}

TEST(ReferenceLineFit, SharpCornerGetsTheMinimumRadius) {
  // Tolerance alone gives R = 0.05 / (sqrt 2 - 1) = 0.12 m; the minimum radius wins, and the
  // arc's midpoint lies R (sqrt 2 - 1) from the vertex.
  const Polyline2 line{{0, 0}, {100, 0}, {100, 100}};
  ReferenceLineOptions options;
  options.min_radius_m = 4.0;
  ReferenceLineReport report;
  const PlanView plan = fit_reference_line(line, options, nullptr, &report);
  ASSERT_EQ(plan.records().size(), 3u);
  EXPECT_NEAR(1.0 / plan.records()[1].curvature, 4.0, 1e-12);
  EXPECT_EQ(report.corners_widened, 1u);
  EXPECT_EQ(report.vertices_merged, 0u);
  EXPECT_NEAR(report.max_departure_m, 4.0 * (std::sqrt(2.0) - 1.0), 1e-3);
  expect_no_arc_below(line, plan, 4.0);
}

TEST(ReferenceLineFit, ChamferedRightAngleIsMergedIntoOneWideArc) {
  // A 90-degree corner drawn as two 45-degree corners 0.71 m apart: arcs of radius 4 m need
  // 1.66 m of each segment, so the two corners merge where the outer segments meet (20.5, 0).
  const Polyline2 line{{0, 0}, {20, 0}, {20.5, 0.5}, {20.5, 20}};
  ReferenceLineOptions options;
  options.min_radius_m = 4.0;
  ReferenceLineReport report;
  std::vector<double> stations;
  const PlanView plan = fit_reference_line(line, options, &stations, &report);
  ASSERT_EQ(plan.records().size(), 3u);
  EXPECT_EQ(plan.records()[1].kind, PlanGeometry::Kind::arc);
  EXPECT_NEAR(1.0 / plan.records()[1].curvature, 4.0, 1e-9);
  EXPECT_NEAR(plan.records()[0].length, 16.5, 1e-9);
  EXPECT_EQ(report.vertices_merged, 1u);
  EXPECT_GT(report.max_departure_m, options.tolerance_m);
  expect_no_arc_below(line, plan, 4.0);
  // Stations stay in order along the line.
  ASSERT_EQ(stations.size(), 4u);
  for (std::size_t i = 1; i < stations.size(); ++i) EXPECT_LE(stations[i - 1], stations[i]);
  EXPECT_NEAR(stations.back(), plan.length(), 1e-12);
}

TEST(ReferenceLineFit, CornerNextToAnEndIsDroppedRatherThanTightened) {
  // A right angle 1 m from the start: an arc of radius 4 m does not fit on the first segment.
  const Polyline2 line{{0, 0}, {1, 0}, {1, 10}};
  ReferenceLineOptions options;
  options.min_radius_m = 4.0;
  ReferenceLineReport report;
  const PlanView plan = fit_reference_line(line, options, nullptr, &report);
  ASSERT_EQ(plan.records().size(), 1u);
  EXPECT_EQ(plan.records()[0].kind, PlanGeometry::Kind::line);
  EXPECT_EQ(report.vertices_merged, 1u);
  EXPECT_NEAR(report.max_departure_m, 10.0 / std::sqrt(101.0), 1e-6);  // (1, 0) from the chord
  expect_no_arc_below(line, plan, 4.0);
}

TEST(ReferenceLineFit, RandomSharpCornersKeepRadiusEndsAndOrder) {
  // Generated: corners of 100 to 180 degrees either way, legs from 0.3 to 30 x the minimum
  // radius, one to three corners in a row. Every fit is G1, no arc is tighter than the minimum
  // radius, both ends stay, stations stay in order; where no vertex had to be merged, each
  // corner costs no more length than its arc of the minimum radius cuts and the reference line
  // stays within that arc's distance from every vertex.
  std::mt19937 rng(20261129u);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int unmerged = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    SCOPED_TRACE("trial " + std::to_string(trial));
    const double radius = 2.0 + 6.0 * u(rng);
    Polyline2 line{{0.0, 0.0}};
    double heading = 0.0, polyline_length = 0.0, cut = 0.0, worst_arc = 0.0;
    const int corners = 1 + static_cast<int>(3.0 * u(rng));
    for (int c = 0; c <= corners; ++c) {
      const double leg = radius * (0.3 + 29.7 * u(rng));
      line.push_back(line.back() + leg * Vec2(std::cos(heading), std::sin(heading)));
      polyline_length += leg;
      const double turn = (100.0 + 80.0 * u(rng)) * kPi / 180.0;
      heading += u(rng) < 0.5 ? turn : -turn;
      if (c < corners) {  // what an arc of the minimum radius cuts and how far it passes
        cut += radius * (2.0 * std::tan(0.5 * turn) - turn);
        worst_arc = std::max(worst_arc, radius * (1.0 / std::cos(0.5 * turn) - 1.0));
      }
    }
    ReferenceLineOptions options;
    options.min_radius_m = radius;
    ReferenceLineReport report;
    std::vector<double> stations;
    const PlanView plan = fit_reference_line(line, options, &stations, &report);
    expect_no_arc_below(line, plan, radius);
    for (std::size_t i = 1; i < stations.size(); ++i) EXPECT_LE(stations[i - 1], stations[i] + 1e-9);
    EXPECT_TRUE(std::isfinite(report.max_departure_m));
    if (report.vertices_merged == 0) {
      ++unmerged;
      EXPECT_GE(plan.length(), polyline_length - cut - 1e-6);
      EXPECT_LE(report.max_departure_m, worst_arc + 1e-3);
    }
    if (::testing::Test::HasFailure()) break;
  }
  EXPECT_GT(unmerged, 1000);  // measured 1090 of 2000
}

TEST(ReferenceLineFit, MinimumRadiusKeepsAZigZagValid) {
  const Polyline2 line{{0, 0}, {5, 0}, {5.3, 2}, {9, 2.5}, {9.2, -1}, {15, -1}, {15, 6}, {22, 6}};
  ReferenceLineOptions options;
  options.min_radius_m = 3.5;
  ReferenceLineReport report;
  const PlanView plan = fit_reference_line(line, options, nullptr, &report);
  expect_no_arc_below(line, plan, 3.5);
  EXPECT_GT(report.vertices_merged, 0u);
  EXPECT_TRUE(std::isfinite(report.max_departure_m));
}

TEST(ReferenceLineFit, RightTurnHasNegativeCurvature) {
  const Polyline2 line{{0, 0}, {10, 0}, {20, -10}};
  const PlanView plan = fit_reference_line(line, {});
  ASSERT_EQ(plan.records().size(), 3u);
  EXPECT_LT(plan.records()[1].curvature, 0.0);
  expect_valid_fit(line, plan, {});
}

TEST(ReferenceLineFit, ShortSegmentsLimitTheRadius) {
  // A gentle bend on 2 m segments: R_fit = 1 m / tan(θ/2) is below R_tol, and the line between
  // two such arcs vanishes.
  const double theta = 0.2;
  const Polyline2 line{
      {0, 0},
      {2, 0},
      {2 + 2 * std::cos(theta), 2 * std::sin(theta)},
      {2 + 2 * std::cos(theta) + 2 * std::cos(2 * theta), 2 * std::sin(theta) + 2 * std::sin(2 * theta)}};
  const ReferenceLineOptions options{0.5, 1e-3};
  const PlanView plan = fit_reference_line(line, options);
  const auto& r = plan.records();
  ASSERT_EQ(r.size(), 4u);  // line, arc, arc, line
  EXPECT_EQ(r[1].kind, PlanGeometry::Kind::arc);
  EXPECT_EQ(r[2].kind, PlanGeometry::Kind::arc);
  EXPECT_NEAR(1.0 / r[1].curvature, 1.0 / std::tan(0.5 * theta), 1e-9);
  EXPECT_NEAR(r[0].length, 1.0, 1e-12);
  expect_valid_fit(line, plan, options);
}

TEST(ReferenceLineFit, CircleGivesArcsOfTheCircleRadius) {
  Polyline2 line;
  const double radius = 50.0;
  for (int i = 0; i <= 72; ++i) {
    const double a = 2.0 * kPi * i / 72.0;
    line.emplace_back(radius * std::cos(a), radius * std::sin(a));
  }
  // Segments of 4.36 m turning 5°: with 5 cm the half-segment limit R_fit = 49.94 m binds and
  // the lines between arcs vanish; with 1 cm R_tol = 10.5 m binds and lines remain between arcs.
  const double half = 0.5 * 2.0 * kPi / 72.0;
  const double r_fit = radius * std::sin(half) / std::tan(half);
  for (const double tolerance : {0.05, 0.01}) {
    const ReferenceLineOptions options{tolerance, 1e-3};
    const double r_tol = tolerance / (1.0 / std::cos(half) - 1.0);
    const PlanView plan = fit_reference_line(line, options);
    int arcs = 0;
    int lines = 0;
    for (const auto& g : plan.records()) {
      if (g.kind == PlanGeometry::Kind::arc) {
        ++arcs;
        EXPECT_NEAR(1.0 / g.curvature, std::min(r_fit, r_tol), 1e-9);
      } else {
        ++lines;
      }
    }
    EXPECT_EQ(arcs, 71);
    EXPECT_EQ(lines, tolerance == 0.05 ? 2 : 72);
    expect_valid_fit(line, plan, options);
    EXPECT_NEAR(plan.length(), 2.0 * kPi * radius, 0.01 * 2.0 * kPi * radius);
  }
  EXPECT_NEAR(r_fit, radius, 0.002 * radius);
}

TEST(ReferenceLineFit, ShortLinesShrinkTheirArcs) {
  // 72-gon with a tolerance whose arcs would leave 2 cm lines: with min_length 5 cm the arcs
  // shrink so that every line is at least 5 cm (a shrink also lengthens the next line, so some
  // end up a little longer), and still lie within the tolerance.
  Polyline2 line;
  const double radius = 50.0;
  for (int i = 0; i <= 72; ++i) {
    const double a = 2.0 * kPi * i / 72.0;
    line.emplace_back(radius * std::cos(a), radius * std::sin(a));
  }
  const double half = kPi / 72.0;
  const double half_segment = radius * std::sin(half);
  const double r_tol = (half_segment - 0.01) / std::tan(half);
  const ReferenceLineOptions options{r_tol * (1.0 / std::cos(half) - 1.0), 0.05};
  const PlanView plan = fit_reference_line(line, options);
  const auto& records = plan.records();
  ASSERT_EQ(records.size(), 71u + 72u);
  for (std::size_t i = 2; i + 2 < records.size(); i += 2) {
    ASSERT_EQ(records[i].kind, PlanGeometry::Kind::line) << i;
    EXPECT_GE(records[i].length, 0.05 - 1e-12) << i;
    EXPECT_LE(records[i].length, 0.07) << i;
    EXPECT_LT(1.0 / records[i + 1].curvature, r_tol) << i;
  }
  expect_valid_fit(line, plan, options);
}

TEST(ReferenceLineFit, HairpinAndUTurnStayFinite) {
  const Polyline2 hairpin{{0, 0}, {100, 0}, {0, 0.5}};
  const Polyline2 u_turn{{0, 0}, {100, 0}, {50, 0}};
  const Polyline2 u_turn_right{{0, 0}, {0, -100}, {0, -50}, {20, -50}};
  for (const auto& line : {hairpin, u_turn, u_turn_right}) {
    std::vector<double> stations;
    const PlanView plan = fit_reference_line(line, {}, &stations);
    expect_valid_fit(line, plan, {});
    for (double s : stations) EXPECT_TRUE(std::isfinite(s));
  }
}

TEST(ReferenceLineFit, ZigZagWithMixedSegmentsIsValid) {
  // Deterministic pseudo-random walk: segment lengths 0.002..30 m, turns up to ±170°.
  Polyline2 line{{0, 0}};
  std::uint64_t state = 99;
  const auto next = [&] {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<double>(state >> 11) / 9007199254740992.0;
  };
  double heading = 0.0;
  for (int i = 0; i < 300; ++i) {
    heading += (next() - 0.5) * 2.0 * (170.0 / 180.0) * kPi * (i % 3 == 0 ? 1.0 : 0.2);
    const double len = i % 17 == 0 ? 0.002 + 0.01 * next() : 0.5 + 30.0 * next();
    line.push_back(line.back() + len * Vec2(std::cos(heading), std::sin(heading)));
  }
  for (const double min_length : {1e-3, 0.05}) {
    const ReferenceLineOptions options{0.05, min_length};
    std::vector<double> stations;
    const PlanView plan = fit_reference_line(line, options, &stations);
    expect_valid_fit(line, plan, options);
    ASSERT_EQ(stations.size(), line.size());
    for (std::size_t i = 1; i < stations.size(); ++i) EXPECT_GE(stations[i], stations[i - 1]) << i;
    // Each station is the reference point nearest to its vertex: within the tolerance.
    for (std::size_t i = 0; i < line.size(); ++i) {
      EXPECT_LE((plan.at(stations[i]).position - line[i]).norm(), 0.05 + 1e-9) << i;
    }
  }
}

TEST(ReferenceLineFit, NearDuplicateVerticesMapToTheSameStation) {
  const Polyline2 line{{0, 0}, {0.0004, 0}, {50, 0}, {50, 0.0002}, {50, 50}, {50, 50.0005}};
  std::vector<double> stations;
  const PlanView plan = fit_reference_line(line, {}, &stations);
  expect_valid_fit(line, plan, {});
  ASSERT_EQ(stations.size(), 6u);
  EXPECT_EQ(stations[0], 0.0);
  EXPECT_EQ(stations[1], 0.0);
  EXPECT_EQ(stations[2], stations[3]);
  EXPECT_EQ(stations[4], plan.length());
  EXPECT_EQ(stations[5], plan.length());
}

TEST(ReferenceLineFit, RejectsDegenerateInput) {
  EXPECT_THROW((void)fit_reference_line({}, {}), InvalidInput);
  EXPECT_THROW((void)fit_reference_line({{1, 1}}, {}), InvalidInput);
  EXPECT_THROW((void)fit_reference_line({{1, 1}, {1, 1.0005}}, {}), InvalidInput);
  EXPECT_THROW((void)fit_reference_line({{0, 0}, {std::nan(""), 1}}, {}), InvalidInput);
  EXPECT_THROW((void)fit_reference_line({{0, 0}, {1, 1}}, {0.0, 1e-3}), InvalidInput);
  EXPECT_THROW((void)fit_reference_line({{0, 0}, {1, 1}}, {0.05, -1.0}), InvalidInput);
  EXPECT_THROW((void)fit_reference_line({{0, 0}, {1, 1}}, {0.05, 1e-3, -1.0}), InvalidInput);
}

TEST(HermiteConnector, ReproducesBothPoses) {
  const Pose2 from{{10.0, -3.0}, 0.4, 0.0};
  const std::vector<Pose2> targets{{{40.0, 20.0}, 1.9, 0.0},
                                   {{12.0, 30.0}, -2.5, 0.0},
                                   {{-5.0, -10.0}, 3.0, 0.0},
                                   {{30.0, 5.0}, 0.4 + kPi, 0.0},
                                   {{25.0, 3.0}, 0.4, 0.0}};
  for (const Pose2& to : targets) {
    for (const double scale : {0.3, 0.5, 1.0}) {
      const PlanGeometry g = hermite_connector(from, to, scale);
      ASSERT_EQ(g.kind, PlanGeometry::Kind::param_poly3);
      EXPECT_NEAR(g.length, param_poly3_length(g.u, g.v, 1.0), 1e-12);
      EXPECT_GE(g.length, (to.position - from.position).norm() - 1e-9);
      const Pose2 a = evaluate(g, 0.0);
      const Pose2 b = evaluate(g, g.length);
      EXPECT_LT((a.position - from.position).norm(), 1e-9);
      EXPECT_LT(angle_gap(a.heading, from.heading), 1e-9);
      EXPECT_LT((b.position - to.position).norm(), 1e-9);
      EXPECT_LT(angle_gap(b.heading, to.heading), 1e-9);
    }
  }
}

TEST(HermiteConnector, ArcTangentScaleFollowsTheCircle) {
  EXPECT_NEAR(arc_tangent_scale(0.0), 1.0, 1e-12);
  EXPECT_NEAR(arc_tangent_scale(kPi / 2.0), 2.0 * std::tan(kPi / 8.0) / std::sin(kPi / 4.0), 1e-12);
  EXPECT_NEAR(arc_tangent_scale(-kPi / 2.0), arc_tangent_scale(kPi / 2.0), 1e-12);
  EXPECT_NEAR(arc_tangent_scale(kPi), arc_tangent_scale(0.9 * kPi), 1e-12);
  // A right turn through 90 degrees on a circle of radius 10 m: with the arc scale the curve
  // stays within 0.03 m of the circle and its radius within 3 % of 10 m; the old default 0.5
  // pinches it to a radius under 5 m, which folds a lane wider than that on the inside.
  const Pose2 from{{0.0, 10.0}, 0.0, 0.0};
  const Pose2 to{{10.0, 0.0}, -kPi / 2.0, 0.0};
  const auto extremes = [&](double scale) {
    const PlanGeometry g = hermite_connector(from, to, scale);
    double min_radius = 1e9, max_off = 0.0;
    for (int i = 0; i <= 200; ++i) {
      const Pose2 p = evaluate(g, g.length * i / 200.0);
      max_off = std::max(max_off, std::abs(p.position.norm() - 10.0));
      min_radius = std::min(min_radius, 1.0 / std::abs(p.curvature));
    }
    return std::pair{min_radius, max_off};
  };
  const auto [arc_radius, arc_off] = extremes(arc_tangent_scale(kPi / 2.0));
  EXPECT_GT(arc_radius, 9.7);
  EXPECT_LT(arc_off, 0.03);
  EXPECT_LT(extremes(0.5).first, 5.0);
}

TEST(CornerConnector, LineThenTheRoundestArc) {
  // Heading east from the origin, arriving heading south at (10, -4): the headings' lines meet
  // at (10, 0), 10 m ahead and 4 m behind, so a 6 m line and a quarter circle of radius 4 m.
  const Pose2 from{{0.0, 0.0}, 0.0, 0.0};
  const Pose2 to{{10.0, -4.0}, -kPi / 2.0, 0.0};
  const std::vector<PlanGeometry> records = corner_connector(from, to);
  ASSERT_EQ(records.size(), 2u);
  EXPECT_EQ(records[0].kind, PlanGeometry::Kind::line);
  EXPECT_NEAR(records[0].length, 6.0, 1e-12);
  EXPECT_EQ(records[1].kind, PlanGeometry::Kind::arc);
  EXPECT_NEAR(records[1].curvature, -0.25, 1e-12);
  EXPECT_NEAR(records[1].s, 6.0, 1e-12);
  const PlanView plan(records);
  EXPECT_NEAR(plan.length(), 6.0 + 2.0 * kPi, 1e-9);
  const Pose2 end = plan.at(plan.length());
  EXPECT_LT((end.position - to.position).norm(), 1e-9);
  EXPECT_LT(angle_gap(end.heading, to.heading), 1e-9);
  // Mirrored (the near end first): arc, then line.
  const std::vector<PlanGeometry> back =
      corner_connector({{10.0, 4.0}, -kPi / 2.0, 0.0}, {{0.0, 0.0}, kPi, 0.0});
  ASSERT_EQ(back.size(), 2u);
  EXPECT_EQ(back[0].kind, PlanGeometry::Kind::arc);
  EXPECT_NEAR(back[0].curvature, -0.25, 1e-12);
  EXPECT_NEAR(back[1].length, 6.0, 1e-12);
}

TEST(CornerConnector, SBendsAndStraightsFallBackToHermite) {
  // The headings' lines meet behind `from`: no corner to round.
  const std::vector<PlanGeometry> s_bend = corner_connector({{0.0, 0.0}, 0.0, 0.0}, {{10.0, 5.0}, 0.3, 0.0});
  ASSERT_EQ(s_bend.size(), 1u);
  EXPECT_EQ(s_bend[0].kind, PlanGeometry::Kind::param_poly3);
  const std::vector<PlanGeometry> straight =
      corner_connector({{0.0, 0.0}, 0.0, 0.0}, {{10.0, 0.0}, 0.0, 0.0});
  ASSERT_EQ(straight.size(), 1u);
  EXPECT_EQ(straight[0].kind, PlanGeometry::Kind::line);
  EXPECT_THROW((void)corner_connector({{0.0, 0.0}, 0.0, 0.0}, {{0.0, 0.0}, 1.0, 0.0}), InvalidInput);
}

TEST(HermiteConnector, StraightAheadGivesALine) {
  const Pose2 from{{1.0, 1.0}, kPi / 4.0, 0.0};
  const Pose2 to{{11.0, 11.0}, kPi / 4.0, 0.0};
  const PlanGeometry g = hermite_connector(from, to);
  ASSERT_EQ(g.kind, PlanGeometry::Kind::line);
  EXPECT_NEAR(g.length, 10.0 * std::sqrt(2.0), 1e-12);
  EXPECT_LT((evaluate(g, g.length).position - to.position).norm(), 1e-9);
  // Straight behind is not straight ahead.
  const PlanGeometry back = hermite_connector(to, {{-9.0, -9.0}, kPi / 4.0, 0.0});
  EXPECT_EQ(back.kind, PlanGeometry::Kind::param_poly3);
}

TEST(HermiteConnector, RejectsCoincidentPosesAndBadScale) {
  const Pose2 p{{1.0, 2.0}, 0.0, 0.0};
  EXPECT_THROW((void)hermite_connector(p, p), InvalidInput);
  EXPECT_THROW((void)hermite_connector(p, {{5.0, 2.0}, 0.0, 0.0}, 0.0), InvalidInput);
  EXPECT_THROW((void)hermite_connector(p, {{5.0, 2.0}, 0.0, 0.0}, -1.0), InvalidInput);
  EXPECT_THROW((void)hermite_connector(p, {{5.0, std::nan("")}, 0.0, 0.0}), InvalidInput);
}

}  // namespace
}  // namespace relief
