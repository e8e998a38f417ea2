#pragma once
// Height queries on one or several DEM rasters (a mosaic) in the local frame.
// Rasters are read with GDAL in their own CRS; query points are transformed from the frame's
// CRS with PROJ (datum shifts included). Only the window of each raster that covers the
// requested area is read into memory.

#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "relief/core/diagnostics.h"
#include "relief/geometry/geo_frame.h"
#include "relief/terrain/dem_source.h"

namespace relief {

/// What an interpolation does with a void among the cells it weighs (bilinear, idw).
enum class NearVoid {
  /// The void is dropped and the other weights renormalised: a height wherever one valid cell
  /// is near, but one that jumps, at the void's centre, from one neighbour's height to the
  /// other's (149 m at an SRTM void on a steep Liechtenstein path: a 37 717 % grade).
  renormalise,
  /// No height: the point counts as in the void (continuous wherever it has a height).
  no_height,
};

struct DemOptions {
  /// Vertical unit of every raster, overriding its metadata (the SF south quadrangle is in feet
  /// and does not say so). Unset: taken from the raster's unit type, metres when it has none.
  std::optional<VerticalUnit> unit;
  Interpolation interpolation = Interpolation::bilinear;
  /// Extra margin around the requested area read from each raster (metres).
  double margin_m = 100.0;

  /// Plausible heights (metres, after scale, offset and unit): a cell outside
  /// [plausible_min_m, plausible_max_m] is a void. It catches fill values a raster does not
  /// flag as nodata (-32768, -9999, 1e30, 3.4e38). The defaults hold every land surface (Dead
  /// Sea shore -430 m, Everest 8849 m); lower plausible_min_m for a bathymetric raster. Either
  /// may be infinite; plausible_min_m < plausible_max_m.
  double plausible_min_m = -500.0;
  double plausible_max_m = 9000.0;

  /// One-cell spikes and pits are voids: a valid cell whose height differs from the median of
  /// its valid 8-neighbours (at least 3) by d > max(spike_min_step_m, spike_step_per_cell *
  /// cell size) while those neighbours agree among themselves (max - min <
  /// spike_max_neighbour_spread * d). The cell size is the longer side of the cell in metres
  /// (a geographic raster's degrees measured at the cell's latitude). With the defaults: a
  /// 30 m step on a 10 m DEM, 135 m on a 90 m SRTM cell, i.e. a summit or a pit one cell wide
  /// whose sides fall at over 72 degrees (10 m cells) or 56 degrees (cells of 20 m and more)
  /// all round, which no terrain sampled at that resolution has. A plane of any slope (its
  /// neighbours' median is the centre), a cliff, and a ridge or valley that runs on (the
  /// neighbours along it agree with it) are never spikes, nor is any feature two cells wide.
  /// spike_min_step_m >= 0 (infinity turns the check off), spike_step_per_cell >= 0,
  /// 0 < spike_max_neighbour_spread <= 1.
  double spike_min_step_m = 30.0;
  double spike_step_per_cell = 1.5;
  double spike_max_neighbour_spread = 1.0 / 3.0;

  /// The rasters are surface models (DSM: buildings, trees, radar artefacts in them): > 0
  /// takes the ground back with a grey opening and then a closing over a flat window of about
  /// ground_filter_m x ground_filter_m (2 r + 1 cells a side, r = max(1, floor(ground_filter_m /
  /// 2 / cell size)) along each axis, the cell size in metres at the window's centre); a cell
  /// differing from the result by more than ground_filter_min_height_m takes it (reported as
  /// "dem.ground_filtered"). Anything narrower than the window standing out of the ground
  /// (a building, a pit) is taken out, on a slope to within the slope over its width; a plane
  /// of any slope, and any feature wider than the window, are kept; a crest or a valley
  /// narrower than the window is cut too, which is why it is off (0) for a bare-earth DEM. The
  /// window read around the area grows by 2 x ground_filter_m, so that the filter over the area
  /// does not depend on where the read stops (tiles of a region filter their shared ground
  /// alike) unless a void reaches from the area to the edge of the read (each pass bridges a
  /// void along its row or column). ground_filter_m finite >= 0, ground_filter_min_height_m
  /// finite >= 0.
  double ground_filter_m = 0.0;
  double ground_filter_min_height_m = 2.0;
};

/// Heights in metres at points of the local frame.
///
/// Mosaic rule: rasters are tried in the order given; the first one that yields a valid height
/// at a point wins (a void in the first falls through to the next).
///
/// Interpolation between cell centres, in the raster's own index space (fractional pixel
/// coordinates; for a geographic raster that is bilinear in lon/lat):
/// - bilinear: weights of the four surrounding cell centres; nodata corners are dropped and the
///   remaining weights renormalised (NearVoid::renormalise; with NearVoid::no_height a nodata
///   corner of weight > 0 gives no height, as the road samples take it); no valid corner -> no
///   height. (A point exactly at the
///   centre of a void cell has no height: its valid neighbours all have weight 0.)
/// - idw: the seed paper's inverse-distance weighting of the same four cells, weight 1/d^2
///   (d to each cell centre in the raster's CRS units, degrees for a geographic raster; an
///   exact hit on a valid cell returns that cell).
/// - nearest: the cell containing the point.
/// Within half a pixel of the raster border, the border cells are used (clamped). Outside the
/// raster: no height. Heights are band values * scale + offset, converted to metres; the band's
/// nodata value and NaN are voids, and so are the cells DemOptions finds implausible (outside
/// the plausible range, one-cell spikes and pits).
///
/// Only `area` + margin_m (+ 2 pixels) of each raster is read: a point farther out may have no
/// height even where a raster covers it. Inside that area, frame -> raster CRS coordinates come
/// from a grid of PROJ-transformed nodes interpolated bilinearly, kept only when it agrees with
/// PROJ to 1e-4 pixel at every cell centre (1 mm on a 10 m DEM); other points go through PROJ.
///
/// Queries are const but share PROJ state: use one DemSampler per thread.
class DemSampler {
 public:
  /// Opens every raster in `paths` (any GDAL path, /vsizip/... included) and reads the part
  /// covering `area` (local frame) plus options.margin_m. A raster that does not reach the area
  /// or is all nodata there contributes nothing. Throws
  /// - IoError: a missing or unreadable file ("cannot open DEM '<path>': <GDAL's reason>");
  /// - InvalidInput: a readable file that is not a raster GDAL knows (a text file named .tif),
  ///   no geotransform, no CRS, a rotated/sheared geotransform, a band unit type relief does not
  ///   know (state options.unit), no path, an empty area, margin_m < 0, plausible, spike or
  ///   ground filter options out of their ranges (see DemOptions); and when no raster has a valid height over
  ///   the area because they are all nodata there ("... is all nodata over the roads' area",
  ///   naming the implausible cells when there are some: a wrong unit?);
  /// - CoverageError (uncovered_percent() == 100) when no raster intersects the area at all
  ///   (the message gives the DEM extents and the area in lon/lat);
  /// - ProjectionError: a CRS PROJ does not know, no transformation to a raster's CRS.
  /// Reports a warning "dem.datum_grid_missing" to `diagnostics` when a more accurate datum
  /// transformation needs a grid that is not installed (naming the grid and the accuracy of
  /// the operation used instead). Reports one warning per raster and kind when cells of the
  /// part read become voids: "dem.implausible_height" (outside the plausible range) and
  /// "dem.spike" (one-cell spikes and pits), each with the count and the first cells' lon/lat,
  /// pixel/line and height; their counts are in sources() (DemInfo::implausible_cells,
  /// spike_cells). With a ground filter, one info "dem.ground_filtered" per raster (the cells
  /// set down and raised, the largest change and where; DemInfo::off_ground_cells).
  DemSampler(const std::vector<std::string>& paths, const GeoFrame& frame, const Aabb2& area,
             const DemOptions& options = {}, Diagnostics* diagnostics = nullptr);
  ~DemSampler();
  DemSampler(DemSampler&& other) noexcept;
  DemSampler& operator=(DemSampler&& other) noexcept;

  /// Height at one point, or nullopt where no raster has a valid value.
  [[nodiscard]] std::optional<double> height_at(const Vec2& local) const;
  /// Heights at many points (much faster than one by one). out.size() == points.size(), else
  /// InvalidInput. Non-finite points get no height. `near_void` for a point whose interpolation
  /// weighs a void cell (with no_height, the next raster of the mosaic is tried).
  void heights_at(std::span<const Vec2> points, std::span<std::optional<double>> out,
                  NearVoid near_void = NearVoid::renormalise) const;
  /// Gradient dz/dx, dz/dy (dimensionless) of the interpolated surface at a point, by central
  /// differences over `step_m` (> 0, else InvalidInput); nullopt where any of the four probes
  /// has no height.
  [[nodiscard]] std::optional<Vec2> gradient_at(const Vec2& local, double step_m = 0.5) const;

  /// Every raster given, in order, with the transformation used for it.
  [[nodiscard]] const std::vector<DemInfo>& sources() const;
  [[nodiscard]] Interpolation interpolation() const;
  /// Area (local frame) covered by the union of the extents of the rasters that contribute
  /// heights (bounding box of their edges transformed back to the frame).
  [[nodiscard]] Aabb2 coverage_bounds() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Opens a raster and reports what relief would use, without reading its pixels (the
/// transform_* and missing_grids fields stay empty: they depend on a frame).
/// Throws IoError / InvalidInput like DemSampler.
[[nodiscard]] DemInfo inspect_dem(const std::string& path, const DemOptions& options = {});

}  // namespace relief
