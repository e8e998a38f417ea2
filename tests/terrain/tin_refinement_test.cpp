#include "terrain/tin_refinement.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <functional>
#include <vector>

namespace relief {
namespace {

using namespace terrain_detail;

// An n x n grid of 1 m samples from (0, 0), every sample valid with z_dem = z_target = f(x, y),
// the samples on the grid's edge flagged kBoundary, and a TIN of its four corners (inserted).
struct World {
  GridSamples grid;
  Tin tin;
};

World world(long n, const std::function<double(double, double)>& f) {
  World w;
  w.grid.nx = n;
  w.grid.ny = n;
  w.grid.step_m = 1.0;
  for (long j = 0; j < n; ++j) {
    for (long i = 0; i < n; ++i) {
      const double z = f(static_cast<double>(i), static_cast<double>(j));
      w.grid.z_dem.push_back(z);
      w.grid.z_target.push_back(z);
      const bool edge = i == 0 || j == 0 || i == n - 1 || j == n - 1;
      w.grid.flags.push_back(static_cast<std::uint8_t>(kValid | (edge ? kBoundary : 0)));
    }
  }
  for (const std::size_t k : {std::size_t{0}, static_cast<std::size_t>(n - 1),
                              static_cast<std::size_t>(n * (n - 1)), static_cast<std::size_t>(n * n - 1)}) {
    const VertexHandle v = w.tin.insert(w.grid.point(k));
    v->info().grid = static_cast<std::uint32_t>(k);
    w.grid.flags[k] |= kInserted;
  }
  return w;
}

// Largest |z_target - TIN| over the samples that may be vertices (valid, not paved, near or
// inserted), brute force.
double max_candidate_error(const World& w) {
  double worst = 0.0;
  for (std::size_t k = 0; k < w.grid.size(); ++k) {
    if (!w.grid.has(k, kValid) || w.grid.has(k, kPaved) || w.grid.has(k, kNear) || w.grid.has(k, kInserted))
      continue;
    const Vec2 p = w.grid.xy(k);
    Tin::Locate_type type{};
    int li = 0;
    FaceHandle f = w.tin.locate(w.grid.point(k), type, li);
    if (type == Tin::VERTEX) continue;
    if (w.tin.is_infinite(f)) f = f->neighbor(li);
    worst = std::max(worst, std::abs(w.grid.z_target[k] - interpolate(f, p.x(), p.y())));
  }
  return worst;
}

std::size_t count_inserted(const GridSamples& grid) {
  std::size_t n = 0;
  for (std::size_t k = 0; k < grid.size(); ++k) n += grid.has(k, kInserted) ? 1 : 0;
  return n;
}

TEST(TinRefinement, APlaneNeedsNoMoreThanItsCorners) {
  World w = world(11, [](double x, double y) { return 1.0 + 2.0 * x - 3.0 * y; });
  EXPECT_EQ(insert_greedy(w.tin, w.grid, 0.01), 0u);
  const RepairResult r = repair_and_measure(w.tin, w.grid, 0.01);
  EXPECT_EQ(r.inserted, 0u);
  EXPECT_NEAR(r.max_error_m, 0.0, 1e-9);
  EXPECT_NEAR(r.max_error_outside_band_m, 0.0, 1e-9);
  EXPECT_EQ(w.tin.number_of_vertices(), 4u);
}

// A 3 x 3 grid, flat at 0 but for its centre sample (1, 1), 1 m high: the only sample the
// greedy phase may insert (the others lie on the edge). The corners' TIN puts 0 there: error 1.
World spike() {
  return world(3, [](double x, double y) { return x == 1.0 && y == 1.0 ? 1.0 : 0.0; });
}
constexpr std::size_t kCentre = 4;

TEST(TinRefinement, GreedyInsertsASampleErringByMoreThanTheTolerance) {
  World w = spike();
  EXPECT_EQ(insert_greedy(w.tin, w.grid, 0.999), 1u);
  EXPECT_TRUE(w.grid.has(kCentre, kInserted));
  EXPECT_EQ(w.tin.number_of_vertices(), 5u);
  // Every remaining sample (the edge midpoints, at 0 between corners at 0) now fits exactly.
  const RepairResult r = repair_and_measure(w.tin, w.grid, 0.999);
  EXPECT_EQ(r.inserted, 0u);
  EXPECT_NEAR(r.max_error_m, 0.0, 1e-12);
}

TEST(TinRefinement, AnErrorEqualToTheToleranceIsWithinIt) {
  World w = spike();
  EXPECT_EQ(insert_greedy(w.tin, w.grid, 1.0), 0u);
  const RepairResult r = repair_and_measure(w.tin, w.grid, 1.0);
  EXPECT_EQ(r.inserted, 0u);
  EXPECT_NEAR(r.max_error_m, 1.0, 1e-12);
  EXPECT_NEAR(r.max_error_outside_band_m, 1.0, 1e-12);
  EXPECT_FALSE(w.grid.has(kCentre, kInserted));
}

TEST(TinRefinement, PavedAndNearSamplesAreNeverInserted) {
  for (const std::uint8_t flag : {std::uint8_t{kPaved}, std::uint8_t{kNear}}) {
    World w = spike();
    w.grid.flags[kCentre] |= flag;
    EXPECT_EQ(insert_greedy(w.tin, w.grid, 0.1), 0u) << int{flag};
    const RepairResult r = repair_and_measure(w.tin, w.grid, 0.1);
    EXPECT_EQ(r.inserted, 0u) << int{flag};
    EXPECT_FALSE(w.grid.has(kCentre, kInserted));
    // Neither counts against the tolerance; a near sample (outside the paved area) still
    // measures the DEM's error outside the band, a paved one does not.
    EXPECT_NEAR(r.max_error_m, 0.0, 1e-12) << int{flag};
    EXPECT_NEAR(r.max_error_outside_band_m, flag == kNear ? 1.0 : 0.0, 1e-12) << int{flag};
  }
}

TEST(TinRefinement, ErrorOutsideTheBandIsAgainstTheDemNotTheTarget) {
  // The centre's target is 1 m (on a batter), its DEM 3 m: 1 m error against the target, 3 m
  // against the DEM; within the band only the target counts.
  World w = spike();
  w.grid.z_dem[kCentre] = 3.0;
  const RepairResult r = repair_and_measure(w.tin, w.grid, 1.0);
  EXPECT_NEAR(r.max_error_m, 1.0, 1e-12);
  EXPECT_NEAR(r.max_error_outside_band_m, 3.0, 1e-12);
  w.grid.flags[kCentre] |= kBand;
  const RepairResult banded = repair_and_measure(w.tin, w.grid, 1.0);
  EXPECT_NEAR(banded.max_error_m, 1.0, 1e-12);
  EXPECT_NEAR(banded.max_error_outside_band_m, 0.0, 1e-12);
}

TEST(TinRefinement, RepairInsertsTheEdgeSamplesTheGreedyPhaseLeavesOut) {
  // The edge midpoint (1, 0) is 2 m high: the greedy phase does not look at edge samples, the
  // repair inserts it (and what its insertion disturbs) until all fit within 0.5 m.
  World w = world(3, [](double x, double y) { return x == 1.0 && y == 0.0 ? 2.0 : 0.0; });
  EXPECT_EQ(insert_greedy(w.tin, w.grid, 0.5), 0u);
  const RepairResult r = repair_and_measure(w.tin, w.grid, 0.5);
  EXPECT_GE(r.inserted, 1u);
  EXPECT_TRUE(w.grid.has(1, kInserted));
  EXPECT_LE(r.max_error_m, 0.5);
  EXPECT_EQ(count_inserted(w.grid), 4u + r.inserted);
  EXPECT_LE(max_candidate_error(w), 0.5);
}

TEST(TinRefinement, GreedyThenRepairFollowASmoothHillWithinTheTolerance) {
  // A Gaussian hill 10 m high (sigma 4 m) in a 31 x 31 grid, 0.1 m tolerance: after the greedy
  // phase every interior candidate fits; the repair fits the edge ones; both fewer vertices
  // than samples.
  World w = world(31, [](double x, double y) {
    return 10.0 * std::exp(-((x - 15.0) * (x - 15.0) + (y - 15.0) * (y - 15.0)) / 32.0);
  });
  const std::size_t greedy = insert_greedy(w.tin, w.grid, 0.1);
  EXPECT_GT(greedy, 0u);
  EXPECT_EQ(count_inserted(w.grid), 4u + greedy);
  EXPECT_EQ(w.tin.number_of_vertices(), 4u + greedy);
  double interior = 0.0;
  for (std::size_t k = 0; k < w.grid.size(); ++k) {
    if (w.grid.has(k, kBoundary) || w.grid.has(k, kInserted)) continue;
    const Vec2 p = w.grid.xy(k);
    Tin::Locate_type type{};
    int li = 0;
    const FaceHandle f = w.tin.locate(w.grid.point(k), type, li);
    if (type == Tin::VERTEX) continue;
    interior = std::max(interior, std::abs(w.grid.z_target[k] - interpolate(f, p.x(), p.y())));
  }
  EXPECT_LE(interior, 0.1 + 1e-9);
  const RepairResult r = repair_and_measure(w.tin, w.grid, 0.1);
  EXPECT_LE(r.max_error_m, 0.1 + 1e-9);
  EXPECT_LE(max_candidate_error(w), 0.1 + 1e-9);
  EXPECT_LT(count_inserted(w.grid), w.grid.size() / 2);
}

}  // namespace
}  // namespace relief
