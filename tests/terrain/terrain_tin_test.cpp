#include "relief/terrain/terrain_tin.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include "relief/core/errors.h"
#include "relief/terrain/dem_writer.h"
#include "support/test_data.h"

namespace relief {
namespace {

// Synthetic DEMs in EPSG:32610, frame origin (550000, 4180000), covering local x, y in
// [-200, 200] with 10 m cells (centres at -195 ... 195). The terrain area stays inside the cell
// centres, where bilinear interpolation reproduces a plane exactly.
constexpr double kExtent = 200.0;
constexpr double kCell = 10.0;

GeoFrame frame() {
  return GeoFrame("EPSG:32610", Vec2(550000.0, 4180000.0));
}

Aabb2 box(double half) {
  Aabb2 b;
  b.extend(Vec2(-half, -half));
  b.extend(Vec2(half, half));
  return b;
}

using Surface = std::function<double(double, double)>;

// A DEM whose value at each cell centre is f(x, y) in local coordinates (nullopt: nodata).
DemSampler make_dem_with_voids(const std::string& name,
                               const std::function<std::optional<double>(double, double)>& f) {
  constexpr double kNodata = -9999.0;
  const Vec2 o = frame().origin();
  const int n = static_cast<int>(2.0 * kExtent / kCell);
  DemGrid grid = make_dem_grid(frame().crs(), o.x() - kExtent, o.y() + kExtent, kCell, kCell, n, n,
                               [&](double x, double y) { return f(x - o.x(), y - o.y()).value_or(kNodata); });
  grid.nodata = kNodata;
  const auto path = (test::scratch_dir("terrain_tin_" + name) / (name + ".tif")).string();
  write_geotiff(path, grid);
  return DemSampler({path}, frame(), box(kExtent));
}

DemSampler make_dem(const std::string& name, const Surface& f) {
  return make_dem_with_voids(name, [&](double x, double y) { return std::optional<double>(f(x, y)); });
}

double plane(double x, double y) {
  return 100.0 + 0.05 * x + 0.02 * y;
}

// Closed square loop (first point not repeated) with a point every `spacing` metres, z = f.
Polyline3 square(double x0, double y0, double x1, double y1, double spacing, const Surface& z) {
  Polyline3 loop;
  const Vec2 corners[] = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
  for (int c = 0; c < 4; ++c) {
    const Vec2 a = corners[c];
    const Vec2 b = corners[(c + 1) % 4];
    const int n = std::max(1, static_cast<int>(std::lround((b - a).norm() / spacing)));
    for (int i = 0; i < n; ++i) {
      const Vec2 p = a + (b - a) * (static_cast<double>(i) / n);
      loop.emplace_back(p.x(), p.y(), z(p.x(), p.y()));
    }
  }
  return loop;
}

bool inside_box(const Vec2& p, double x0, double y0, double x1, double y1) {
  return p.x() > x0 && p.x() < x1 && p.y() > y0 && p.y() < y1;
}

Vec2 centroid(const TriangleMesh& mesh, const std::array<std::uint32_t, 3>& t) {
  const Vec3 c = (mesh.vertices[t[0]] + mesh.vertices[t[1]] + mesh.vertices[t[2]]) / 3.0;
  return {c.x(), c.y()};
}

double signed_area(const TriangleMesh& mesh, const std::array<std::uint32_t, 3>& t) {
  const Vec3 a = mesh.vertices[t[1]] - mesh.vertices[t[0]];
  const Vec3 b = mesh.vertices[t[2]] - mesh.vertices[t[0]];
  return 0.5 * (a.x() * b.y() - a.y() * b.x());
}

// Height of the mesh at p (brute force over the triangles), nullopt outside it.
std::optional<double> height_on(const TriangleMesh& mesh, const Vec2& p) {
  for (const auto& t : mesh.triangles) {
    const Vec3& a = mesh.vertices[t[0]];
    const Vec3& b = mesh.vertices[t[1]];
    const Vec3& c = mesh.vertices[t[2]];
    const double det = (b.x() - a.x()) * (c.y() - a.y()) - (c.x() - a.x()) * (b.y() - a.y());
    const double u = ((p.x() - a.x()) * (c.y() - a.y()) - (c.x() - a.x()) * (p.y() - a.y())) / det;
    const double v = ((b.x() - a.x()) * (p.y() - a.y()) - (p.x() - a.x()) * (b.y() - a.y())) / det;
    constexpr double kEps = 1e-9;
    if (u >= -kEps && v >= -kEps && u + v <= 1.0 + kEps)
      return a.z() + u * (b.z() - a.z()) + v * (c.z() - a.z());
  }
  return std::nullopt;
}

// Distance to the nearest point of the loops and the loops' height there (brute force).
std::pair<double, double> nearest_edge(const std::vector<Polyline3>& loops, const Vec2& p) {
  double best = std::numeric_limits<double>::infinity();
  double z = 0.0;
  for (const Polyline3& loop : loops) {
    for (std::size_t i = 0; i < loop.size(); ++i) {
      const Vec3& a = loop[i];
      const Vec3& b = loop[(i + 1) % loop.size()];
      const Vec2 ab(b.x() - a.x(), b.y() - a.y());
      const double t = std::clamp((p - Vec2(a.x(), a.y())).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
      const double d = (Vec2(a.x(), a.y()) + t * ab - p).norm();
      if (d < best) {
        best = d;
        z = a.z() + t * (b.z() - a.z());
      }
    }
  }
  return {best, z};
}

using Key = std::tuple<double, double, double>;
std::set<Key> vertex_set(const TriangleMesh& mesh) {
  std::set<Key> out;
  for (const Vec3& v : mesh.vertices) out.emplace(v.x(), v.y(), v.z());
  return out;
}

void expect_well_formed(const TriangleMesh& mesh) {
  EXPECT_EQ(mesh.name, "Terrain");
  EXPECT_EQ(mesh.kind, SurfaceKind::terrain);
  ASSERT_FALSE(mesh.triangles.empty());
  EXPECT_EQ(mesh.normals.size(), mesh.vertices.size());
  EXPECT_EQ(mesh.uvs.size(), mesh.vertices.size());
  for (const auto& t : mesh.triangles) EXPECT_GT(signed_area(mesh, t), 0.0);  // CCW from above
  for (const Vec3& n : mesh.normals) EXPECT_GT(n.z(), 0.0);
}

// ---------------------------------------------------------------- simplification

TEST(TerrainTin, PlaneNeedsOnlyTheCornersAndIsExact) {
  const DemSampler dem = make_dem("plane", plane);
  const TerrainBuild build = build_terrain(dem, box(150.0), {});  // + 30 m margin: [-180, 180]

  expect_well_formed(build.terrain);
  EXPECT_EQ(build.dem_points, 37u * 37u);  // every 10 m from -180 to 180
  EXPECT_EQ(build.dem_voids, 0u);
  EXPECT_EQ(build.tin_vertices, 4u);
  EXPECT_EQ(build.terrain.triangles.size(), 2u);
  EXPECT_LE(build.max_vertical_error_m, 1e-9);
  EXPECT_EQ(build.triangles_removed, 0u);
  for (double x = -180.0; x <= 180.0; x += 30.0) {
    for (double y = -180.0; y <= 180.0; y += 30.0) {
      const auto z = height_on(build.terrain, Vec2(x, y));
      ASSERT_TRUE(z.has_value()) << x << ", " << y;
      EXPECT_NEAR(*z, plane(x, y), 1e-9);
    }
  }
}

TEST(TerrainTin, WavySurfaceStaysWithinTheToleranceAtEverySample) {
  const Surface wave = [](double x, double y) {
    return 50.0 + 5.0 * std::sin(x / 60.0) * std::cos(y / 50.0) + 1e-4 * x * y;
  };
  const DemSampler dem = make_dem("wave", wave);
  TerrainOptions options;
  options.vertical_tolerance_m = 0.1;
  const TerrainBuild build = build_terrain(dem, box(150.0), {}, options);

  expect_well_formed(build.terrain);
  EXPECT_LE(build.max_vertical_error_m, options.vertical_tolerance_m + 1e-6);
  EXPECT_GT(build.tin_vertices, 20u);
  EXPECT_LT(build.tin_vertices, build.dem_points / 2);  // it did simplify
  // Independent check at every DEM sample of the grid.
  double worst = 0.0;
  for (double x = -180.0; x <= 180.0; x += 10.0) {
    for (double y = -180.0; y <= 180.0; y += 10.0) {
      const auto z = height_on(build.terrain, Vec2(x, y));
      const auto h = dem.height_at(Vec2(x, y));
      ASSERT_TRUE(z && h) << x << ", " << y;
      worst = std::max(worst, std::abs(*z - *h));
    }
  }
  EXPECT_LE(worst, options.vertical_tolerance_m + 1e-6);
  EXPECT_NEAR(worst, build.max_vertical_error_m, 1e-9);
}

// Heights quantised to whole metres tie the greedy insertion's errors everywhere. The TIN must
// not depend on where its faces lie in memory: each build below runs after the heap was
// fragmented differently, and all must give the same vertices and triangles.
TEST(TerrainTin, TiedErrorsGiveTheSameTinWhateverTheMemoryLayout) {
  const Surface terraces = [](double x, double y) {
    return std::round(40.0 - 0.08 * std::abs(x) - 0.05 * std::abs(y) + 3.0 * std::sin(x / 40.0));
  };
  const DemSampler dem = make_dem("terraces", terraces);
  TerrainOptions options;
  options.vertical_tolerance_m = 0.1;
  const TriangleMesh first = build_terrain(dem, box(180.0), {}, options).terrain;
  ASSERT_GT(first.triangles.size(), 100u);
  for (int layout = 1; layout <= 6; ++layout) {
    std::vector<std::vector<char>> blocks;  // every other block freed: holes of varied sizes
    for (int i = 0; i < 300 * layout; ++i)
      blocks.emplace_back(static_cast<std::size_t>(64 + (i * 7919) % 200000));
    for (std::size_t i = 0; i < blocks.size(); i += 2) std::vector<char>().swap(blocks[i]);
    const TriangleMesh again = build_terrain(dem, box(180.0), {}, options).terrain;
    ASSERT_EQ(again.vertices.size(), first.vertices.size()) << "layout " << layout;
    ASSERT_EQ(again.triangles.size(), first.triangles.size()) << "layout " << layout;
    for (std::size_t i = 0; i < first.vertices.size(); ++i) {
      ASSERT_EQ(again.vertices[i], first.vertices[i]) << "layout " << layout << ", vertex " << i;
    }
    for (std::size_t i = 0; i < first.triangles.size(); ++i) {
      ASSERT_EQ(again.triangles[i], first.triangles[i]) << "layout " << layout << ", triangle " << i;
    }
  }
}

TEST(TerrainTin, GridStepOptionSetsTheSampling) {
  const DemSampler dem = make_dem("plane_step", plane);
  TerrainOptions options;
  options.grid_step_m = 5.0;
  options.margin_m = 0.0;
  const TerrainBuild build = build_terrain(dem, box(100.0), {}, options);
  EXPECT_EQ(build.dem_points, 41u * 41u);
}

// ---------------------------------------------------------------- outline

TEST(TerrainTin, SquareRoadLeavesAHoleBoundedExactlyByTheOutline) {
  const DemSampler dem = make_dem("square", plane);
  const std::vector<Polyline3> outline{square(-50.0, -50.0, 50.0, 50.0, 5.0, plane)};
  const TerrainBuild build = build_terrain(dem, box(150.0), outline);

  expect_well_formed(build.terrain);
  EXPECT_GT(build.triangles_removed, 0u);
  EXPECT_EQ(build.outline_crossings, 0u);
  // Every outline point is a terrain vertex, bit for bit.
  const std::set<Key> vertices = vertex_set(build.terrain);
  for (const Vec3& p : outline[0]) EXPECT_TRUE(vertices.count({p.x(), p.y(), p.z()})) << p.transpose();
  // The hole's boundary is exactly the outline: the boundary loop with no hull vertex.
  const auto loops = boundary_loops(build.terrain);
  ASSERT_EQ(loops.size(), 2u);
  std::set<Key> outline_points;
  for (const Vec3& p : outline[0]) outline_points.emplace(p.x(), p.y(), p.z());
  int holes = 0;
  for (const auto& loop : loops) {
    const Vec3& first = build.terrain.vertices[loop.front()];
    if (std::abs(first.x()) > 100.0 || std::abs(first.y()) > 100.0) continue;  // the outer border
    ++holes;
    std::set<Key> hole;
    for (const std::uint32_t v : loop) {
      const Vec3& p = build.terrain.vertices[v];
      hole.emplace(p.x(), p.y(), p.z());
    }
    EXPECT_EQ(hole, outline_points);
  }
  EXPECT_EQ(holes, 1);
  for (const auto& t : build.terrain.triangles) {
    EXPECT_FALSE(inside_box(centroid(build.terrain, t), -50.0, -50.0, 50.0, 50.0));
  }
  // Flat road on flat ground: no batter, and the terrain stays exact.
  EXPECT_EQ(build.vertices_on_slopes, 0u);
  EXPECT_LE(build.max_cut_m, 1e-9);
  EXPECT_LE(build.max_fill_m, 1e-9);
  EXPECT_LE(build.max_vertical_error_m, 1e-9);
}

TEST(TerrainTin, LiftedRoadGetsAFillBatterThatMeetsItsEdge) {
  constexpr double kLift = 10.0;  // the batter reaches 15 m out: samples 10 m from the edge move
  const DemSampler dem = make_dem("lifted", plane);
  const std::vector<Polyline3> outline{
      square(-40.0, -40.0, 40.0, 40.0, 4.0, [](double x, double y) { return plane(x, y) + kLift; })};
  TerrainOptions options;
  options.vertical_tolerance_m = 0.05;
  const TerrainBuild build = build_terrain(dem, box(150.0), outline, options);

  expect_well_formed(build.terrain);
  const std::set<Key> vertices = vertex_set(build.terrain);
  for (const Vec3& p : outline[0]) EXPECT_TRUE(vertices.count({p.x(), p.y(), p.z()}));
  EXPECT_GT(build.vertices_on_slopes, 0u);
  EXPECT_NEAR(build.max_fill_m, kLift, 1e-9);  // at the samples on the road edge
  EXPECT_LE(build.max_cut_m, 1e-9);
  EXPECT_LE(build.max_vertical_error_m, options.vertical_tolerance_m + 1e-6);

  // Every vertex within the batter width: no steeper than 1 / run from the nearest edge point.
  const double run = options.slope_run_per_rise;
  for (const Vec3& v : build.terrain.vertices) {
    const auto [d, z_edge] = nearest_edge(outline, Vec2(v.x(), v.y()));
    if (d >= options.max_slope_width_m) continue;
    EXPECT_LE(std::abs(v.z() - z_edge), d / run + 1e-9) << v.transpose();
  }
  // At the DEM samples outside the road: on the batter within the tolerance; beyond the
  // batter's reach the natural ground.
  for (double x = -180.0; x <= 180.0; x += kCell) {
    for (double y = -180.0; y <= 180.0; y += kCell) {
      if (inside_box(Vec2(x, y), -40.0, -40.0, 40.0, 40.0)) continue;
      const auto [d, z_edge] = nearest_edge(outline, Vec2(x, y));
      const auto z = height_on(build.terrain, Vec2(x, y));
      ASSERT_TRUE(z.has_value());
      const double tolerance = options.vertical_tolerance_m + 1e-6;
      if (d < options.max_slope_width_m) {
        EXPECT_LE(std::abs(*z - z_edge), d / run + tolerance) << x << ", " << y;
      }
      if (d >= kLift * run) {
        EXPECT_NEAR(*z, plane(x, y), tolerance) << x << ", " << y;
      }
    }
  }
}

TEST(TerrainTin, ADeckBesideAFillStaysAboveTheTerrain) {
  // A road lifted 10 m (its fill batter reaches 15 m out) and, 5 m from its edge, a deck 5 m
  // above the plane: the batter there is 6.7 m up and would rise through the deck.
  const DemSampler dem = make_dem("deck", plane);
  const std::vector<Polyline3> outline{
      square(-40.0, -40.0, 40.0, 40.0, 4.0, [](double x, double y) { return plane(x, y) + 10.0; })};
  const auto deck_z = [](double x, double y) { return plane(x, y) + 5.0; };
  TriangleMesh deck;
  for (const Vec2& p : {Vec2(45, -20), Vec2(60, -20), Vec2(60, 20), Vec2(45, 20)})
    deck.vertices.emplace_back(p.x(), p.y(), deck_z(p.x(), p.y()));
  deck.triangles = {{0, 1, 2}, {0, 2, 3}};
  TerrainOptions options;
  options.vertical_tolerance_m = 0.05;
  const auto highest_over_deck = [&](const TriangleMesh& terrain) {
    double worst = -std::numeric_limits<double>::infinity();  // terrain height - deck height
    for (double x = 45.0; x <= 60.0; x += 0.5) {
      for (double y = -20.0; y <= 20.0; y += 0.5) {
        const auto z = height_on(terrain, Vec2(x, y));
        if (z) worst = std::max(worst, *z - deck_z(x, y));
      }
    }
    return worst;
  };
  const TerrainBuild without = build_terrain(dem, box(150.0), outline, options);
  EXPECT_GT(highest_over_deck(without.terrain), 1.0);
  EXPECT_EQ(without.vertices_under_decks, 0u);

  const TerrainBuild build = build_terrain(dem, box(150.0), outline, options, deck);
  expect_well_formed(build.terrain);
  EXPECT_EQ(build.deck_edges_constrained, 4u);  // the rectangle; its diagonal is inside
  EXPECT_GT(build.vertices_under_decks, 0u);
  EXPECT_LE(highest_over_deck(build.terrain), -options.deck_clearance_m + 1e-9);
  // The road edge is still the terrain's, vertex for vertex.
  const std::set<Key> vertices = vertex_set(build.terrain);
  for (const Vec3& p : outline[0]) EXPECT_TRUE(vertices.count({p.x(), p.y(), p.z()}));
  // Away from the deck the terrain is unchanged.
  for (const Vec2& p : {Vec2(-60.0, 0.0), Vec2(0.0, 60.0), Vec2(100.0, 100.0)}) {
    EXPECT_NEAR(*height_on(build.terrain, p), *height_on(without.terrain, p), 1e-9);
  }
}

TEST(TerrainTin, RingRoadKeepsTheBlockInsideAsTerrain) {
  const DemSampler dem = make_dem("ring", plane);
  const std::vector<Polyline3> outline{square(-80.0, -80.0, 80.0, 80.0, 8.0, plane),
                                       square(-40.0, -40.0, 40.0, 40.0, 8.0, plane)};
  const TerrainBuild build = build_terrain(dem, box(150.0), outline);

  expect_well_formed(build.terrain);
  double block_area = 0.0;
  for (const auto& t : build.terrain.triangles) {
    const Vec2 c = centroid(build.terrain, t);
    const bool in_block = inside_box(c, -40.0, -40.0, 40.0, 40.0);
    EXPECT_FALSE(inside_box(c, -80.0, -80.0, 80.0, 80.0) && !in_block) << c.transpose();
    if (in_block) block_area += signed_area(build.terrain, t);
  }
  EXPECT_NEAR(block_area, 80.0 * 80.0, 1e-6);
  const std::set<Key> vertices = vertex_set(build.terrain);
  for (const Polyline3& loop : outline) {
    for (const Vec3& p : loop) EXPECT_TRUE(vertices.count({p.x(), p.y(), p.z()}));
  }
  EXPECT_EQ(boundary_loops(build.terrain).size(), 3u);
}

TEST(TerrainTin, CrossingLoopsAreSplitAndTheOverlapIsTerrain) {
  const DemSampler dem = make_dem("crossing", plane);
  // Two squares given by their corners only; their edges cross at (20, -20) and (-20, 20).
  const std::vector<Polyline3> outline{square(-60.0, -60.0, 20.0, 20.0, 1000.0, plane),
                                       square(-20.0, -20.0, 60.0, 60.0, 1000.0, plane)};
  const TerrainBuild build = build_terrain(dem, box(150.0), outline);

  expect_well_formed(build.terrain);
  EXPECT_EQ(build.outline_crossings, 2u);
  const std::set<Key> vertices = vertex_set(build.terrain);
  const auto has_vertex_near = [&](double x, double y) {
    return std::any_of(vertices.begin(), vertices.end(), [&](const Key& k) {
      return std::abs(std::get<0>(k) - x) < 1e-9 && std::abs(std::get<1>(k) - y) < 1e-9 &&
             std::abs(std::get<2>(k) - plane(x, y)) < 1e-9;
    });
  };
  EXPECT_TRUE(has_vertex_near(20.0, -20.0));
  EXPECT_TRUE(has_vertex_near(-20.0, 20.0));
  double overlap_area = 0.0;
  for (const auto& t : build.terrain.triangles) {
    const Vec2 c = centroid(build.terrain, t);
    const bool in_a = inside_box(c, -60.0, -60.0, 20.0, 20.0);
    const bool in_b = inside_box(c, -20.0, -20.0, 60.0, 60.0);
    EXPECT_FALSE(in_a != in_b) << c.transpose();  // inside exactly one loop: paved
    if (in_a && in_b) overlap_area += signed_area(build.terrain, t);
  }
  EXPECT_NEAR(overlap_area, 40.0 * 40.0, 1e-6);
}

// ---------------------------------------------------------------- region tiles' core lines

// How many triangles of the build's terrain (only those in its core: `core_only`) hold p strictly
// inside (brute force).
int faces_containing(const TerrainBuild& build, const Vec2& p, bool core_only) {
  int n = 0;
  const TriangleMesh& mesh = build.terrain;
  for (std::size_t k = 0; k < mesh.triangles.size(); ++k) {
    if (core_only && build.in_core[k] == 0) continue;
    const auto& t = mesh.triangles[k];
    const Vec3& a = mesh.vertices[t[0]];
    const Vec3& b = mesh.vertices[t[1]];
    const Vec3& c = mesh.vertices[t[2]];
    const auto side = [&](const Vec3& u, const Vec3& w) {
      return (w.x() - u.x()) * (p.y() - u.y()) - (w.y() - u.y()) * (p.x() - u.x());
    };
    if (side(a, b) > 0.0 && side(b, c) > 0.0 && side(c, a) > 0.0) ++n;
  }
  return n;
}

TEST(TerrainTin, NeighbouringCoresMeetOnALineTheDemDoesNotReach) {
  // The DEM has heights west of x = -40 only; two roads run east across the tile line x = 0,
  // beyond it, so the terrain reaches the line only over the roads' outline (Portland's DEM
  // ends 42 to 73 m short of a tile line). Both tiles must still cut the line at the same
  // vertices and keep one side each: before, the line had no point where the DEM had no height,
  // and the flood telling the sides crossed the gap (104 leaks in one Portland tile).
  const DemSampler dem = make_dem_with_voids("dem_edge", [](double x, double y) -> std::optional<double> {
    if (x >= -40.0) return std::nullopt;
    return plane(x, y);
  });
  const std::vector<Polyline3> outline{square(-141.0, -50.0, 139.0, -40.0, 4.0, plane),
                                       square(-141.0, 40.0, 139.0, 50.0, 4.0, plane)};
  const auto tile = [&](double x0, double x1, double core_x0, double core_x1) {
    TerrainOptions options;
    options.core = Aabb2{Vec2(core_x0, -150.0), Vec2(core_x1, 150.0)};
    return build_terrain(dem, Aabb2{Vec2(x0, -150.0), Vec2(x1, 150.0)}, outline, options);
  };
  const TerrainBuild west = tile(-150.0, 60.0, -150.0, 0.0), east = tile(-60.0, 150.0, 0.0, 150.0);
  for (const TerrainBuild* b : {&west, &east}) {
    expect_well_formed(b->terrain);
    ASSERT_EQ(b->in_core.size(), b->terrain.triangles.size());
    EXPECT_EQ(b->core_leaks, 0u);
    EXPECT_EQ(b->core_blocked, 0u);
  }
  // The line's vertices, to the bit, in both tiles' kept terrain.
  const auto on_line = [](const TerrainBuild& b) {
    std::set<Key> out;
    for (std::size_t k = 0; k < b.terrain.triangles.size(); ++k) {
      if (b.in_core[k] == 0) continue;
      for (const std::uint32_t i : b.terrain.triangles[k]) {
        const Vec3& v = b.terrain.vertices[i];
        if (v.x() == 0.0) out.emplace(v.x(), v.y(), v.z());
      }
    }
    return out;
  };
  const std::set<Key> west_line = on_line(west), east_line = on_line(east);
  EXPECT_GE(west_line.size(), 20u);
  EXPECT_EQ(west_line, east_line);
  // Where both tiles have terrain near the line, exactly one of them keeps it: no overlap, no gap.
  int checked = 0;
  for (double y = -139.37; y < 140.0; y += 3.1) {
    for (double x = -29.71; x < 30.0; x += 2.3) {
      const Vec2 p(x, y);
      if (faces_containing(west, p, false) == 0 || faces_containing(east, p, false) == 0) continue;
      ++checked;
      EXPECT_EQ(faces_containing(west, p, true) + faces_containing(east, p, true), 1) << p.transpose();
    }
  }
  EXPECT_GT(checked, 1000);
}

// ---------------------------------------------------------------- voids and errors

TEST(TerrainTin, VoidsGetNoVertexAndNoFakeHeight) {
  const Surface wave = [](double x, double y) {
    return 20.0 + 5.0 * std::sin(x / 25.0) + 3.0 * std::cos(y / 35.0);
  };
  const DemSampler dem = make_dem_with_voids("void", [&](double x, double y) -> std::optional<double> {
    if (std::abs(x) < 60.0 && std::abs(y) < 40.0) return std::nullopt;
    return wave(x, y);
  });
  TerrainOptions options;
  options.vertical_tolerance_m = 0.2;
  const TerrainBuild build = build_terrain(dem, box(150.0), {}, options);

  expect_well_formed(build.terrain);
  EXPECT_GT(build.dem_voids, 0u);
  EXPECT_EQ(build.dem_points + build.dem_voids, 37u * 37u);
  EXPECT_LE(build.max_vertical_error_m, options.vertical_tolerance_m + 1e-6);
  for (const Vec3& v : build.terrain.vertices) {
    const auto h = dem.height_at(Vec2(v.x(), v.y()));
    ASSERT_TRUE(h.has_value()) << v.transpose();
    EXPECT_NEAR(v.z(), *h, 1e-9) << v.transpose();
  }
}

TEST(TerrainTin, RejectsBadOptionsAndAnAreaWithoutDem) {
  const DemSampler dem = make_dem("errors", plane);
  const auto with = [](auto change) {
    TerrainOptions o;
    change(o);
    return o;
  };
  EXPECT_THROW((void)build_terrain(dem, box(100.0), {}, with([](auto& o) { o.vertical_tolerance_m = -1.0; })),
               InvalidInput);
  EXPECT_THROW((void)build_terrain(dem, box(100.0), {}, with([](auto& o) { o.grid_step_m = -1.0; })),
               InvalidInput);
  EXPECT_THROW((void)build_terrain(dem, box(100.0), {}, with([](auto& o) { o.margin_m = -1.0; })),
               InvalidInput);
  EXPECT_THROW((void)build_terrain(dem, box(100.0), {}, with([](auto& o) { o.slope_run_per_rise = 0.0; })),
               InvalidInput);
  EXPECT_THROW((void)build_terrain(dem, box(100.0), {}, with([](auto& o) { o.max_slope_width_m = -1.0; })),
               InvalidInput);
  EXPECT_THROW(
      (void)build_terrain(dem, box(100.0), {}, with([](auto& o) { o.constraint_clearance_m = 0.0; })),
      InvalidInput);
  EXPECT_THROW((void)build_terrain(dem, Aabb2{}, {}), InvalidInput);
  EXPECT_THROW((void)build_terrain(dem, box(100.0), {Polyline3{Vec3(0, 0, 0), Vec3(1, 0, 0)}}), InvalidInput);
  Aabb2 far;
  far.extend(Vec2(5000.0, 5000.0));
  far.extend(Vec2(5100.0, 5100.0));
  EXPECT_THROW((void)build_terrain(dem, far, {}), CoverageError);
}

}  // namespace
}  // namespace relief
