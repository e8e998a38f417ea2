#pragma once
// Private to src/terrain: the ground under a surface model. A DSM (SRTM over a city, a photo or
// radar surface) holds buildings, trees and radar artefacts: in San Francisco's Financial
// District 1-arc-second cells stand up to 100 m over the streets beside them and fall 20 m
// below the bay. A road fitted to that climbs every tower. The ground is taken back by grey
// morphology, as off-terrain-object filters do (Zhang et al. 2003, "A progressive morphological
// filter for removing nonground measurements"; WhiteboxTools' RemoveOffTerrainObjects): an
// opening (erosion, then dilation) removes every bump narrower than its window, a closing
// (dilation, then erosion) every pit; a plane of any slope, and any feature wider than the
// window, pass both unchanged.

#include <cstddef>
#include <span>

namespace relief::terrain_detail {

/// What filter_off_ground changed.
struct GroundFiltered {
  std::size_t lowered = 0;      ///< cells standing out of the ground (buildings, trees), set down to it
  std::size_t raised = 0;       ///< cells in narrow pits, raised to the ground around them
  double largest_m = 0.0;       ///< the largest change
  double largest_from_m = 0.0;  ///< the height the cell of the largest change had
  int largest_col = -1;         ///< where (in the window), -1 when nothing changed
  int largest_row = -1;
};

/// Runs an opening and then a closing over `z` (row-major, `cols` columns, metres, NaN = void)
/// with a flat rectangular window of (2 radius_cols + 1) x (2 radius_rows + 1) cells, and sets
/// each valid cell that differs from the result by more than `min_height_m` to it; the others
/// keep their heights and voids stay voids. The window is separable: each pass runs along the
/// rows or the columns, where a run of voids takes the straight line between its valid ends
/// and the line is reflected through its end values beyond the grid (v(-k) = 2 v(0) - v(k)):
/// so a plane of any slope is kept exactly, up to the grid's edges and around its voids.
/// Linear in the cells whatever the window (van Herk / Gil-Werman running extrema).
/// radius_* >= 0, min_height_m >= 0.
GroundFiltered filter_off_ground(std::span<double> z, int cols, int radius_cols, int radius_rows,
                                 double min_height_m);

}  // namespace relief::terrain_detail
