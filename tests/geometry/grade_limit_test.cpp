#include "relief/geometry/grade_limit.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <random>
#include <vector>

#include "relief/core/errors.h"

namespace relief {
namespace {

std::vector<double> stations(double length, double step) {
  std::vector<double> s;
  for (int i = 0; i * step <= length + 1e-9; ++i) s.push_back(i * step);
  return s;
}

template <class F>
std::vector<double> heights(const std::vector<double>& s, F f) {
  std::vector<double> z;
  z.reserve(s.size());
  for (const double x : s) z.push_back(f(x));
  return z;
}

double steepest_chord(const std::vector<double>& s, const std::vector<double>& z) {
  double g = 0.0;
  for (std::size_t i = 1; i < s.size(); ++i) g = std::max(g, std::abs(z[i] - z[i - 1]) / (s[i] - s[i - 1]));
  return g;
}

// Largest change of grade from one chord to the next.
double largest_kink(const std::vector<double>& s, const std::vector<double>& z) {
  double k = 0.0;
  for (std::size_t i = 2; i < s.size(); ++i) {
    const double a = (z[i - 1] - z[i - 2]) / (s[i - 1] - s[i - 2]), b = (z[i] - z[i - 1]) / (s[i] - s[i - 1]);
    k = std::max(k, std::abs(b - a));
  }
  return k;
}

TEST(GradeLimit, HeightsWithinTheLimitDoNotMove) {
  const std::vector<double> s = stations(50.0, 0.5);
  const std::vector<double> z =
      heights(s, [](double x) { return 100.0 + 0.1 * x + 0.5 * std::sin(x / 7.0); });  // at most 17 %
  EXPECT_EQ(grade_limited(s, z, 0.18, 5.0), z);
}

// A 2 m step at s = 50 under a 10 % limit: the nearest heights within it (least squares) are
// a ramp at the limit centred on the step, from s = 40 to 60 (1 m off at the step, corners of
// 10 % grade); the 5 m moving mean rounds its corners (5 mm of grade per 0.5 m at most) and
// leaves the heights exactly as they were from 10 m beyond the stations the ramp moved.
TEST(GradeLimit, AStepBecomesARoundedRampWithinTheLimit) {
  const std::vector<double> s = stations(100.0, 0.5);
  const std::vector<double> z = heights(s, [](double x) { return x < 50.0 ? 0.0 : 2.0; });
  const std::vector<double> out = grade_limited(s, z, 0.1, 5.0);
  const std::vector<double> sharp = grade_limited(s, z, 0.1, 0.0);
  EXPECT_LE(steepest_chord(s, out), 0.1 * (1.0 + 1e-9));
  EXPECT_LE(steepest_chord(s, sharp), 0.1 * (1.0 + 1e-9));
  EXPECT_NEAR(sharp[79], 0.0, 1e-9);               // s = 39.5
  EXPECT_NEAR(sharp[90], 0.525, 1e-9);             // s = 45, on the ramp
  EXPECT_NEAR(sharp[120], 2.0, 1e-9);              // s = 60
  EXPECT_GE(largest_kink(s, sharp), 0.05 - 1e-9);  // the ramp's corners, unrounded
  EXPECT_LE(largest_kink(s, out), 0.0051);
  double departure = 0.0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    departure = std::max(departure, std::abs(out[i] - z[i]));
    if (s[i] <= 29.5 || s[i] >= 70.0) {
      EXPECT_EQ(out[i], z[i]) << "s = " << s[i];
    }
  }
  EXPECT_NEAR(departure, 1.0, 0.03);
}

TEST(GradeLimit, EndsAsFarApartAsTheLimitAllowsGiveTheStraightRamp) {
  const std::vector<double> s = stations(20.0, 0.25);
  std::vector<double> z = heights(s, [](double x) { return 5.0 * std::cos(x); });
  z.front() = 0.0;
  z.back() = 3.0;  // 15 % over 20 m
  const std::vector<double> out = grade_limited(s, z, 0.15, 4.0);
  for (std::size_t i = 0; i < s.size(); ++i) EXPECT_NEAR(out[i], 0.15 * s[i], 1e-12) << "s = " << s[i];
}

TEST(GradeLimit, RefusesWhatCannotBeMet) {
  const std::vector<double> s{0.0, 1.0, 2.0};
  EXPECT_THROW((void)grade_limited(s, {0.0, 0.0, 1.0}, 0.4, 1.0), InvalidInput);  // ends 50 % apart
  EXPECT_THROW((void)grade_limited(s, {0.0, 0.0}, 0.4, 1.0), InvalidInput);
  EXPECT_THROW((void)grade_limited({0.0}, {0.0}, 0.4, 1.0), InvalidInput);
  EXPECT_THROW((void)grade_limited({0.0, 1.0, 1.0}, {0.0, 0.0, 0.0}, 0.4, 1.0), InvalidInput);
  EXPECT_THROW((void)grade_limited(s, {0.0, NAN, 0.0}, 0.4, 1.0), InvalidInput);
  EXPECT_THROW((void)grade_limited(s, {0.0, 0.0, 0.0}, -0.1, 1.0), InvalidInput);
  EXPECT_THROW((void)grade_limited(s, {0.0, 0.0, 0.0}, 0.1, INFINITY), InvalidInput);
  EXPECT_EQ(grade_limited(s, {0.0, 0.0, 0.0}, 0.0, 1.0), (std::vector<double>{0.0, 0.0, 0.0}));
}

// Random profiles, limits and stations: the limit holds at every chord, the ends stay, and
// profiles already within the limit come back as they were.
TEST(GradeLimit, RandomProfilesKeepTheLimit) {
  std::mt19937 rng(20261128);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int seed = 0; seed < 2000; ++seed) {
    const int n = 2 + static_cast<int>(unit(rng) * 200.0);
    const double limit = 0.01 + 0.5 * unit(rng);
    const double blend = seed % 7 == 0 ? 0.0 : 10.0 * unit(rng);
    const double roughness = 3.0 * unit(rng) * limit;
    std::vector<double> s{0.0}, z{100.0 * unit(rng)};
    for (int i = 1; i < n; ++i) {
      const double ds = 0.05 + 2.0 * unit(rng);
      s.push_back(s.back() + ds);
      z.push_back(z.back() + (2.0 * unit(rng) - 1.0) * roughness * ds);
    }
    const double span = s.back() - s.front(), rise = z.back() - z.front();
    z.back() = z.front() + std::clamp(rise, -0.999 * limit * span, 0.999 * limit * span);
    const std::vector<double> out = grade_limited(s, z, limit, blend);
    ASSERT_EQ(out.size(), z.size());
    EXPECT_EQ(out.front(), z.front());
    EXPECT_EQ(out.back(), z.back());
    for (std::size_t i = 1; i < s.size(); ++i)
      ASSERT_LE(std::abs(out[i] - out[i - 1]), limit * (s[i] - s[i - 1]) * (1.0 + 1e-9) + 1e-12)
          << "seed " << seed << " station " << i;
    for (const double v : out) ASSERT_TRUE(std::isfinite(v)) << "seed " << seed;
    if (steepest_chord(s, z) <= limit) {
      EXPECT_EQ(out, z) << "seed " << seed;
    }
  }
}

}  // namespace
}  // namespace relief
