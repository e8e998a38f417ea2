#pragma once
// Private to src/terrain: the terrain TIN refined until it follows the DEM samples within a
// vertical tolerance (greedy insertion, then a check of every sample that repairs what the greedy
// phase missed). The TIN and the samples are terrain_cdt.h's.

#include <cstddef>

#include "terrain/terrain_cdt.h"

namespace relief::terrain_detail {

/// Simplification of the samples not yet in `tin` (flags kValid, not kPaved/kNear/kBoundary/
/// kInserted) by greedy insertion: the sample of largest vertical error (against z_target) is
/// inserted until every error is within tolerance_m. Points are kept in the face containing them
/// and moved only when that face is destroyed (Garland & Heckbert 1995, "Fast polygonal
/// approximation of terrains and height fields", algorithm III). Returns the vertices inserted.
std::size_t insert_greedy(Tin& tin, GridSamples& grid, double tolerance_m);

struct RepairResult {
  std::size_t inserted = 0;               ///< samples added by the repair passes
  double max_error_m = 0.0;               ///< against z_target, over every sample that may be a vertex
  double max_error_outside_band_m = 0.0;  ///< against the DEM, samples outside the slope band
};

/// Checks every sample outside the paved area against the TIN and, while some that may become
/// vertices err by more than tolerance_m, inserts the worst one of each face (a safety net for
/// errors the greedy phase cannot see, e.g. along the hull). Faces created are not paved.
RepairResult repair_and_measure(Tin& tin, GridSamples& grid, double tolerance_m);

}  // namespace relief::terrain_detail
