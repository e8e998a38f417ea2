#include "relief/terrain/terrain_tin.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <numbers>
#include <numeric>
#include <optional>
#include <string>
#include <utility>

#include "relief/core/errors.h"
#include "relief/geometry/polyline.h"
#include "terrain/core_lines.h"
#include "terrain/outline_index.h"
#include "terrain/terrain_cdt.h"
#include "terrain/tin_refinement.h"
#include "terrain/under_decks.h"

namespace relief {
namespace {

using namespace terrain_detail;

constexpr double kMetresPerDegree = 111320.0;  // along a meridian, and along the equator
constexpr double kMaxSamples = 2.0e8;

void check_input(const Aabb2& area, const std::vector<Polyline3>& outline, const TerrainOptions& o) {
  const auto require = [](bool ok, const std::string& what) {
    if (!ok) throw InvalidInput("terrain: " + what);
  };
  require(!area.empty(), "the area is empty");
  require(std::isfinite(o.vertical_tolerance_m) && o.vertical_tolerance_m >= 0.0,
          "vertical_tolerance_m must be >= 0, got " + std::to_string(o.vertical_tolerance_m));
  require(std::isfinite(o.grid_step_m) && o.grid_step_m >= 0.0,
          "grid_step_m must be >= 0 (0: the DEM's resolution), got " + std::to_string(o.grid_step_m));
  require(std::isfinite(o.margin_m) && o.margin_m >= 0.0,
          "margin_m must be >= 0, got " + std::to_string(o.margin_m));
  require(std::isfinite(o.slope_run_per_rise) && o.slope_run_per_rise > 0.0,
          "slope_run_per_rise must be > 0, got " + std::to_string(o.slope_run_per_rise));
  require(std::isfinite(o.max_slope_width_m) && o.max_slope_width_m >= 0.0,
          "max_slope_width_m must be >= 0, got " + std::to_string(o.max_slope_width_m));
  require(std::isfinite(o.constraint_clearance_m) && o.constraint_clearance_m > 0.0,
          "constraint_clearance_m must be > 0, got " + std::to_string(o.constraint_clearance_m));
  require(std::isfinite(o.deck_clearance_m) && o.deck_clearance_m >= 0.0,
          "deck_clearance_m must be >= 0, got " + std::to_string(o.deck_clearance_m));
  for (std::size_t i = 0; i < outline.size(); ++i) {
    require(outline[i].size() >= 3, "outline loop " + std::to_string(i) + " has " +
                                        std::to_string(outline[i].size()) + " points (>= 3)");
    for (const Vec3& p : outline[i])
      require(p.allFinite(), "outline loop " + std::to_string(i) + " has a non-finite point");
  }
}

// Finest pixel of the DEMs in metres (a geographic raster's degrees converted at its centre).
double dem_resolution_m(const DemSampler& dem) {
  double best = std::numeric_limits<double>::infinity();
  for (const DemInfo& info : dem.sources()) {
    if (!(info.pixel_size.x() > 0.0 && info.pixel_size.y() > 0.0)) continue;
    const bool geographic = info.crs_wkt.rfind("GEOG", 0) == 0 || info.crs_wkt.rfind("GEODCRS", 0) == 0;
    Vec2 pixel_m = info.pixel_size;
    if (geographic) {
      const double lat = info.extent.centre().y() * std::numbers::pi / 180.0;
      pixel_m = Vec2(info.pixel_size.x() * kMetresPerDegree * std::cos(lat),
                     info.pixel_size.y() * kMetresPerDegree);
    }
    best = std::min(best, pixel_m.minCoeff());
  }
  if (!std::isfinite(best) || best <= 0.0) {
    throw InvalidInput("terrain: cannot tell the DEM's resolution; set TerrainOptions::grid_step_m");
  }
  return best;
}

// The DEM on a grid of `step` over `box` (nodes at whole multiples of the step), row by row.
GridSamples sample_grid(const DemSampler& dem, const Aabb2& box, double step) {
  GridSamples grid;
  grid.step_m = step;
  grid.origin = Vec2(std::floor(box.min.x() / step) * step, std::floor(box.min.y() / step) * step);
  const double nx = std::ceil((box.max.x() - grid.origin.x()) / step) + 1.0;
  const double ny = std::ceil((box.max.y() - grid.origin.y()) / step) + 1.0;
  if (nx * ny > kMaxSamples) {
    throw InvalidInput("terrain: a grid of " + std::to_string(static_cast<long long>(nx * ny)) +
                       " DEM samples is too large; raise TerrainOptions::grid_step_m");
  }
  grid.nx = static_cast<long>(nx);
  grid.ny = static_cast<long>(ny);
  const auto n = static_cast<std::size_t>(grid.nx * grid.ny);
  grid.z_dem.assign(n, 0.0);
  grid.flags.assign(n, 0);

  // In chunks of whole rows, so that the query buffers stay small.
  const long rows_per_chunk = std::max(1L, 1'000'000L / grid.nx);
  std::vector<Vec2> points;
  std::vector<std::optional<double>> heights;
  for (long j0 = 0; j0 < grid.ny; j0 += rows_per_chunk) {
    const long j1 = std::min(grid.ny, j0 + rows_per_chunk);
    const auto first = static_cast<std::size_t>(j0 * grid.nx);
    const auto count = static_cast<std::size_t>((j1 - j0) * grid.nx);
    points.resize(count);
    heights.assign(count, std::nullopt);
    for (std::size_t k = 0; k < count; ++k) points[k] = grid.xy(first + k);
    dem.heights_at(points, heights);
    for (std::size_t k = 0; k < count; ++k) {
      if (!heights[k]) continue;
      grid.z_dem[first + k] = *heights[k];
      grid.flags[first + k] = kValid;
    }
  }
  grid.z_target = grid.z_dem;
  return grid;
}

// Moves samples near the outline onto the batter: z = clamp(z_dem, z_edge - d/run, z_edge + d/run)
// within max_slope_width_m of the nearest outline point (height z_edge, distance d).
void apply_batter(GridSamples& grid, const std::vector<Polyline3>& outline, const TerrainOptions& o) {
  if (outline.empty()) return;
  const terrain_detail::OutlineIndex index(outline, std::max(o.max_slope_width_m, o.constraint_clearance_m));
  for (std::size_t k = 0; k < grid.size(); ++k) {
    if (!grid.has(k, kValid)) continue;
    const auto hit = index.nearest(grid.xy(k));
    if (!hit) continue;
    if (hit->distance_m < o.constraint_clearance_m) grid.flags[k] |= kNear;
    if (hit->distance_m >= o.max_slope_width_m) continue;
    grid.flags[k] |= kBand;
    const double reach = hit->distance_m / o.slope_run_per_rise;
    grid.z_target[k] = std::clamp(grid.z_dem[k], hit->z - reach, hit->z + reach);
  }
}

// Indices into `grid` of the samples along the polyline `chain` kept by Douglas-Peucker on the
// heights (vertical error within tolerance_m, parameter = position along the chain). The first
// is kept, the last is not (it starts the next chain).
void simplify_chain(const GridSamples& grid, const std::vector<std::uint32_t>& chain,
                    const std::vector<long>& position, double tolerance_m, std::vector<std::uint32_t>& kept) {
  const std::vector<std::uint8_t> keep =
      douglas_peucker(chain.size(), tolerance_m, [&](std::size_t a, std::size_t m, std::size_t b) {
        const double za = grid.z_target[chain[a]];
        const double zb = grid.z_target[chain[b]];
        const double t =
            static_cast<double>(position[m] - position[a]) / static_cast<double>(position[b] - position[a]);
        return std::abs(grid.z_target[chain[m]] - (za + t * (zb - za)));
      });
  for (std::size_t m = 0; m + 1 < chain.size(); ++m) {
    if (keep[m]) kept.push_back(chain[m]);
  }
}

// The convex hull of the valid samples (Andrew's monotone chain on grid indices, exact), every
// sample on it flagged kBoundary, and the ones to insert: the hull's corners and the samples
// Douglas-Peucker keeps along its edges. Empty when the valid samples are collinear.
std::vector<std::uint32_t> hull_samples(GridSamples& grid, double tolerance_m) {
  using Node = std::pair<long, long>;  // (i, j)
  std::vector<Node> extremes;
  for (long j = 0; j < grid.ny; ++j) {
    long first = -1, last = -1;
    for (long i = 0; i < grid.nx; ++i) {
      if (!grid.has(static_cast<std::size_t>(j * grid.nx + i), kValid)) continue;
      if (first < 0) first = i;
      last = i;
    }
    if (first < 0) continue;
    extremes.emplace_back(first, j);
    if (last != first) extremes.emplace_back(last, j);
  }
  std::sort(extremes.begin(), extremes.end());
  const auto cross = [](const Node& o, const Node& a, const Node& b) {
    return (a.first - o.first) * (b.second - o.second) - (a.second - o.second) * (b.first - o.first);
  };
  std::vector<Node> hull(2 * extremes.size());
  std::size_t h = 0;
  for (const Node& p : extremes) {  // lower hull
    while (h >= 2 && cross(hull[h - 2], hull[h - 1], p) <= 0) --h;
    hull[h++] = p;
  }
  for (std::size_t i = extremes.size() - 1, lower = h + 1; i-- > 0;) {  // upper hull
    const Node& p = extremes[i];
    while (h >= lower && cross(hull[h - 2], hull[h - 1], p) <= 0) --h;
    hull[h++] = p;
  }
  if (h < 4) return {};  // fewer than 3 corners (the last repeats the first)
  hull.resize(h);

  std::vector<std::uint32_t> kept;
  std::vector<std::uint32_t> chain;
  std::vector<long> position;
  for (std::size_t e = 0; e + 1 < hull.size(); ++e) {
    const Node a = hull[e];
    const Node b = hull[e + 1];
    const long di = b.first - a.first;
    const long dj = b.second - a.second;
    const long g = std::gcd(std::abs(di), std::abs(dj));
    chain.clear();
    position.clear();
    for (long s = 0; s <= g; ++s) {
      const auto k = static_cast<std::size_t>((a.second + s * dj / g) * grid.nx + a.first + s * di / g);
      if (!grid.has(k, kValid)) continue;
      grid.flags[k] |= kBoundary;
      chain.push_back(static_cast<std::uint32_t>(k));
      position.push_back(s);
    }
    simplify_chain(grid, chain, position, tolerance_m, kept);
  }
  return kept;
}

// Inserts the outline points (as given) and the loops as constraints. Returns the number of
// vertices CGAL added where constraints cross.
std::size_t insert_outline(Tin& tin, const std::vector<Polyline3>& outline) {
  // Points first, all at once (spatially sorted: no flip cascades along straight edges); the
  // triangulation is empty, so every vertex is an outline point (a repeated one keeps one height).
  std::vector<Point> points;
  for (const Polyline3& loop : outline) {
    for (const Vec3& p : loop) points.emplace_back(p.x(), p.y(), p.z());
  }
  tin.insert(points.begin(), points.end());
  for (auto v = tin.finite_vertices_begin(); v != tin.finite_vertices_end(); ++v) v->info().outline = true;
  for (const Polyline3& loop : outline) {
    points.clear();
    for (const Vec3& p : loop) points.emplace_back(p.x(), p.y(), p.z());
    tin.insert_constraint(points.begin(), points.end(), true);
  }
  std::size_t crossings = 0;
  for (auto v = tin.finite_vertices_begin(); v != tin.finite_vertices_end(); ++v) {
    if (v->info().outline) continue;
    v->info().outline = true;  // on the road edge, at the constraints' interpolated height
    ++crossings;
  }
  return crossings;
}

// Flags every face inside an odd number of outline loops as paved: a flood fill from the
// infinite faces that flips parity across edges covered by an odd number of loop segments.
void mark_paved(Tin& tin) {
  using Key = std::pair<const void*, const void*>;
  const auto key = [](const VertexHandle& a, const VertexHandle& b) {
    const void* pa = &*a;
    const void* pb = &*b;
    return pa < pb ? Key{pa, pb} : Key{pb, pa};
  };
  std::vector<Key> covered;
  for (auto c = tin.constraints_begin(); c != tin.constraints_end(); ++c) {
    auto v = tin.vertices_in_constraint_begin(*c);
    const auto end = tin.vertices_in_constraint_end(*c);
    if (v == end) continue;
    for (auto next = std::next(v); next != end; v = next++) covered.push_back(key(*v, *next));
  }
  std::sort(covered.begin(), covered.end());
  std::vector<Key> odd;
  for (std::size_t i = 0; i < covered.size();) {
    std::size_t j = i;
    while (j < covered.size() && covered[j] == covered[i]) ++j;
    if ((j - i) % 2 == 1) odd.push_back(covered[i]);
    i = j;
  }
  const auto flips = [&](const FaceHandle& f, int i) {
    if (!f->is_constrained(i)) return false;
    return std::binary_search(odd.begin(), odd.end(), key(f->vertex(Tin::cw(i)), f->vertex(Tin::ccw(i))));
  };

  std::vector<FaceHandle> stack{tin.infinite_face()};
  tin.infinite_face()->info().visited = true;
  while (!stack.empty()) {
    const FaceHandle f = stack.back();
    stack.pop_back();
    for (int i = 0; i < 3; ++i) {
      const FaceHandle n = f->neighbor(i);
      if (n->info().visited) continue;
      n->info().visited = true;
      n->info().paved = f->info().paved != flips(f, i);
      stack.push_back(n);
    }
  }
}

// Flags the samples in paved faces (row order keeps the walks short).
void mark_paved_samples(const Tin& tin, GridSamples& grid) {
  FaceHandle hint;
  for (std::size_t k = 0; k < grid.size(); ++k) {
    if (!grid.has(k, kValid)) continue;
    Tin::Locate_type type{};
    int li = 0;
    const FaceHandle f = tin.locate(grid.point(k), type, li, hint);
    hint = f;
    // On an edge: paved only when both sides are (a sample on the road edge is terrain).
    const bool paved = type == Tin::FACE   ? f->info().paved
                       : type == Tin::EDGE ? f->info().paved && f->neighbor(li)->info().paved
                                           : false;
    if (paved) grid.flags[k] |= kPaved;
  }
}

TriangleMesh extract_mesh(const Tin& tin, const GridSamples& grid, bool core, TerrainBuild& build) {
  TriangleMesh mesh;
  mesh.name = "Terrain";
  mesh.kind = SurfaceKind::terrain;
  for (auto v = tin.finite_vertices_begin(); v != tin.finite_vertices_end(); ++v) {
    if (v->info().grid != kNoIndex) ++build.tin_vertices;
  }
  // Mesh index of every vertex of a kept face (sorted by address), numbered in vertex order.
  using Slot = std::pair<const void*, std::uint32_t>;
  std::vector<Slot> index;
  for (auto f = tin.finite_faces_begin(); f != tin.finite_faces_end(); ++f) {
    if (f->info().paved) {
      ++build.triangles_removed;
      continue;
    }
    for (int i = 0; i < 3; ++i) index.emplace_back(&*f->vertex(i), 0);
  }
  std::sort(index.begin(), index.end());
  index.erase(std::unique(index.begin(), index.end()), index.end());
  const auto slot = [&](const VertexHandle& v) {
    const void* key = &*v;
    return std::lower_bound(index.begin(), index.end(), Slot{key, 0},
                            [](const Slot& a, const Slot& b) { return a.first < b.first; });
  };
  for (auto v = tin.finite_vertices_begin(); v != tin.finite_vertices_end(); ++v) {
    const auto it = slot(v);
    if (it == index.end() || it->first != &*v) continue;
    it->second = static_cast<std::uint32_t>(mesh.vertices.size());
    const Point& p = v->point();
    mesh.vertices.emplace_back(p.x(), p.y(), p.z());
    const std::uint32_t k = v->info().grid;
    if (k != kNoIndex && grid.z_target[k] != grid.z_dem[k]) ++build.vertices_on_slopes;
  }
  for (auto f = tin.finite_faces_begin(); f != tin.finite_faces_end(); ++f) {
    if (f->info().paved) continue;
    if (core) build.in_core.push_back(f->info().core == 1);
    mesh.triangles.push_back(
        {slot(f->vertex(0))->second, slot(f->vertex(1))->second, slot(f->vertex(2))->second});
  }
  mesh.normals = vertex_normals(mesh);
  mesh.uvs.reserve(mesh.vertices.size());
  for (const Vec3& p : mesh.vertices) mesh.uvs.emplace_back(p.x() / 10.0, p.y() / 10.0);
  return mesh;
}

}  // namespace

TerrainBuild build_terrain(const DemSampler& dem, const Aabb2& area, const std::vector<Polyline3>& outline,
                           const TerrainOptions& options, const TriangleMesh& decks) {
  check_input(area, outline, options);
  for (const Vec3& p : decks.vertices) {
    if (!p.allFinite()) throw InvalidInput("terrain: a deck has a non-finite point");
  }
  const double step = options.grid_step_m > 0.0 ? options.grid_step_m : dem_resolution_m(dem);

  // 1. The DEM on a regular grid over the area (clipped to where the DEMs are).
  Aabb2 box = area.inflated(options.margin_m);
  const Aabb2 coverage = dem.coverage_bounds();
  box.min = box.min.cwiseMax(coverage.min);
  box.max = box.max.cwiseMin(coverage.max);
  if (coverage.empty() || box.empty())
    throw CoverageError("terrain: the DEMs do not reach the terrain area", 100.0);
  GridSamples grid = sample_grid(dem, box, step);

  TerrainBuild build;
  for (std::size_t k = 0; k < grid.size(); ++k) ++(grid.has(k, kValid) ? build.dem_points : build.dem_voids);
  if (build.dem_points == 0)
    throw CoverageError("terrain: the DEMs have no height in the terrain area", 100.0);

  // 2. Target heights: the DEM, moved onto the cut/fill batter near the road edges.
  apply_batter(grid, outline, options);

  // 3. Triangulation: road edges as constraints, the hull of the samples, paved faces marked.
  const std::vector<std::uint32_t> hull = hull_samples(grid, options.vertical_tolerance_m);
  if (hull.empty())
    throw CoverageError("terrain: the DEMs have heights only along a line in the terrain area", 100.0);
  Tin tin;
  build.outline_crossings = insert_outline(tin, outline);
  FaceHandle hint;
  for (const std::uint32_t k : hull) {
    const VertexHandle v = tin.insert(grid.point(k), hint);
    hint = v->face();
    if (v->info().outline) continue;  // the road edge point stays as given
    v->info().grid = k;
    grid.flags[k] |= kInserted;
  }
  mark_paved(tin);
  mark_paved_samples(tin, grid);
  // A region tile's core lines, before the simplification keeps clear of them.
  CoreLines lines;
  if (options.core) {
    lines = insert_core_lines(tin, grid, dem, *options.core, step, outline, options);
    build.core_line_vertices = lines.line_vertices;
    build.core_detours = lines.detours;
    build.core_blocked = lines.blocked;
  }

  // 4. Simplification within the tolerance, then a check of every sample.
  insert_greedy(tin, grid, options.vertical_tolerance_m);
  const RepairResult check = repair_and_measure(tin, grid, options.vertical_tolerance_m);
  build.max_vertical_error_m = check.max_error_outside_band_m;

  // 5. Cut and fill at the samples of the terrain.
  for (std::size_t k = 0; k < grid.size(); ++k) {
    if (!grid.has(k, kValid) || grid.has(k, kPaved)) continue;
    build.max_cut_m = std::max(build.max_cut_m, grid.z_dem[k] - grid.z_target[k]);
    build.max_fill_m = std::max(build.max_fill_m, grid.z_target[k] - grid.z_dem[k]);
  }
  // 6. Under the decks.
  const UnderDecks under = keep_under_decks(tin, decks, outline, options.deck_clearance_m);
  build.deck_edges_constrained = under.edges_constrained;
  build.vertices_under_decks = under.vertices_lowered;
  if (options.core) build.core_leaks = mark_core_faces(tin, lines, *options.core);
  build.terrain = extract_mesh(tin, grid, options.core.has_value(), build);
  return build;
}

}  // namespace relief
