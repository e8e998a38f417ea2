#include "relief/geometry/plan_overlap.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <vector>

#include "relief/core/errors.h"
#include "support/mesh_grid.h"

namespace relief {
namespace {

using test::add_grid;

std::size_t flagged(const std::vector<std::uint8_t>& flags, std::size_t first, std::size_t last) {
  return static_cast<std::size_t>(std::count(flags.begin() + static_cast<std::ptrdiff_t>(first),
                                             flags.begin() + static_cast<std::ptrdiff_t>(last), 1));
}

TEST(PlanOverlap, NeighboursSharingEdgesAndVerticesDoNotOverlap) {
  TriangleMesh m;
  add_grid(m, -5, -5, 10, 10, 0.0);
  add_grid(m, 5, -5, 3, 3, 0.0);  // own vertices on the grid's edge x = 5: touching only
  const PlanOverlaps o = plan_overlaps(m);
  EXPECT_EQ(o.pairs, 0u);
  EXPECT_EQ(flagged(o.under, 0, m.triangles.size()), 0u);
}

// A road (strip along x at z = 0) running under a crossing street (strip along y at z = 5), as
// a tunnel approach under the street at its portal: the 2 x 2 squares under the street are
// flagged, the street none, and what is left overlaps nothing.
TEST(PlanOverlap, TheLowerOfTwoCrossingStripsIsFlaggedWhereTheyOverlap) {
  TriangleMesh m;
  add_grid(m, -5, -1, 10, 2, 0.0);
  const std::size_t road = m.triangles.size();  // 40
  add_grid(m, -1, -5, 2, 10, 5.0);
  const PlanOverlaps o = plan_overlaps(m);
  EXPECT_EQ(flagged(o.under, 0, road), 8u);
  EXPECT_EQ(flagged(o.under, road, m.triangles.size()), 0u);
  EXPECT_GE(o.pairs, 8u);
  ASSERT_EQ(o.lower_upper.size(), o.pairs);
  for (const auto& [lower, upper] : o.lower_upper) {
    EXPECT_LT(lower, road);  // the road under the street
    EXPECT_GE(upper, road);
  }
  ASSERT_FALSE(o.sites.empty());
  for (const Vec3& s : o.sites) {
    EXPECT_LT(std::abs(s.x()), 1.0);
    EXPECT_LT(std::abs(s.y()), 1.0);
    EXPECT_EQ(s.z(), 0.0);
  }
  std::vector<std::uint8_t> left(m.triangles.size());
  for (std::size_t i = 0; i < left.size(); ++i) left[i] = !o.under[i];
  EXPECT_EQ(plan_overlaps(m, left).pairs, 0u);

  // The street raised on a slope through the road's height: the road is flagged where it is
  // lower, the street where it is.
  TriangleMesh sloped = m;
  for (std::size_t v = (10 + 1) * (2 + 1); v < sloped.vertices.size(); ++v) {
    sloped.vertices[v].z() = sloped.vertices[v].y();  // street z = y, road z = 0
  }
  const PlanOverlaps s = plan_overlaps(sloped);
  EXPECT_EQ(flagged(s.under, 0, road), 4u);                        // under the street's y > 0 half
  EXPECT_EQ(flagged(s.under, road, sloped.triangles.size()), 4u);  // the street's y < 0 half
}

TEST(PlanOverlap, OnlyCandidatesTakePartAndTiesFlagTheLater) {
  TriangleMesh m;
  add_grid(m, 0, 0, 1, 1, 2.0);
  add_grid(m, 0, 0, 1, 1, 2.0);  // the same square again
  std::vector<std::uint8_t> candidates{1, 1, 0, 0};
  EXPECT_EQ(plan_overlaps(m, candidates).pairs, 0u);
  const PlanOverlaps o = plan_overlaps(m);
  EXPECT_EQ(o.pairs, 2u);  // each triangle overlaps its copy; the other half only touches it
  EXPECT_EQ(o.under, (std::vector<std::uint8_t>{0, 0, 1, 1}));
  EXPECT_THROW((void)plan_overlaps(m, {1, 1}), InvalidInput);
}

}  // namespace
}  // namespace relief
