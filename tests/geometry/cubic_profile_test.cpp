#include "relief/geometry/cubic_profile.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>

#include "relief/core/errors.h"

namespace relief {
namespace {

double cubic(double s) {
  return 12.0 + 0.2 * s - 0.003 * s * s + 1e-5 * s * s * s;
}
double cubic_slope(double s) {
  return 0.2 - 0.006 * s + 3e-5 * s * s;
}

TEST(CubicProfile, EmptyIsZeroAndConstantIsConstant) {
  const CubicProfile empty;
  EXPECT_TRUE(empty.empty());
  EXPECT_EQ(empty.value(3.0), 0.0);
  EXPECT_EQ(empty.derivative(3.0), 0.0);
  const auto c = CubicProfile::constant(3.5);
  EXPECT_FALSE(c.empty());
  EXPECT_EQ(c.value(-100.0), 3.5);
  EXPECT_EQ(c.value(1e6), 3.5);
  EXPECT_EQ(c.derivative(42.0), 0.0);
}

TEST(CubicProfile, PiecesUseLocalDsAndExtendBeyondTheEnds) {
  // Piece 0 on [0, 10): 1 + 0.5 ds; piece 1 from 10: 6 + ds^2.
  const CubicProfile p({CubicPiece{0.0, {1.0, 0.5, 0.0, 0.0}}, CubicPiece{10.0, {6.0, 0.0, 1.0, 0.0}}});
  EXPECT_DOUBLE_EQ(p.value(4.0), 3.0);
  EXPECT_DOUBLE_EQ(p.value(-2.0), 0.0);   // first piece extended left
  EXPECT_DOUBLE_EQ(p.value(10.0), 6.0);   // a knot belongs to the next piece
  EXPECT_DOUBLE_EQ(p.value(13.0), 15.0);  // last piece extended right
  EXPECT_DOUBLE_EQ(p.derivative(4.0), 0.5);
  EXPECT_DOUBLE_EQ(p.derivative(13.0), 6.0);
}

TEST(CubicProfile, ConstructorRejectsUnsortedPieces) {
  EXPECT_THROW(CubicProfile({CubicPiece{5.0, {}}, CubicPiece{1.0, {}}}), InvalidInput);
  EXPECT_THROW(CubicProfile({CubicPiece{1.0, {}}, CubicPiece{1.0, {}}}), InvalidInput);
  EXPECT_THROW(CubicProfile({CubicPiece{std::nan(""), {}}}), InvalidInput);
}

TEST(CubicProfile, HermiteProfileMatchesEndConditions) {
  const auto p = hermite_profile(50.0, 10.0, 0.02, 11.0, -0.01);
  ASSERT_EQ(p.pieces().size(), 1u);
  EXPECT_NEAR(p.value(0.0), 10.0, 1e-12);
  EXPECT_NEAR(p.derivative(0.0), 0.02, 1e-12);
  EXPECT_NEAR(p.value(50.0), 11.0, 1e-12);
  EXPECT_NEAR(p.derivative(50.0), -0.01, 1e-12);
  // A cubic is its own Hermite interpolant.
  const auto q = hermite_profile(100.0, cubic(0.0), cubic_slope(0.0), cubic(100.0), cubic_slope(100.0));
  EXPECT_NEAR(q.value(37.0), cubic(37.0), 1e-10);
  EXPECT_THROW((void)hermite_profile(0.0, 0, 0, 0, 0), InvalidInput);
  EXPECT_THROW((void)hermite_profile(-1.0, 0, 0, 0, 0), InvalidInput);
}

TEST(CubicProfile, FitReproducesACubicWithOnePiece) {
  std::vector<double> s;
  std::vector<double> z;
  for (int i = 0; i <= 100; ++i) {
    s.push_back(i);
    z.push_back(cubic(i));
  }
  const auto p = fit_cubic_profile(s, z, 1e-6, std::pair{cubic_slope(0.0), cubic_slope(100.0)});
  ASSERT_EQ(p.pieces().size(), 1u);
  const Poly3& poly = p.pieces()[0].poly;
  EXPECT_NEAR(poly.a, 12.0, 1e-12);
  EXPECT_NEAR(poly.b, 0.2, 1e-12);
  EXPECT_NEAR(poly.c, -0.003, 1e-12);
  EXPECT_NEAR(poly.d, 1e-5, 1e-14);

  // Without end slopes the three-point slopes are off by O(h^2); still within a looser tolerance.
  const auto q = fit_cubic_profile(s, z, 2e-3);
  EXPECT_EQ(q.pieces().size(), 1u);
}

TEST(CubicProfile, QuadraticIsExactWithoutEndSlopes) {
  // Three-point slopes are exact for quadratics, also on non-uniform stations.
  std::vector<double> s{0.0, 0.7, 3.0, 3.2, 9.0, 15.5, 20.0};
  std::vector<double> z;
  for (double x : s) z.push_back(2.0 - 0.5 * x + 0.03 * x * x);
  const auto p = fit_cubic_profile(s, z, 1e-9);
  ASSERT_EQ(p.pieces().size(), 1u);
  EXPECT_NEAR(p.derivative(0.0), -0.5, 1e-12);
  EXPECT_NEAR(p.derivative(20.0), -0.5 + 0.06 * 20.0, 1e-12);
}

struct NoisyRoad {
  std::vector<double> s;
  std::vector<double> z;
};

// 10 km at 1 m: hills, short bumps and deterministic pseudo-random noise of +-0.1 m.
NoisyRoad noisy_road() {
  NoisyRoad road;
  std::uint64_t state = 12345;
  for (int i = 0; i <= 10000; ++i) {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    const double noise = (static_cast<double>(state >> 11) / 9007199254740992.0 - 0.5) * 0.2;
    const double x = i;
    road.s.push_back(x);
    road.z.push_back(300.0 + 20.0 * std::sin(x / 300.0) + 0.5 * std::sin(x / 17.0) + noise);
  }
  return road;
}

void expect_c1_at_knots(const CubicProfile& p) {
  const auto& pieces = p.pieces();
  for (std::size_t i = 1; i < pieces.size(); ++i) {
    const double h = pieces[i].s - pieces[i - 1].s;
    EXPECT_NEAR(pieces[i - 1].poly.value(h), pieces[i].poly.a, 1e-9) << i;
    EXPECT_NEAR(pieces[i - 1].poly.derivative(h), pieces[i].poly.b, 1e-9) << i;
  }
}

TEST(CubicProfile, NoisyTenKilometreProfileRespectsTolerance) {
  const NoisyRoad road = noisy_road();
  const double tolerance = 0.15;
  const auto start = std::chrono::steady_clock::now();
  const auto p = fit_cubic_profile(road.s, road.z, tolerance);
  const double elapsed_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_LT(elapsed_s, 0.5);  // milliseconds normally; generous for shared CI machines
  for (std::size_t i = 0; i < road.s.size(); ++i) {
    ASSERT_LE(std::abs(p.value(road.s[i]) - road.z[i]), tolerance + 1e-9) << road.s[i];
  }
  EXPECT_NEAR(p.value(0.0), road.z.front(), 1e-12);
  EXPECT_NEAR(p.value(10000.0), road.z.back(), 1e-9);
  EXPECT_GT(p.pieces().size(), 10u);
  EXPECT_LT(p.pieces().size(), 2000u);
  expect_c1_at_knots(p);
}

TEST(CubicProfile, TightToleranceStillFitsEverySample) {
  const NoisyRoad road = noisy_road();
  const auto p = fit_cubic_profile(road.s, road.z, 0.0);
  for (std::size_t i = 0; i < road.s.size(); i += 7) {
    ASSERT_NEAR(p.value(road.s[i]), road.z[i], 1e-9) << road.s[i];
  }
  expect_c1_at_knots(p);
}

TEST(CubicProfile, EndSlopesAreHonoured) {
  const NoisyRoad road = noisy_road();
  const std::vector<double> s(road.s.begin(), road.s.begin() + 501);
  const std::vector<double> z(road.z.begin(), road.z.begin() + 501);
  const auto p = fit_cubic_profile(s, z, 0.1, std::pair{0.05, -0.08});
  EXPECT_NEAR(p.derivative(0.0), 0.05, 1e-12);
  EXPECT_NEAR(p.derivative(500.0), -0.08, 1e-9);
  EXPECT_NEAR(p.value(500.0), z.back(), 1e-9);
  for (std::size_t i = 0; i < s.size(); ++i) EXPECT_LE(std::abs(p.value(s[i]) - z[i]), 0.1 + 1e-9);
  expect_c1_at_knots(p);
}

TEST(CubicProfile, OneAndTwoSamples) {
  const auto one = fit_cubic_profile({5.0}, {7.0}, 0.1);
  EXPECT_DOUBLE_EQ(one.value(0.0), 7.0);
  EXPECT_DOUBLE_EQ(one.value(5.0), 7.0);
  const auto two = fit_cubic_profile({0.0, 10.0}, {1.0, 3.0}, 0.1);
  ASSERT_EQ(two.pieces().size(), 1u);
  EXPECT_NEAR(two.value(5.0), 2.0, 1e-12);
  EXPECT_NEAR(two.derivative(5.0), 0.2, 1e-12);
}

TEST(CubicProfile, FitRejectsBadInput) {
  EXPECT_THROW((void)fit_cubic_profile({}, {}, 0.1), InvalidInput);
  EXPECT_THROW((void)fit_cubic_profile({0.0, 1.0}, {0.0}, 0.1), InvalidInput);
  EXPECT_THROW((void)fit_cubic_profile({0.0, 1.0, 1.0}, {0.0, 1.0, 2.0}, 0.1), InvalidInput);
  EXPECT_THROW((void)fit_cubic_profile({0.0, 2.0, 1.0}, {0.0, 1.0, 2.0}, 0.1), InvalidInput);
  EXPECT_THROW((void)fit_cubic_profile({0.0, 1.0}, {0.0, std::nan("")}, 0.1), InvalidInput);
  EXPECT_THROW((void)fit_cubic_profile({0.0, 1.0}, {0.0, 1.0}, -0.1), InvalidInput);
  EXPECT_THROW((void)fit_cubic_profile({0.0, 1.0}, {0.0, 1.0}, 0.1, std::pair{0.0, std::nan("")}),
               InvalidInput);
}

// Steepest slope and largest jump of value or slope across pieces, sampled every 1 mm.
struct ProfileShape {
  double steepest = 0.0, value_jump = 0.0, slope_jump = 0.0;
};
ProfileShape shape_of(const CubicProfile& p, double length) {
  ProfileShape out;
  for (int k = 0; k <= 1000 * static_cast<int>(std::ceil(length)); ++k) {
    const double s = std::min(length, 0.001 * k);
    out.steepest = std::max(out.steepest, std::abs(p.derivative(s)));
  }
  for (std::size_t k = 1; k < p.pieces().size(); ++k) {
    const CubicPiece& a = p.pieces()[k - 1];
    const CubicPiece& b = p.pieces()[k];
    out.value_jump = std::max(out.value_jump, std::abs(a.poly.value(b.s - a.s) - b.poly.value(0.0)));
    out.slope_jump =
        std::max(out.slope_jump, std::abs(a.poly.derivative(b.s - a.s) - b.poly.derivative(0.0)));
  }
  return out;
}

// The fitted profile of a hairpin's stretch between two tight arcs: 35 % for a metre or two
// between 20 % (the fit flattens the arcs for their inner lane). A cubic through these samples
// overshoots 35 % between them; the grade-bounded fit does not.
TEST(GradeBoundedProfile, ASteepStretchBetweenFlatterOnesKeepsItsGrade) {
  std::vector<double> s{0.0};
  std::vector<double> z{100.0};
  const double grades[] = {0.2, 0.2, 0.2, 0.35, 0.35, 0.2, 0.2, 0.35, 0.2, 0.2, 0.2};
  for (const double g : grades) {
    s.push_back(s.back() + 1.0);
    z.push_back(z.back() + g);
  }
  const double tolerance = 0.01;
  const CubicProfile cubic = fit_cubic_profile(s, z, tolerance, std::pair{0.2, 0.2});
  const CubicProfile bounded = fit_grade_bounded_profile(s, z, tolerance, std::pair{0.2, 0.2});
  double cubic_steepest = 0.0, bounded_steepest = 0.0;
  for (double x = 0.0; x <= s.back(); x += 1e-3) {
    cubic_steepest = std::max(cubic_steepest, std::abs(cubic.derivative(x)));
    bounded_steepest = std::max(bounded_steepest, std::abs(bounded.derivative(x)));
  }
  EXPECT_GT(cubic_steepest, 0.37);  // the overshoot this fit exists for
  EXPECT_LE(bounded_steepest, 0.35 + 1e-4);
  for (std::size_t i = 0; i < s.size(); ++i)
    EXPECT_LE(std::abs(bounded.value(s[i]) - z[i]), tolerance + 1e-12);
  EXPECT_NEAR(bounded.value(0.0), 100.0, 1e-12);
  EXPECT_NEAR(bounded.value(s.back()), z.back(), 1e-9);
  EXPECT_NEAR(bounded.derivative(0.0), 0.2, 1e-12);
  EXPECT_NEAR(bounded.derivative(s.back()), 0.2, 1e-9);
  expect_c1_at_knots(bounded);
}

// Generated profiles: uneven stations (0.1 to 3 m), grades and end slopes up to 60 %, noise.
TEST(GradeBoundedProfile, GeneratedProfilesKeepTheirGradesValuesEndsAndC1) {
  std::uint64_t state = 7;
  const auto uniform = [&](double lo, double hi) {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return lo + (hi - lo) * (static_cast<double>(state >> 11) / 9007199254740992.0);
  };
  for (int trial = 0; trial < 300; ++trial) {
    const int n = 2 + static_cast<int>(uniform(0.0, 60.0));
    std::vector<double> s{0.0}, z{uniform(-50.0, 900.0)};
    double steepest = 0.0;
    for (int i = 1; i < n; ++i) {
      const double h = uniform(0.1, 3.0), g = uniform(-0.6, 0.6);
      s.push_back(s.back() + h);
      z.push_back(z.back() + g * h);
      steepest = std::max(steepest, std::abs(g));
    }
    const double e0 = uniform(-0.6, 0.6), e1 = uniform(-0.6, 0.6);
    const double tolerance = trial % 3 == 0 ? 0.001 : 0.01;
    const CubicProfile p = fit_grade_bounded_profile(s, z, tolerance, std::pair{e0, e1});
    // An end interval's grade may rise by tolerance / (4 (h - ramp / 2)) <= tolerance / (3 h).
    const double ends = tolerance / (3.0 * std::min(s[1] - s[0], s[n - 1] - s[n - 2]));
    const double bound = std::max({steepest, std::abs(e0), std::abs(e1)}) + ends + 1e-4;
    for (const CubicPiece& piece : p.pieces()) {
      for (double x = piece.s; x <= s.back() && x < piece.s + 10.0; x += 1e-2) {
        ASSERT_LE(std::abs(p.derivative(x)), bound) << "trial " << trial << " at s = " << x;
      }
    }
    for (std::size_t i = 0; i < s.size(); ++i) {
      ASSERT_LE(std::abs(p.value(s[i]) - z[i]), tolerance + 1e-9) << "trial " << trial << ", sample " << i;
    }
    ASSERT_NEAR(p.value(0.0), z.front(), 1e-9);
    ASSERT_NEAR(p.value(s.back()), z.back(), 1e-9);
    ASSERT_NEAR(p.derivative(0.0), e0, 1e-9);
    ASSERT_NEAR(p.derivative(s.back()), e1, 1e-9);
    expect_c1_at_knots(p);
  }
}

TEST(GradeBoundedProfile, SmoothProfilesStayFewPiecesAndZeroToleranceIsTheCubicFit) {
  // A 10 km noisy road: no more pieces than twice the cubic fit's.
  const NoisyRoad road = noisy_road();
  const CubicProfile cubic = fit_cubic_profile(road.s, road.z, 0.15);
  const CubicProfile bounded = fit_grade_bounded_profile(road.s, road.z, 0.15);
  for (std::size_t i = 0; i < road.s.size(); ++i) {
    ASSERT_LE(std::abs(bounded.value(road.s[i]) - road.z[i]), 0.15 + 1e-9) << road.s[i];
  }
  EXPECT_LE(bounded.pieces().size(), 2 * cubic.pieces().size());
  // A quadratic needs one piece.
  std::vector<double> s{0.0, 0.7, 3.0, 3.2, 9.0, 15.5, 20.0}, z;
  for (double x : s) z.push_back(2.0 - 0.5 * x + 0.03 * x * x);
  EXPECT_EQ(fit_grade_bounded_profile(s, z, 1e-6, std::pair{-0.5, 0.7}).pieces().size(), 1u);
  // Tolerance 0: the cubic fit itself.
  const CubicProfile exact = fit_grade_bounded_profile(s, z, 0.0);
  const CubicProfile reference = fit_cubic_profile(s, z, 0.0);
  ASSERT_EQ(exact.pieces().size(), reference.pieces().size());
  EXPECT_EQ(exact.pieces()[0].poly.b, reference.pieces()[0].poly.b);
  EXPECT_THROW((void)fit_grade_bounded_profile({0.0, 1.0}, {0.0, std::nan("")}, 0.1), InvalidInput);
}

TEST(SlopeBoundedProfile, KeepsTheHermiteCubicWhereItStaysWithinTheBound) {
  const CubicProfile p = slope_bounded_profile(50.0, 10.0, 0.02, 11.0, -0.01, 0.02);
  ASSERT_EQ(p.pieces().size(), 1u);
  const CubicProfile h = hermite_profile(50.0, 10.0, 0.02, 11.0, -0.01);
  EXPECT_EQ(p.pieces()[0].poly.c, h.pieces()[0].poly.c);
  EXPECT_EQ(p.pieces()[0].poly.d, h.pieces()[0].poly.d);
}

TEST(SlopeBoundedProfile, AShortSteepConnectionLeavingDownhillAndArrivingUphillStaysWithinItsEnds) {
  // Liechtenstein's junction connector: 4.3 m, 1.11 m down, leaving at -35 %, arriving at +20.7 %:
  // the Hermite cubic reaches -43 %; bounded, the slope stays within 35 % (the steeper end), C1,
  // with both ends and the rise kept.
  const double L = 4.296, z0 = 858.18, z1 = 857.07, g0 = -0.35, g1 = 0.207;
  EXPECT_GT(shape_of(hermite_profile(L, z0, g0, z1, g1), L).steepest, 0.42);
  const CubicProfile p = slope_bounded_profile(L, z0, g0, z1, g1, 0.02);
  const ProfileShape s = shape_of(p, L);
  EXPECT_LE(s.steepest, 0.35 + 1e-9);
  EXPECT_LT(s.value_jump, 1e-12);
  EXPECT_LT(s.slope_jump, 1e-12);
  EXPECT_NEAR(p.value(0.0), z0, 1e-12);
  EXPECT_NEAR(p.value(L), z1, 1e-9);
  EXPECT_NEAR(p.derivative(0.0), g0, 1e-12);
  EXPECT_NEAR(p.derivative(L), g1, 1e-9);
}

TEST(SlopeBoundedProfile, TwoRampsWhereTheyFitAndNothingBetterWhereTheRiseItselfIsTooSteep) {
  // Level ends, 2 m up over 10 m: the Hermite cubic peaks at 30 %, beyond the bound (22 %) by
  // more than the allowance: three pieces, the straight grade at 22 %.
  const CubicProfile p = slope_bounded_profile(10.0, 0.0, 0.0, 2.0, 0.0, 0.02);
  EXPECT_EQ(p.pieces().size(), 3u);
  EXPECT_NEAR(shape_of(p, 10.0).steepest, 0.22, 1e-9);
  EXPECT_NEAR(p.value(10.0), 2.0, 1e-9);
  // A crest 10 m long, +20 % in and -20 % out, 0.95 m up: the Hermite cubic climbs at 21 %;
  // two parabolas meeting in the middle (at 19 %) stay within the 20 % of the ends.
  EXPECT_GT(shape_of(hermite_profile(10.0, 0.0, 0.2, 0.95, -0.2), 10.0).steepest, 0.21);
  const CubicProfile q = slope_bounded_profile(10.0, 0.0, 0.2, 0.95, -0.2, 0.0);
  EXPECT_EQ(q.pieces().size(), 2u);
  EXPECT_LE(shape_of(q, 10.0).steepest, 0.2 + 1e-9);
  EXPECT_NEAR(q.value(10.0), 0.95, 1e-9);
  EXPECT_NEAR(q.derivative(10.0), -0.2, 1e-9);
  // A Hermite overshoot within the allowance is kept (the smoothest curve).
  EXPECT_EQ(slope_bounded_profile(10.0, 0.0, 0.0, 1.0, 0.0, 0.05).pieces().size(), 1u);
  // Without an allowance the straight grade would have to be the mean grade itself, with ramps
  // of no length (kinks): the Hermite cubic stays.
  EXPECT_EQ(slope_bounded_profile(10.0, 0.0, 0.0, 2.0, 0.0, 0.0).pieces().size(), 1u);
  EXPECT_THROW((void)slope_bounded_profile(10.0, 0, 0, 1, 0, -0.1), InvalidInput);
}

}  // namespace
}  // namespace relief
