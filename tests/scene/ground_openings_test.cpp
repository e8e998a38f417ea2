#include "scene/ground_openings.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "support/mesh_grid.h"

namespace relief {
namespace {

using test::add_grid;

// A road (strip along x at z = 0, x in [-5, 5]) under a street (strip along y, x in [-1, 1]) at
// `street_z`; the road's squares under the street leave the ground.
std::vector<std::pair<Vec3, Vec3>> tops_under_street(double street_z, std::size_t& road_triangles) {
  TriangleMesh m;
  add_grid(m, -5, -1, 10, 2, 0.0);
  road_triangles = m.triangles.size();
  add_grid(m, -1, -5, 2, 10, street_z);
  const PlanOverlaps overlaps = plan_overlaps(m);
  std::vector<std::uint8_t> ground(m.triangles.size()), tunnel(m.triangles.size(), 0);
  for (std::size_t i = 0; i < ground.size(); ++i) ground[i] = !overlaps.under[i];
  return opening_tops(m, ground, tunnel, overlaps);
}

TEST(GroundOpenings, ARoadUnderAStreetOpensToTheStreetsHeight) {
  std::size_t road = 0;
  const auto tops = tops_under_street(4.0, road);
  // The road's cut edges at x = -1 and x = 1, three vertices each, raised to the street (4 m).
  ASSERT_EQ(tops.size(), 6u);
  for (const auto& [at, top] : tops) {
    EXPECT_DOUBLE_EQ(std::abs(at.x()), 1.0);
    EXPECT_DOUBLE_EQ(at.z(), 0.0);
    EXPECT_DOUBLE_EQ(top.z(), 4.0);
    EXPECT_EQ(top.head<2>(), at.head<2>());
  }
  EXPECT_EQ(opening_top(tops, Vec3(1, 0, 0)).z(), 4.0);
  EXPECT_EQ(opening_top(tops, Vec3(3, 0, 0)).z(), 0.0);  // no opening there: unchanged
}

TEST(GroundOpenings, ASmallStepIsLeftToTheTerrainAsARamp) {
  std::size_t road = 0;
  EXPECT_TRUE(tops_under_street(1.5, road).empty());  // below the 2 m a vehicle needs
}

TEST(GroundOpenings, ATunnelMouthOpensByTheMouthHeight) {
  TriangleMesh m;
  add_grid(m, 0, 0, 4, 2, 10.0);  // the road on the ground, x in [0, 4]
  add_grid(m, 4, 0, 4, 2, 10.0);  // the tunnel, x in [4, 8], own vertices at the seam
  // Weld the seam (x = 4) as the road mesh does.
  for (auto& t : m.triangles) {
    for (auto& v : t) {
      for (std::uint32_t w = 0; w < 15; ++w) {
        if (v >= 15 && m.vertices[v] == m.vertices[w]) v = w;
      }
    }
  }
  std::vector<std::uint8_t> ground(m.triangles.size(), 0), tunnel(m.triangles.size(), 0);
  std::fill_n(ground.begin(), 16, 1);
  std::fill(tunnel.begin() + 16, tunnel.end(), 1);
  PlanOverlaps none;
  none.under.assign(m.triangles.size(), 0);
  const auto tops = opening_tops(m, ground, tunnel, none);
  ASSERT_EQ(tops.size(), 3u);  // the seam's three vertices
  for (const auto& [at, top] : tops) {
    EXPECT_DOUBLE_EQ(at.x(), 4.0);
    EXPECT_DOUBLE_EQ(top.z(), 15.0);
  }
}

}  // namespace
}  // namespace relief
