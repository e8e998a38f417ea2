#include "terrain/dem_sanity.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <utility>
#include <vector>

namespace relief::terrain_detail {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// A cols x rows window whose cell (c, r) holds f(c, r).
std::vector<double> window(int cols, int rows, const std::function<double(int, int)>& f) {
  std::vector<double> z;
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) z.push_back(f(c, r));
  }
  return z;
}

double& cell(std::vector<double>& z, int cols, int c, int r) {
  return z[static_cast<std::size_t>(r) * cols + c];
}

std::size_t voids(const std::vector<double>& z) {
  return static_cast<std::size_t>(std::count_if(z.begin(), z.end(), [](double v) { return std::isnan(v); }));
}

// ---------------------------------------------------------------- implausible heights

TEST(DemSanity, HeightsOutsideTheRangeBecomeVoidsAndAreListed) {
  std::vector<double> z = window(4, 3, [](int c, int r) { return 100.0 + c + 10.0 * r; });
  cell(z, 4, 1, 0) = 1e30;
  cell(z, 4, 3, 0) = -32768.0;
  cell(z, 4, 0, 1) = kInf;
  cell(z, 4, 2, 1) = -kInf;
  cell(z, 4, 1, 2) = std::nan("");  // already a void: not counted again
  cell(z, 4, 2, 2) = 9000.0;        // the bounds themselves are plausible
  cell(z, 4, 3, 2) = -500.0;
  const VoidedCells out = void_implausible_heights(z, 4, -500.0, 9000.0, 3);
  EXPECT_EQ(out.count, 4U);
  ASSERT_EQ(out.first.size(), 3U);  // the first 3, row-major
  EXPECT_EQ(out.first[0].col, 1);
  EXPECT_EQ(out.first[0].row, 0);
  EXPECT_EQ(out.first[0].height_m, 1e30);
  EXPECT_TRUE(std::isnan(out.first[0].around_m));
  EXPECT_EQ(out.first[1].col, 3);
  EXPECT_EQ(out.first[1].height_m, -32768.0);
  EXPECT_EQ(out.first[2].col, 0);
  EXPECT_EQ(out.first[2].row, 1);
  EXPECT_EQ(voids(z), 5U);
  EXPECT_EQ(cell(z, 4, 2, 2), 9000.0);
  EXPECT_EQ(cell(z, 4, 3, 2), -500.0);
  EXPECT_EQ(cell(z, 4, 0, 0), 100.0);
}

// ---------------------------------------------------------------- spikes

// Default criteria (DemOptions' defaults).
const SpikeCriteria kDefault{};

TEST(DemSanity, OneCellPeakAndPitOnAPlaneAreSpikes) {
  const auto plane = [](int c, int r) { return 200.0 + 0.5 * c - 0.3 * r; };
  std::vector<double> z = window(12, 10, plane);
  cell(z, 12, 3, 4) += 100.0;  // peak
  cell(z, 12, 8, 6) -= 45.0;   // pit, just over the 30 m step of 10 m cells
  const std::vector<double> cell_m(10, 10.0);
  const VoidedCells out = void_spikes(z, 12, cell_m, kDefault, 5);
  ASSERT_EQ(out.count, 2U);
  EXPECT_EQ(out.first[0].col, 3);
  EXPECT_EQ(out.first[0].row, 4);
  EXPECT_NEAR(out.first[0].height_m, plane(3, 4) + 100.0, 1e-12);
  EXPECT_NEAR(out.first[0].around_m, plane(3, 4), 1e-12);  // a plane's neighbours: median = centre
  EXPECT_EQ(out.first[1].col, 8);
  EXPECT_EQ(out.first[1].row, 6);
  EXPECT_TRUE(std::isnan(cell(z, 12, 3, 4)));
  EXPECT_TRUE(std::isnan(cell(z, 12, 8, 6)));
  EXPECT_EQ(voids(z), 2U);  // their neighbours (which saw a disagreeing neighbour) stay
}

TEST(DemSanity, StepThresholdIsTheLargerOfTheMinimumAndTheCellMultiple) {
  // Flat ground, a 40 m peak: a spike on 10 m cells (step 30 m), not on 30 m cells (45 m).
  for (const auto& [size_m, expected] : {std::pair{10.0, 1U}, std::pair{30.0, 0U}, std::pair{26.0, 1U}}) {
    std::vector<double> z = window(5, 5, [](int, int) { return 50.0; });
    cell(z, 5, 2, 2) = 90.0;
    EXPECT_EQ(void_spikes(z, 5, std::vector<double>(5, size_m), kDefault, 1).count, expected) << size_m;
  }
  // The size is per row: the same peak in a row of 30 m cells is none.
  std::vector<double> z = window(5, 6, [](int, int) { return 50.0; });
  cell(z, 5, 2, 1) = 90.0;
  cell(z, 5, 2, 4) = 90.0;
  const std::vector<double> rows{10.0, 10.0, 10.0, 30.0, 30.0, 30.0};
  const VoidedCells out = void_spikes(z, 5, rows, kDefault, 5);
  ASSERT_EQ(out.count, 1U);
  EXPECT_EQ(out.first[0].row, 1);
}

TEST(DemSanity, NeighboursThatDisagreeMakeNoSpike) {
  // A 100 m peak whose neighbours spread 40 m (> 100 / 3): rough ground, kept.
  std::vector<double> z = window(3, 3, [](int c, int) { return 10.0 + 20.0 * c; });
  cell(z, 3, 1, 1) = 130.0;  // median of the neighbours 30 m, d = 100
  EXPECT_EQ(void_spikes(z, 3, std::vector<double>(3, 10.0), kDefault, 1).count, 0U);
  // The same with neighbours within 30 m of each other (< 100 / 3 = 33.3): a spike.
  z = window(3, 3, [](int c, int) { return 15.0 + 15.0 * c; });
  cell(z, 3, 1, 1) = 130.0;
  EXPECT_EQ(void_spikes(z, 3, std::vector<double>(3, 10.0), kDefault, 1).count, 1U);
}

TEST(DemSanity, PlanesOfAnySlopeCliffsRidgesAndValleysAreNoSpikes) {
  const std::vector<double> cell_m(9, 90.0);
  const auto none = [&](const std::function<double(int, int)>& f, const char* what) {
    std::vector<double> z = window(9, 9, f);
    EXPECT_EQ(void_spikes(z, 9, cell_m, kDefault, 1).count, 0U) << what;
    EXPECT_EQ(voids(z), 0U) << what;
  };
  // 90 m cells: 45 degrees is 90 m from cell to cell, 72 degrees 270 m.
  none([](int c, int) { return 90.0 * c; }, "45 degree plane");
  none([](int c, int r) { return 1000.0 + 270.0 * c - 270.0 * r; }, "72 degree diagonal plane");
  none([](int c, int) { return c < 4 ? 0.0 : 500.0; }, "500 m cliff");
  none([](int c, int) { return 3000.0 - 270.0 * std::abs(c - 4); }, "knife ridge, 72 degree flanks");
  none([](int, int r) { return 270.0 * std::abs(r - 4); }, "V valley, 72 degree sides");
  none([](int c, int r) { return 3000.0 - 90.0 * std::hypot(c - 4, r - 4); }, "45 degree cone");
  // A pinnacle two cells wide: each cell has the other as a neighbour far from the median.
  std::vector<double> z = window(9, 9, [](int, int) { return 0.0; });
  cell(z, 9, 4, 4) = cell(z, 9, 5, 4) = 1000.0;
  EXPECT_EQ(void_spikes(z, 9, cell_m, kDefault, 1).count, 0U);
}

TEST(DemSanity, VoidsAndBordersLeaveFewerNeighbours) {
  // A corner cell has 3 neighbours: enough. With two of them voids it has 1: not judged.
  std::vector<double> z = window(4, 4, [](int, int) { return 0.0; });
  cell(z, 4, 0, 0) = 100.0;
  EXPECT_EQ(void_spikes(z, 4, std::vector<double>(4, 10.0), kDefault, 1).count, 1U);
  z = window(4, 4, [](int, int) { return 0.0; });
  cell(z, 4, 0, 0) = 100.0;
  cell(z, 4, 1, 0) = std::nan("");
  cell(z, 4, 0, 1) = std::nan("");
  EXPECT_EQ(void_spikes(z, 4, std::vector<double>(4, 10.0), kDefault, 1).count, 0U);
  // An even number of neighbours: the median is the mean of the middle two.
  z = window(3, 3, [](int c, int) { return c == 2 ? 9.0 : 0.0; });
  cell(z, 3, 1, 1) = 100.0;  // neighbours 0,0,0,0,0,9,9,9 -> median 0; spread 9 < 100 / 3
  cell(z, 3, 0, 0) = std::nan("");
  cell(z, 3, 0, 1) = std::nan("");  // now 0,0,0,9,9,9 -> median 4.5
  const VoidedCells out = void_spikes(z, 3, std::vector<double>(3, 10.0), kDefault, 1);
  ASSERT_EQ(out.count, 1U);
  EXPECT_EQ(out.first[0].around_m, 4.5);
}

TEST(DemSanity, InfiniteMinimumStepTurnsTheCheckOffAndKeepLimitsTheList) {
  std::vector<double> z = window(9, 9, [](int, int) { return 0.0; });
  for (int k : {1, 4, 7}) cell(z, 9, k, k) = 500.0;
  SpikeCriteria off;
  off.min_step_m = kInf;
  EXPECT_EQ(void_spikes(z, 9, std::vector<double>(9, 10.0), off, 5).count, 0U);
  const VoidedCells out = void_spikes(z, 9, std::vector<double>(9, 10.0), kDefault, 2);
  EXPECT_EQ(out.count, 3U);
  EXPECT_EQ(out.first.size(), 2U);
  EXPECT_EQ(voids(z), 3U);
}

}  // namespace
}  // namespace relief::terrain_detail
