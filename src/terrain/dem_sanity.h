#pragma once
// Private to src/terrain: plausibility checks on a window of DEM heights that DemSampler has
// read (metres, NaN = void). They find what a raster's nodata flag does not: fill values it
// never declared (-32768, -9999, 1e30, 3.4e38) and one-cell spikes and pits. The cells found
// become voids (NaN), which the sampler and the elevation sampling then handle exactly like
// the raster's own nodata.

#include <cstddef>
#include <span>
#include <vector>

namespace relief::terrain_detail {

/// Cells one check turned into voids.
struct VoidedCells {
  struct Cell {
    int col = 0;            ///< in the window
    int row = 0;            ///< in the window
    double height_m = 0.0;  ///< the height it had
    double around_m = 0.0;  ///< spikes: median of its valid 8-neighbours; NaN otherwise
  };
  std::size_t count = 0;
  std::vector<Cell> first;  ///< the first few (row-major order), at most the `keep` asked for
};

/// Turns every height outside [min_m, max_m] into a void (+-infinity included; NaN stays a void
/// and is not counted). `z` is row-major with `cols` columns.
VoidedCells void_implausible_heights(std::span<double> z, int cols, double min_m, double max_m,
                                     std::size_t keep);

/// When a one-cell feature is a spike (DemOptions has the same fields, documented there).
struct SpikeCriteria {
  double min_step_m = 30.0;                 ///< the step is always more than this (m)
  double step_per_cell = 1.5;               ///< ... and more than this times the cell size
  double max_neighbour_spread = 1.0 / 3.0;  ///< neighbours' max - min below this times the step
};

/// Turns one-cell spikes and pits into voids. A valid cell is one when its height differs from
/// the median m of its valid 8-neighbours (at least 3 of them) by d > max(min_step_m,
/// step_per_cell * cell_m[row]) while those neighbours agree: max - min < max_neighbour_spread * d.
/// Every cell is judged on the heights as given, then all are voided together: two spike cells
/// side by side see each other as a neighbour that disagrees, so a feature two cells wide is
/// never one. A plane of any slope never is (the median of its 8-neighbours is the centre), nor
/// a cliff edge (the neighbours on its own side hold the median near it), nor a ridge or valley
/// that runs on (the neighbours along it are at its height: their spread is at least d).
/// `z` is row-major with `cols` columns; cell_m has one size (m) per row, > 0.
VoidedCells void_spikes(std::span<double> z, int cols, std::span<const double> cell_m,
                        const SpikeCriteria& criteria, std::size_t keep);

}  // namespace relief::terrain_detail
