#include "terrain/dem_ground_filter.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <vector>

namespace relief::terrain_detail {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// A cols x rows window whose cell (c, r) holds f(c, r).
std::vector<double> window(int cols, int rows, const std::function<double(int, int)>& f) {
  std::vector<double> z;
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) z.push_back(f(c, r));
  }
  return z;
}

// One pass written the slow way: each line's voids bridged by straight lines (an end run takes
// the nearest valid value), the line reflected through its ends, every extremum over its whole
// window.
std::vector<double> slow_line(const std::vector<double>& line, int r, bool take_min) {
  const int n = static_cast<int>(line.size());
  std::vector<int> valid;
  for (int i = 0; i < n; ++i) {
    if (!std::isnan(line[i])) valid.push_back(i);
  }
  if (valid.empty()) return line;
  std::vector<double> filled(line.size());
  for (int i = 0; i < n; ++i) {
    const auto after = std::lower_bound(valid.begin(), valid.end(), i);
    if (after == valid.end()) {
      filled[i] = line[valid.back()];
    } else if (*after == i || after == valid.begin()) {
      filled[i] = line[*after];
    } else {
      const int a = *(after - 1), b = *after;
      filled[i] = line[a] + (line[b] - line[a]) * (i - a) / (b - a);
    }
  }
  const auto at = [&](int i) {
    if (i < 0) return 2.0 * filled[0] - filled[std::min(-i, n - 1)];
    if (i >= n) return 2.0 * filled[n - 1] - filled[std::max(n - 1 - (i - n + 1), 0)];
    return filled[i];
  };
  std::vector<double> out(line.size());
  for (int i = 0; i < n; ++i) {
    double best = at(i - r);
    for (int j = i - r + 1; j <= i + r; ++j) best = take_min ? std::min(best, at(j)) : std::max(best, at(j));
    out[i] = best;
  }
  return out;
}

std::vector<double> slow_pass(std::vector<double> z, int cols, int rc, int rr, bool take_min) {
  const int rows = static_cast<int>(z.size()) / cols;
  for (int r = 0; r < rows; ++r) {
    std::vector<double> line(z.begin() + r * cols, z.begin() + (r + 1) * cols);
    line = slow_line(line, rc, take_min);
    std::copy(line.begin(), line.end(), z.begin() + r * cols);
  }
  for (int c = 0; c < cols; ++c) {
    std::vector<double> line;
    for (int r = 0; r < rows; ++r) line.push_back(z[static_cast<std::size_t>(r) * cols + c]);
    line = slow_line(line, rr, take_min);
    for (int r = 0; r < rows; ++r) z[static_cast<std::size_t>(r) * cols + c] = line[r];
  }
  return z;
}

std::vector<double> brute_force(std::vector<double> z, int cols, int rc, int rr, double min_height_m) {
  const auto pass = [&](const std::vector<double>& in, bool take_min) {
    return slow_pass(in, cols, rc, rr, take_min);
  };
  const std::vector<double> ground = pass(pass(pass(pass(z, true), false), false), true);
  for (std::size_t i = 0; i < z.size(); ++i) {
    if (!std::isnan(z[i]) && !std::isnan(ground[i]) && std::abs(z[i] - ground[i]) > min_height_m)
      z[i] = ground[i];
  }
  return z;
}

// A building (a block of 3 x 4 cells, 40 m high) and a pit (2 x 2 cells, 20 m deep). On flat
// ground both go back to it exactly and nothing else moves. On a slope a flat window cannot
// fit the ground beside them exactly (the grey opening's known limit, why such filters take a
// slope-dependent threshold): what is left is bounded by the slope over the object's width,
// and the ground farther than two windows from them is not touched.
TEST(DemGroundFilter, BuildingAndPitGoBackToTheGround) {
  for (const double slope : {0.0, 3.0}) {
    const auto plane = [&](int c, int r) { return 100.0 + slope * c - 0.5 * slope * r; };
    std::vector<double> z = window(40, 30, plane);
    for (int r = 6; r < 10; ++r) {
      for (int c = 12; c < 15; ++c) z[static_cast<std::size_t>(r) * 40 + c] += 40.0;
    }
    for (int r = 20; r < 22; ++r) {
      for (int c = 26; c < 28; ++c) z[static_cast<std::size_t>(r) * 40 + c] -= 20.0;
    }
    const GroundFiltered f = filter_off_ground(z, 40, 3, 3, 2.0);
    EXPECT_GE(f.lowered, 12u) << slope;
    EXPECT_GE(f.raised, 4u) << slope;
    EXPECT_GT(f.largest_m, 30.0) << slope;
    const auto near = [](int c, int r) {
      return (c >= 12 - 14 && c < 15 + 14 && r >= 6 - 14 && r < 10 + 14) ||
             (c >= 26 - 14 && c < 28 + 14 && r >= 20 - 14 && r < 22 + 14);
    };
    for (int r = 0; r < 30; ++r) {
      for (int c = 0; c < 40; ++c) {
        const double left = z[static_cast<std::size_t>(r) * 40 + c] - plane(c, r);
        if (slope == 0.0 || !near(c, r)) {
          EXPECT_EQ(left, 0.0) << slope << ": " << c << ", " << r;
        } else {
          // The building: 3 cells along the slope of `slope` per cell, 4 across it of slope / 2.
          EXPECT_LE(std::abs(left), 3.0 * slope + 4.0 * 0.5 * slope + 1e-9)
              << slope << ": " << c << ", " << r;
        }
      }
    }
  }
}

// The ground itself passes: planes of any slope (up to 70 degrees on 30 m cells), a mesa and a
// basin wider than the window, and a bump lower than min_height_m.
TEST(DemGroundFilter, PlanesWideFeaturesAndLowBumpsAreKept) {
  for (const double slope : {0.0, 0.1, 0.35, 1.0, 2.75}) {
    std::vector<double> z = window(25, 25, [&](int c, int r) { return 30.0 * slope * (0.8 * c + 0.6 * r); });
    const std::vector<double> before = z;
    const GroundFiltered f = filter_off_ground(z, 25, 2, 2, 2.0);
    EXPECT_EQ(f.lowered + f.raised, 0u) << slope;
    EXPECT_EQ(z, before) << slope;
  }
  // A mesa of 7 x 7 cells 30 m high and a basin as wide 30 m deep, the window 5 x 5 cells.
  std::vector<double> z = window(40, 20, [](int c, int r) {
    if (c >= 5 && c < 12 && r >= 5 && r < 12) return 130.0;
    if (c >= 25 && c < 32 && r >= 5 && r < 12) return 70.0;
    return 100.0;
  });
  z[15 * 40 + 35] += 1.9;  // one cell, lower than min_height_m
  const std::vector<double> before = z;
  const GroundFiltered f = filter_off_ground(z, 40, 2, 2, 2.0);
  EXPECT_EQ(f.lowered + f.raised, 0u);
  EXPECT_EQ(z, before);
  EXPECT_EQ(f.largest_col, -1);
}

// The window is rectangular: a wall 3 cells thick along the rows goes with a window 7 cells
// tall; with one 3 cells tall (radius 1 < the wall's half-thickness rounded up) it stays.
TEST(DemGroundFilter, EachAxisHasItsOwnRadius) {
  const auto wall = [](int, int r) { return r >= 8 && r < 11 ? 25.0 : 0.0; };
  std::vector<double> tall = window(20, 20, wall), short_window = tall;
  EXPECT_EQ(filter_off_ground(tall, 20, 1, 3, 2.0).lowered, 60u);
  EXPECT_EQ(filter_off_ground(short_window, 20, 3, 1, 2.0).lowered, 0u);
}

// Voids are left out of every minimum and maximum and stay voids; a window all void is left alone.
TEST(DemGroundFilter, VoidsStayVoidsAndAreLeftOut) {
  std::vector<double> z = window(12, 12, [](int c, int) { return 10.0 + c; });
  for (int r = 0; r < 12; ++r) z[static_cast<std::size_t>(r) * 12 + 6] = kNaN;  // a void column
  z[3 * 12 + 2] = 80.0;                                                         // a tower beside it
  const GroundFiltered f = filter_off_ground(z, 12, 2, 2, 2.0);
  EXPECT_EQ(f.lowered, 1u);
  EXPECT_EQ(z[3 * 12 + 2], 12.0);
  for (int r = 0; r < 12; ++r) EXPECT_TRUE(std::isnan(z[static_cast<std::size_t>(r) * 12 + 6]));
  std::vector<double> empty(9, kNaN);
  EXPECT_EQ(filter_off_ground(empty, 3, 1, 1, 2.0).lowered, 0u);
  EXPECT_TRUE(std::all_of(empty.begin(), empty.end(), [](double v) { return std::isnan(v); }));
}

// The running extrema against the definition, on random surfaces with random voids, radii 0 to 6
// (windows longer than the grid included).
TEST(DemGroundFilter, AgreesWithTheFilterWrittenTheSlowWay) {
  std::mt19937 random(17);
  std::uniform_real_distribution<double> height(-50.0, 150.0), unit(0.0, 1.0);
  for (int trial = 0; trial < 40; ++trial) {
    const int cols = 1 + static_cast<int>(unit(random) * 23), rows = 1 + static_cast<int>(unit(random) * 19);
    const int rc = trial % 7, rr = (trial / 7) % 7;
    std::vector<double> z =
        window(cols, rows, [&](int, int) { return unit(random) < 0.15 ? kNaN : height(random); });
    const std::vector<double> expected = brute_force(z, cols, rc, rr, 2.0);
    (void)filter_off_ground(z, cols, rc, rr, 2.0);
    for (std::size_t i = 0; i < z.size(); ++i) {
      if (std::isnan(expected[i])) {
        EXPECT_TRUE(std::isnan(z[i])) << trial << " " << i;
      } else {
        EXPECT_NEAR(z[i], expected[i], 1e-9) << trial << " " << i;
      }
    }
  }
}

}  // namespace
}  // namespace relief::terrain_detail
