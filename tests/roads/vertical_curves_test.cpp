#include "relief/roads/vertical_curves.h"

#include <gtest/gtest.h>

#include <cmath>

#include "relief/core/errors.h"

namespace relief {
namespace {

// AASHTO Green Book (2018) Table 3-1 (stopping sight distance) and Tables 3-35 / 3-37 (design K,
// rounded up): 50 km/h: SSD 65 m, crest K 7, sag K 13; 100 km/h: 185 m, 52, 45.
TEST(VerticalCurves, MatchTheGreenBookDesignValues) {
  EXPECT_NEAR(stopping_sight_distance_m(50.0), 63.5, 1.0);    // the table rounds up to 65
  EXPECT_NEAR(stopping_sight_distance_m(100.0), 184.2, 1.0);  // 185
  const VerticalCurveBounds k50 = vertical_curve_bounds(50.0);
  EXPECT_EQ(std::ceil(k50.crest_k), 7.0);
  EXPECT_EQ(std::ceil(k50.sag_k), 12.0);  // the table's 13 is from the rounded-up 65 m
  const VerticalCurveBounds k100 = vertical_curve_bounds(100.0);
  EXPECT_EQ(std::ceil(k100.crest_k), 52.0);
  EXPECT_EQ(std::ceil(k100.sag_k), 45.0);
  // K is metres per percent of grade change: |z''| <= 1 / (100 K).
  EXPECT_NEAR(k100.crest_curvature_per_m(), 1.0 / (100.0 * k100.crest_k), 1e-15);
  EXPECT_NEAR(k100.crest_curvature_per_m(), 1.93e-4, 0.02e-4);
  EXPECT_GT(k50.crest_curvature_per_m(), k100.crest_curvature_per_m());  // slower: tighter curves
}

TEST(VerticalCurves, RefuseANonPositiveSpeed) {
  EXPECT_THROW((void)vertical_curve_bounds(0.0), InvalidInput);
  EXPECT_THROW((void)vertical_curve_bounds(-30.0), InvalidInput);
  EXPECT_THROW((void)vertical_curve_bounds(std::nan("")), InvalidInput);
}

}  // namespace
}  // namespace relief
