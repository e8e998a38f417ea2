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

struct DemOptions {
  /// Vertical unit of every raster, overriding its metadata (the SF south quadrangle is in feet
  /// and does not say so). Unset: taken from the raster's unit type, metres when it has none.
  std::optional<VerticalUnit> unit;
  Interpolation interpolation = Interpolation::bilinear;
  /// Extra margin around the requested area read from each raster (metres).
  double margin_m = 100.0;
};

/// Heights in metres at points of the local frame.
///
/// Mosaic rule: rasters are tried in the order given; the first one that yields a valid height
/// at a point wins (a void in the first falls through to the next).
///
/// Interpolation between cell centres:
/// - bilinear: weights of the four surrounding cell centres; nodata corners are dropped and the
///   remaining weights renormalised; no valid corner -> no height.
/// - idw: the seed paper's inverse-distance weighting of the same four cells, weight 1/d^2
///   (d to each cell centre, exact hit returns that cell).
/// - nearest: the cell containing the point.
/// Within half a pixel of the raster border, the border cells are used (clamped). Outside the
/// raster: no height.
class DemSampler {
 public:
  /// Opens every raster in `paths` and reads the part covering `area` (local frame) plus
  /// options.margin_m. Throws IoError (missing/unreadable file: the message names it),
  /// InvalidInput (no georeferencing, a raster that is all nodata in the area), ProjectionError.
  /// Reports a warning to `diagnostics` when a more accurate datum transformation needs a grid
  /// that is not installed.
  DemSampler(const std::vector<std::string>& paths, const GeoFrame& frame, const Aabb2& area,
             const DemOptions& options = {}, Diagnostics* diagnostics = nullptr);
  ~DemSampler();
  DemSampler(DemSampler&&) noexcept;
  DemSampler& operator=(DemSampler&&) noexcept;

  /// Height at one point, or nullopt where no raster has a valid value.
  [[nodiscard]] std::optional<double> height_at(const Vec2& local) const;
  /// Heights at many points (much faster: one PROJ call per raster). out.size() == points.size().
  void heights_at(std::span<const Vec2> points, std::span<std::optional<double>> out) const;
  /// Gradient dz/dx, dz/dy (dimensionless) of the interpolated surface at a point, by central
  /// differences over `step_m`; nullopt where any of the four probes has no height.
  [[nodiscard]] std::optional<Vec2> gradient_at(const Vec2& local, double step_m = 0.5) const;

  [[nodiscard]] const std::vector<DemInfo>& sources() const;
  [[nodiscard]] Interpolation interpolation() const;
  /// Area (local frame) covered by the union of the rasters' extents (bounding box).
  [[nodiscard]] Aabb2 coverage_bounds() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Opens a raster and reports what relief would use, without reading its pixels.
/// Throws IoError / InvalidInput like DemSampler.
[[nodiscard]] DemInfo inspect_dem(const std::string& path, const DemOptions& options = {});

}  // namespace relief
