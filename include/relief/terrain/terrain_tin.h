#pragma once
// Terrain as a TIN: the DEM triangulated (CGAL, Projection_traits_xy_3) and simplified within a
// vertical tolerance, with the paved area's outline inserted as constraints, the triangles under
// the paved area removed, and cut/fill slopes between the road edges and the natural ground, so
// that terrain and roads meet exactly (shared positions) with no hole and no overlap.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "relief/geometry/triangle_mesh.h"
#include "relief/terrain/dem_sampler.h"

namespace relief {

struct TerrainOptions {
  double vertical_tolerance_m = 0.25;  ///< simplified TIN vs DEM, largest vertical error
  double grid_step_m = 0.0;            ///< DEM sampling step; 0 = the DEM's own resolution
  double margin_m = 30.0;              ///< terrain extends this far beyond the area given
  double slope_run_per_rise = 1.5;     ///< cut/fill batter: horizontal metres per metre of height
  double max_slope_width_m = 30.0;     ///< the batter never reaches further than this from a road edge
  /// DEM samples closer than this to the outline never become vertices (no slivers along the
  /// road edges); > 0.
  double constraint_clearance_m = 0.3;
  /// Terrain under a bridge deck stays at least this far below it (a fill slope beside a deck,
  /// or the DEM between its samples, would otherwise rise through it); >= 0.
  double deck_clearance_m = 0.3;
  /// Region tiles: the tile's core (local frame). Its four edges' lines are cut into the
  /// terrain with vertices that depend only on the line, the DEM and the road outline near it,
  /// so that neighbouring tiles' terrain meets along them vertex for vertex, and
  /// TerrainBuild::in_core tells the triangles on the core's side (terrain/core_lines.h).
  std::optional<Aabb2> core;
};

struct TerrainBuild {
  TriangleMesh terrain;                ///< "Terrain"; its hole boundaries are exactly the outline's vertices
  std::size_t dem_points = 0;          ///< DEM samples considered (grid points with a height)
  std::size_t dem_voids = 0;           ///< grid points without a height (skipped)
  std::size_t tin_vertices = 0;        ///< DEM samples kept as vertices (outline points not counted)
  double max_vertical_error_m = 0.0;   ///< measured at the DEM samples outside the slopes
  std::size_t triangles_removed = 0;   ///< under the paved area
  std::size_t outline_crossings = 0;   ///< vertices added where outline loops cross each other
  std::size_t vertices_on_slopes = 0;  ///< moved to a cut/fill batter
  double max_cut_m = 0.0;              ///< natural ground above the batter, largest (at the DEM samples)
  double max_fill_m = 0.0;             ///< natural ground below the batter, largest (at the DEM samples)
  std::size_t deck_edges_constrained = 0;  ///< deck outline edges inserted as constraints
  std::size_t vertices_under_decks = 0;    ///< terrain vertices lowered under a deck
  /// With TerrainOptions::core: per triangle of `terrain`, 1 on the core's side of its lines.
  std::vector<std::uint8_t> in_core;
  std::size_t core_line_vertices = 0;  ///< points of the core's lines inserted
  std::size_t core_detours = 0;        ///< where a line crosses a road edge: to one of its ends
  std::size_t core_blocked = 0;        ///< crossings no end of whose road edge could be reached
  std::size_t core_leaks = 0;          ///< faces reached from both sides of the lines (0: closed)
};

/// Builds the terrain over `area` (local frame) grown by options.margin_m. `outline` are closed
/// loops (first point not repeated) of the paved area that sits on the ground, in 3D: the
/// boundary loops of the ground part of the road mesh, whose exact vertices the terrain takes
/// over. A point inside an odd number of loops is paved. Loops may touch; crossing constraints
/// are split by CGAL (exact predicates; the crossing point, rounded to double, gets the average
/// of the two constraints' interpolated heights). Samples without a DEM height are skipped;
/// triangles may span a void between valid samples. The TIN approximates the DEM moved onto the
/// cut/fill batter, so the batter is refined like any other relief (no fixed densification).
/// `decks` are the road triangles of bridge decks off the ground: the terrain stays
/// options.deck_clearance_m under them (their outline edges become constraints where they keep
/// clear of the road outline, and terrain vertices under them are lowered; max_vertical_error_m
/// is measured before).
/// Throws InvalidInput for options out of range or an outline loop of < 3 (or non-finite)
/// points; CoverageError when the DEM has no height anywhere in the area (or only along a line).
[[nodiscard]] TerrainBuild build_terrain(const DemSampler& dem, const Aabb2& area,
                                         const std::vector<Polyline3>& outline,
                                         const TerrainOptions& options = {}, const TriangleMesh& decks = {});

}  // namespace relief
