#include "relief/geometry/mesh_quality.h"

#include <gtest/gtest.h>

#include <array>
#include <chrono>
#include <cmath>
#include <ctime>
#include <functional>
#include <iostream>
#include <numbers>
#include <random>

#include "relief/core/errors.h"

namespace relief {
namespace {

// nx x ny cells of `cell` metres from `origin`, two counter-clockwise triangles per cell
// ((i,j), (i+1,j), (i+1,j+1)) and ((i,j), (i+1,j+1), (i,j+1)); z from `height`.
TriangleMesh grid(std::uint32_t nx, std::uint32_t ny, double cell = 1.0, const Vec3& origin = Vec3::Zero(),
                  const std::function<double(double, double)>& height = nullptr) {
  TriangleMesh m;
  m.name = "grid";
  for (std::uint32_t j = 0; j <= ny; ++j) {
    for (std::uint32_t i = 0; i <= nx; ++i) {
      const double x = origin.x() + cell * i, y = origin.y() + cell * j;
      m.vertices.emplace_back(x, y, origin.z() + (height ? height(x, y) : 0.0));
    }
  }
  const auto v = [nx](std::uint32_t i, std::uint32_t j) { return j * (nx + 1) + i; };
  for (std::uint32_t j = 0; j < ny; ++j) {
    for (std::uint32_t i = 0; i < nx; ++i) {
      m.triangles.push_back({v(i, j), v(i + 1, j), v(i + 1, j + 1)});
      m.triangles.push_back({v(i, j), v(i + 1, j + 1), v(i, j + 1)});
    }
  }
  return m;
}

TriangleMesh soup(const std::vector<Vec3>& vertices,
                  const std::vector<std::array<std::uint32_t, 3>>& triangles) {
  TriangleMesh m;
  m.vertices = vertices;
  m.triangles = triangles;
  return m;
}

TEST(MeshQuality, FlatTwoByTwoGrid) {
  const MeshQuality q = analyse_mesh(grid(2, 2));
  EXPECT_EQ(q.name, "grid");
  EXPECT_EQ(q.vertices, 9u);
  EXPECT_EQ(q.triangles, 8u);
  EXPECT_EQ(q.unused_vertices, 0u);
  EXPECT_EQ(q.components, 1u);
  EXPECT_EQ(q.boundary_edges, 8u);
  EXPECT_EQ(q.boundary_loops, 1u);
  EXPECT_EQ(q.holes, 0u);
  EXPECT_EQ(q.non_manifold_edges, 0u);
  EXPECT_EQ(q.non_manifold_vertices, 0u);
  EXPECT_EQ(q.inconsistent_orientation_edges, 0u);
  EXPECT_EQ(q.upside_down_triangles, 0u);
  EXPECT_TRUE(q.self_intersections_checked);
  EXPECT_EQ(q.self_intersecting_pairs, 0u);
  EXPECT_EQ(q.degenerate_triangles, 0u);
  EXPECT_EQ(q.sliver_triangles, 0u);
  EXPECT_NEAR(q.min_angle_deg, 45.0, 1e-12);
  EXPECT_NEAR(q.max_aspect_ratio, 2.0, 1e-12);  // hypotenuse^2 / (2 area) = 2 / 1
  EXPECT_NEAR(q.area_m2, 4.0, 1e-12);
  EXPECT_EQ(q.bounds.min, Vec2(0, 0));
  EXPECT_EQ(q.bounds.max, Vec2(2, 2));
  EXPECT_EQ(q.min_z, 0.0);
  EXPECT_EQ(q.max_z, 0.0);
}

TEST(MeshQuality, GridWithoutItsCentreCellHasOneHole) {
  TriangleMesh m = grid(3, 3);
  m.triangles.erase(m.triangles.begin() + 8, m.triangles.begin() + 10);  // cell (1, 1)
  m.vertices.emplace_back(9, 9, 9);                                      // and one stray vertex
  const MeshQuality q = analyse_mesh(m);
  EXPECT_EQ(q.triangles, 16u);
  EXPECT_EQ(q.unused_vertices, 1u);
  EXPECT_EQ(q.components, 1u);
  EXPECT_EQ(q.boundary_edges, 16u);
  EXPECT_EQ(q.boundary_loops, 2u);
  EXPECT_EQ(q.holes, 1u);
  ASSERT_EQ(q.hole_sites.size(), 1u);  // the cell's centre, its loop 4 m long
  EXPECT_LT((q.hole_sites[0] - Vec3(1.5, 1.5, 0.0)).norm(), 1e-12);
  EXPECT_NEAR(q.hole_lengths_m[0], 4.0, 1e-12);
  EXPECT_EQ(q.non_manifold_vertices, 0u);
  EXPECT_EQ(q.bounds.max, Vec2(3, 3));  // the stray vertex is not part of the mesh
  EXPECT_EQ(q.max_z, 0.0);
}

TEST(MeshQuality, IntersectionsAcrossTwoSetsLeavePairsWithinEachOut) {
  // T0 lies in z = 0; T1 (plane x = 0.5) and T2 (plane y = 0.25) both pierce it, not each other.
  TriangleMesh m;
  m.vertices = {{0, 0, 0},     {2, 0, 0},       {0, 2, 0},      {0.5, 0.5, -1}, {0.5, 0.5, 1},
                {0.5, 1.0, 0}, {0.2, 0.25, -1}, {0.2, 0.25, 1}, {1.0, 0.25, 0}};
  m.triangles = {{0, 1, 2}, {3, 4, 5}, {6, 7, 8}};
  EXPECT_EQ(analyse_mesh(m).self_intersecting_pairs, 2u);
  MeshQualityOptions across;
  across.intersections_across = {1, 1, 0};  // T0 and T1 one set, T2 the other
  const MeshQuality q = analyse_mesh(m, across);
  EXPECT_EQ(q.self_intersecting_pairs, 1u);
  ASSERT_EQ(q.self_intersection_sites.size(), 1u);
  EXPECT_NEAR(q.self_intersection_sites[0].y(), (2.0 / 3.0 + 0.25) / 2.0, 1e-12);  // T0 and T2
  ASSERT_EQ(q.self_intersection_triangles.size(), 1u);  // the pair's triangles, to name owners
  EXPECT_EQ(q.self_intersection_triangles[0], (std::array<std::size_t, 2>{0, 2}));
  const MeshQuality all = analyse_mesh(m);
  ASSERT_EQ(all.self_intersection_triangles.size(), 2u);
  for (const auto& [s, t] : all.self_intersection_triangles) {
    EXPECT_EQ(s, 0u);
    EXPECT_TRUE(t == 1u || t == 2u);
  }
  across.intersections_across = {1, 0};
  EXPECT_THROW((void)analyse_mesh(m, across), InvalidInput);
}

TEST(MeshQuality, ThreeTrianglesOnOneEdge) {
  // p-q carries a flat triangle on each side and a vertical one.
  const MeshQuality q = analyse_mesh(soup({{0, 0, 0}, {1, 0, 0}, {0.5, 1, 0}, {0.5, -1, 0}, {0.5, 0, 1}},
                                          {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}}));
  EXPECT_EQ(q.non_manifold_edges, 1u);
  EXPECT_EQ(q.non_manifold_vertices, 2u);  // p and q: three fans each
  EXPECT_EQ(q.components, 1u);
  EXPECT_EQ(q.boundary_edges, 6u);
  EXPECT_EQ(q.inconsistent_orientation_edges, 0u);
  EXPECT_EQ(q.self_intersecting_pairs, 0u);
}

TEST(MeshQuality, TwoFansTouchingAtOneVertex) {
  const MeshQuality q = analyse_mesh(
      soup({{0, 0, 0}, {-1, -1, 0}, {-1.5, 0, 0}, {-1, 1, 0}, {1, -1, 0}, {1.5, 0, 0}, {1, 1, 0}},
           {{0, 3, 2}, {0, 2, 1}, {0, 4, 5}, {0, 5, 6}}));
  EXPECT_EQ(q.non_manifold_vertices, 1u);
  EXPECT_EQ(q.non_manifold_edges, 0u);
  EXPECT_EQ(q.components, 2u);
  EXPECT_EQ(q.boundary_loops, 2u);  // split at the shared vertex
  EXPECT_EQ(q.holes, 0u);
  EXPECT_EQ(q.self_intersecting_pairs, 0u);
}

TEST(MeshQuality, OneFlippedTriangle) {
  TriangleMesh m = grid(2, 2);
  std::swap(m.triangles[0][1], m.triangles[0][2]);  // its two interior edges now disagree
  const MeshQuality q = analyse_mesh(m);
  EXPECT_EQ(q.inconsistent_orientation_edges, 2u);
  EXPECT_EQ(q.upside_down_triangles, 1u);
  EXPECT_EQ(q.non_manifold_edges, 0u);
  EXPECT_EQ(q.self_intersecting_pairs, 0u);
  EXPECT_EQ(q.boundary_loops, 1u);
}

TEST(MeshQuality, CrossingTrianglesIntersect) {
  const MeshQuality q = analyse_mesh(soup(
      {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0.5, 0.5, -1}, {0.5, 0.5, 1}, {3, 3, 0}}, {{0, 1, 2}, {3, 5, 4}}));
  EXPECT_EQ(q.components, 2u);
  EXPECT_EQ(q.self_intersecting_pairs, 1u);
  // Located (CGAL PMP's path: the mesh is manifold) at the midpoint of the two centroids.
  ASSERT_EQ(q.self_intersection_sites.size(), 1u);
  EXPECT_LT((q.self_intersection_sites[0] - Vec3(1.0, 1.0, 0.0)).norm(), 1e-12);
}

TEST(MeshQuality, TrianglesSharingAnEdgeAtAnAngleDoNotIntersect) {
  const MeshQuality q =
      analyse_mesh(soup({{0, 0, 0}, {1, 0, 0}, {0.5, 1, 0}, {0.5, -1, 0.5}}, {{0, 1, 2}, {1, 0, 3}}));
  EXPECT_EQ(q.components, 1u);
  EXPECT_EQ(q.self_intersecting_pairs, 0u);
}

TEST(MeshQuality, TrianglesTouchingAtAVertex) {
  const std::vector<Vec3> v{{0, 0, 0},    {2, 0, 0},  {0, 2, 0}, {-1, 0, 0.5},
                            {0, -1, 0.5}, {1, 1, -1}, {1, 1, 1}};
  const MeshQuality apart = analyse_mesh(soup(v, {{0, 1, 2}, {0, 3, 4}}));
  EXPECT_EQ(apart.non_manifold_vertices, 1u);
  EXPECT_EQ(apart.self_intersecting_pairs, 0u);
  // A vertical triangle from the shared vertex that pierces the flat one.
  const MeshQuality through = analyse_mesh(soup(v, {{0, 1, 2}, {0, 5, 6}}));
  EXPECT_EQ(through.self_intersecting_pairs, 1u);
  // Located by the soup test (a non-manifold vertex): centroids (2/3, 2/3, 0) and (2/3, 2/3, 0).
  ASSERT_EQ(through.self_intersection_sites.size(), 1u);
  EXPECT_LT((through.self_intersection_sites[0] - Vec3(2.0 / 3.0, 2.0 / 3.0, 0.0)).norm(), 1e-12);
}

TEST(MeshQuality, CoplanarTrianglesTouchingAtAVertex) {
  const std::vector<Vec3> v{{0, 0, 0},  {2, 0, 0},   {0, 2, 0},   {-1, 0, 0},  {0, -1, 0},
                            {1, -1, 0}, {1, 0.5, 0}, {0.5, 1, 0}, {-1, -1, 0}, {1, 0, 0}};
  EXPECT_EQ(analyse_mesh(soup(v, {{0, 1, 2}, {0, 3, 4}})).self_intersecting_pairs, 0u);  // edges back to back
  EXPECT_EQ(analyse_mesh(soup(v, {{0, 1, 2}, {0, 4, 5}})).self_intersecting_pairs, 0u);  // side by side
  EXPECT_EQ(analyse_mesh(soup(v, {{0, 1, 2}, {0, 8, 4}})).self_intersecting_pairs, 0u);  // opposite
  EXPECT_EQ(analyse_mesh(soup(v, {{0, 1, 2}, {0, 6, 7}})).self_intersecting_pairs, 1u);  // one inside
  EXPECT_EQ(analyse_mesh(soup(v, {{0, 1, 2}, {0, 5, 9}})).self_intersecting_pairs, 1u);  // along an edge
}

TEST(MeshQuality, CoplanarTrianglesOverlappingAlongASharedEdge) {
  const std::vector<Vec3> v{{0, 0, 0}, {2, 0, 0}, {1, 1, 0}, {1, 2, 0}};
  // Both the same way round (inconsistent: the triangle-soup test) ...
  const MeshQuality same = analyse_mesh(soup(v, {{0, 1, 2}, {0, 1, 3}}));
  EXPECT_EQ(same.inconsistent_orientation_edges, 1u);
  EXPECT_EQ(same.self_intersecting_pairs, 1u);
  // ... and folded over (consistent, manifold: CGAL Surface_mesh and PMP).
  const MeshQuality folded = analyse_mesh(soup(v, {{0, 1, 2}, {1, 0, 3}}));
  EXPECT_EQ(folded.inconsistent_orientation_edges, 0u);
  EXPECT_EQ(folded.upside_down_triangles, 1u);
  EXPECT_EQ(folded.self_intersecting_pairs, 1u);
  // Side by side in the plane: no overlap.
  const MeshQuality flat =
      analyse_mesh(soup({{0, 0, 0}, {2, 0, 0}, {1, 1, 0}, {1, -1, 0}}, {{0, 1, 2}, {1, 0, 3}}));
  EXPECT_EQ(flat.self_intersecting_pairs, 0u);
}

TEST(MeshQuality, SliverAndDegenerateTriangles) {
  const MeshQuality q = analyse_mesh(
      soup({{0, 0, 0}, {10, 0, 0}, {5, 0.1, 0}, {20, 0, 0}, {21, 0, 0}, {22, 0, 0}}, {{0, 1, 2}, {3, 4, 5}}));
  EXPECT_EQ(q.degenerate_triangles, 1u);
  EXPECT_EQ(q.sliver_triangles, 1u);
  EXPECT_NEAR(q.min_angle_deg, std::atan2(0.1, 5.0) * 180.0 / std::numbers::pi, 1e-9);
  EXPECT_NEAR(q.max_aspect_ratio, 100.0, 1e-9);  // 10^2 / (2 * 0.5)
  EXPECT_NEAR(q.area_m2, 0.5, 1e-12);
  EXPECT_EQ(q.self_intersecting_pairs, 0u);
  // Only the aspect ratio makes it a sliver when the angle bound is relaxed.
  MeshQualityOptions options;
  options.sliver_min_angle_deg = 1.0;
  EXPECT_EQ(analyse_mesh(soup({{0, 0, 0}, {10, 0, 0}, {5, 0.1, 0}}, {{0, 1, 2}}), options).sliver_triangles,
            1u);
  options.sliver_max_aspect_ratio = 101;
  EXPECT_EQ(analyse_mesh(soup({{0, 0, 0}, {10, 0, 0}, {5, 0.1, 0}}, {{0, 1, 2}}), options).sliver_triangles,
            0u);
}

TEST(MeshQuality, TwoSeparatedSquares) {
  TriangleMesh m = grid(1, 1);
  m.append(grid(1, 1, 1.0, Vec3(5, 0, 2)));
  const MeshQuality q = analyse_mesh(m);
  EXPECT_EQ(q.components, 2u);
  EXPECT_EQ(q.boundary_loops, 2u);
  EXPECT_EQ(q.holes, 0u);
  EXPECT_EQ(q.min_z, 0.0);
  EXPECT_EQ(q.max_z, 2.0);
  EXPECT_EQ(q.bounds.max, Vec2(6, 1));
}

TEST(MeshQuality, SelfIntersectionTestCanBeSkipped) {
  MeshQualityOptions options;
  options.self_intersections = false;
  const MeshQuality q =
      analyse_mesh(soup({{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0.5, 0.5, -1}, {0.5, 0.5, 1}, {3, 3, 0}},
                        {{0, 1, 2}, {3, 5, 4}}),
                   options);
  EXPECT_FALSE(q.self_intersections_checked);
  EXPECT_EQ(q.self_intersecting_pairs, 0u);
}

// A crumpled grid (manifold: CGAL PMP) and the same grid with a far-away non-manifold gadget
// (triangle-soup test) must find the same intersecting pairs.
TEST(MeshQuality, HalfedgeAndSoupTestsAgree) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> jitter(-0.7, 0.7);
  TriangleMesh m = grid(12, 12);
  for (Vec3& v : m.vertices) v += Vec3(jitter(rng), jitter(rng), 0.3 * jitter(rng));
  const MeshQuality manifold = analyse_mesh(m);
  ASSERT_EQ(manifold.non_manifold_edges, 0u);
  ASSERT_EQ(manifold.inconsistent_orientation_edges, 0u);
  EXPECT_GT(manifold.self_intersecting_pairs, 0u);
  m.append(soup({{100, 0, 0}, {101, 0, 0}, {100.5, 1, 0}, {100.5, -1, 0}, {100.5, 0, 1}},
                {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}}));
  const MeshQuality with_gadget = analyse_mesh(m);
  ASSERT_EQ(with_gadget.non_manifold_edges, 1u);
  EXPECT_EQ(with_gadget.self_intersecting_pairs, manifold.self_intersecting_pairs);
}

TEST(MeshQuality, WavyGridOfFortyThousandTriangles) {
  const MeshQuality q = analyse_mesh(grid(200, 100, 0.5, Vec3::Zero(), [](double x, double y) {
    return 3.0 * std::sin(0.1 * x) * std::cos(0.07 * y);
  }));
  EXPECT_EQ(q.triangles, 40000u);
  EXPECT_EQ(q.components, 1u);
  EXPECT_EQ(q.boundary_edges, 600u);
  EXPECT_EQ(q.boundary_loops, 1u);
  EXPECT_EQ(q.holes, 0u);
  EXPECT_EQ(q.non_manifold_vertices, 0u);
  EXPECT_EQ(q.self_intersecting_pairs, 0u);
  EXPECT_EQ(q.upside_down_triangles, 0u);
}

TEST(MeshQuality, BadIndexThrows) {
  EXPECT_THROW((void)analyse_mesh(soup({{0, 0, 0}, {1, 0, 0}}, {{0, 1, 2}})), InvalidInput);
  EXPECT_THROW((void)boundary_loops(soup({{0, 0, 0}, {1, 0, 0}}, {{0, 1, 2}})), InvalidInput);
}

// Timing on 1 M triangles (run with --gtest_also_run_disabled_tests).
TEST(MeshQuality, DISABLED_MillionTriangleTiming) {
  const TriangleMesh m = grid(1000, 500, 1.0, Vec3::Zero(), [](double x, double y) {
    return 5.0 * std::sin(0.05 * x) * std::cos(0.03 * y);
  });
  for (const bool self : {false, true}) {
    MeshQualityOptions options;
    options.self_intersections = self;
    const auto start = std::chrono::steady_clock::now();
    const std::clock_t cpu = std::clock();
    const MeshQuality q = analyse_mesh(m, options);
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::cout << "1M triangles, self-intersections " << (self ? "on" : "off") << ": " << s << " s wall, "
              << static_cast<double>(std::clock() - cpu) / CLOCKS_PER_SEC << " s CPU\n";
    EXPECT_EQ(q.triangles, 1000000u);
    EXPECT_EQ(q.boundary_edges, 3000u);
    EXPECT_EQ(q.self_intersecting_pairs, 0u);
  }
  TriangleMesh broken = m;
  broken.triangles.push_back(broken.triangles.front());  // a duplicate: soup test on 1 M
  const auto start = std::chrono::steady_clock::now();
  const std::clock_t cpu = std::clock();
  const MeshQuality q = analyse_mesh(broken);
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::cout << "1M triangles, triangle-soup self-intersections: " << s << " s wall, "
            << static_cast<double>(std::clock() - cpu) / CLOCKS_PER_SEC << " s CPU\n";
  EXPECT_EQ(q.self_intersecting_pairs, 1u);
}

TEST(BoundaryLoops, GridHasOneCounterClockwiseLoop) {
  const auto loops = boundary_loops(grid(2, 2));
  ASSERT_EQ(loops.size(), 1u);
  ASSERT_EQ(loops[0].size(), 8u);
  double twice_area = 0.0;
  const TriangleMesh m = grid(2, 2);
  for (std::size_t i = 0; i < 8; ++i) {
    const Vec3& a = m.vertices[loops[0][i]];
    const Vec3& b = m.vertices[loops[0][(i + 1) % 8]];
    twice_area += a.x() * b.y() - b.x() * a.y();
  }
  EXPECT_NEAR(twice_area, 8.0, 1e-12);
}

TEST(BoundaryLoops, LoopsTouchingAtAVertexAreSplit) {
  const auto loops = boundary_loops(
      soup({{0, 0, 0}, {-1, -1, 0}, {-1.5, 0, 0}, {-1, 1, 0}, {1, -1, 0}, {1.5, 0, 0}, {1, 1, 0}},
           {{0, 3, 2}, {0, 2, 1}, {0, 4, 5}, {0, 5, 6}}));
  ASSERT_EQ(loops.size(), 2u);
  for (const auto& loop : loops) {
    EXPECT_EQ(loop.size(), 4u);
    EXPECT_EQ(std::count(loop.begin(), loop.end(), 0u), 1);
  }
}

TEST(SeamGap, GridsSharingAnEdge) {
  const TriangleMesh a = grid(2, 2);
  const SeamGap joined = seam_gap(a, grid(2, 2, 1.0, Vec3(2, 0, 0)));
  EXPECT_EQ(joined.vertices_checked, 3u);
  EXPECT_EQ(joined.max_gap_m, 0.0);
  const SeamGap offset = seam_gap(a, grid(2, 2, 1.0, Vec3(2, 0, 0.03)));
  EXPECT_EQ(offset.vertices_checked, 3u);
  EXPECT_NEAR(offset.max_gap_m, 0.03, 1e-9);
  // An edge 3 m above (a deck over the other surface's edge) is no seam: the reach is in 3D.
  const SeamGap above = seam_gap(a, grid(2, 2, 1.0, Vec3(2, 0, 3)));
  EXPECT_EQ(above.vertices_checked, 0u);
  EXPECT_EQ(above.max_gap_m, 0.0);
  // With a 3.5 m reach the column one metre in counts too: sqrt(1 + 9).
  EXPECT_NEAR(seam_gap(a, grid(2, 2, 1.0, Vec3(2, 0, 3)), 3.5).max_gap_m, std::sqrt(10.0), 1e-9);
  // Out of reach: nothing checked.
  const SeamGap apart = seam_gap(a, grid(2, 2, 1.0, Vec3(3, 0, 0)));
  EXPECT_EQ(apart.vertices_checked, 0u);
  EXPECT_EQ(apart.max_gap_m, 0.0);
  EXPECT_THROW((void)seam_gap(a, a, -1.0), InvalidInput);
}

TEST(SeamGap, LongEdgesAreFound) {
  // b: one 100 m strip whose long edges pass beside a's vertices, 0.2 m away in the plane.
  const TriangleMesh a = grid(2, 2);
  const TriangleMesh b = soup({{-50, 2.2, 0}, {50, 2.2, 0}, {50, 3, 0}, {-50, 3, 0}}, {{0, 1, 2}, {0, 2, 3}});
  const SeamGap g = seam_gap(a, b);
  EXPECT_EQ(g.vertices_checked, 3u);
  EXPECT_NEAR(g.max_gap_m, 0.2, 1e-12);
}

}  // namespace
}  // namespace relief
