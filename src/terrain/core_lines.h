#pragma once
// Private to src/terrain: the terrain of a region tile, cut along its core's edges so that
// neighbouring tiles' terrain meets vertex for vertex. Each edge's line (x = const or y = const,
// across the terrain) becomes a chain of constraints whose vertices depend only on the line, the
// DEM and the road outline near it: points at whole multiples of the DEM step (where the other
// lines cross it, and 0.5, 1, 2... m from each road edge it crosses), at the DEM's height moved
// onto the batter like any sample (where the DEM has no height, in a void or beyond its edge,
// the nearest valid heights around the point: the terrain may still reach the line there).
// Where the line crosses a road edge the chain leaves it for an end of that edge (an outline
// vertex, which both tiles share), so the terrain meets the roads as in any build (no vertex on a
// road edge), and goes on straight across the paved area to the next edge's end. The TIN's own
// vertices keep clear of the chains, so the simplification (which differs between windows)
// neither moves nor splits them. The faces are then told inside or outside the core by the side
// of the chains they lie on.

#include <cstddef>
#include <vector>

#include "relief/terrain/dem_sampler.h"
#include "relief/terrain/terrain_tin.h"
#include "terrain/terrain_cdt.h"

namespace relief::terrain_detail {

/// One inserted piece of a line's chain: a constraint from `a` to `b`, directed along its line
/// (increasing coordinate).
struct CoreSeparator {
  Tin::Constraint_id id;
  Vec2 a, b;     ///< its ends in plan
  int line = 0;  ///< 0, 1: x = core.min.x, core.max.x; 2, 3: y = core.min.y, core.max.y
};

struct CoreLines {
  std::vector<CoreSeparator> separators;
  std::size_t line_vertices = 0;  ///< points of the lines inserted
  std::size_t detours = 0;        ///< chain ends moved to a road edge's vertex
  std::size_t blocked = 0;        ///< crossings where no end of the road edge could be reached
};

/// Inserts the four lines of `core` into `tin` (after the outline, the hull and the paved
/// marking; before the simplification) and flags the samples within `o.constraint_clearance_m`
/// of them kNear, so that no later vertex falls on them. `step` is the DEM step the points are
/// spaced by.
CoreLines insert_core_lines(Tin& tin, GridSamples& grid, const DemSampler& dem, const Aabb2& core,
                            double step, const std::vector<Polyline3>& outline, const TerrainOptions& o);

/// Sets FaceData::core on the finished `tin` (1: on the core's side of all four chains; the
/// faces no chain reaches by their centroid, in the half-open core). Returns how often a flood
/// from one side of a chain met the other side's (0 when the chains close).
std::size_t mark_core_faces(Tin& tin, const CoreLines& lines, const Aabb2& core);

}  // namespace relief::terrain_detail
