#pragma once
// Coordinate transformation between two CRSs, backed by PROJ (kept out of this header).
// Axis order is always x = easting/longitude, y = northing/latitude (PROJ's
// "normalize for visualization"), whatever the CRS's official axis order.

#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "relief/geometry/types.h"

namespace relief {

class CrsTransform {
 public:
  /// `from` and `to` are anything PROJ accepts: "EPSG:4326", a WKT string, a PROJ string.
  /// `area` (WGS84 degrees), when given, lets PROJ pick the most accurate operation for it.
  /// Throws ProjectionError if either CRS is unknown or no operation exists.
  CrsTransform(std::string_view from, std::string_view to, std::optional<LonLatBox> area = std::nullopt);
  ~CrsTransform();
  CrsTransform(CrsTransform&& other) noexcept;
  CrsTransform& operator=(CrsTransform&& other) noexcept;
  CrsTransform(const CrsTransform&) = delete;
  CrsTransform& operator=(const CrsTransform&) = delete;

  /// Transforms one point; throws ProjectionError when PROJ cannot (point outside the domain).
  [[nodiscard]] Vec2 apply(const Vec2& p) const;
  /// Transforms points in place; points PROJ cannot transform become NaN (no throw).
  void apply(std::span<Vec2> points) const;
  /// The inverse direction, same conventions.
  [[nodiscard]] Vec2 apply_inverse(const Vec2& p) const;

  /// Box in the target CRS that contains the transformed box (edges densified).
  [[nodiscard]] Aabb2 transform_bounds(const Aabb2& box) const;

  /// Name of the operation PROJ chose, e.g. "Inverse of UTM zone 10N + NAD27 to WGS 84 (6) ...".
  [[nodiscard]] const std::string& operation_name() const;
  /// Stated accuracy of that operation in metres, if PROJ knows it (0 for exact conversions).
  [[nodiscard]] std::optional<double> accuracy_m() const;
  /// True when a more accurate operation exists but needs a grid file that is not installed.
  [[nodiscard]] bool better_operation_missing_grid() const;
  /// Grids named by that more accurate operation (e.g. "us_noaa_conus.tif").
  [[nodiscard]] const std::string& missing_grids() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// PROJ's identifier of `crs` ("EPSG:26710") or its name when it has no authority code.
[[nodiscard]] std::string crs_identifier(std::string_view crs);

/// PROJ string of `crs` ("+proj=utm +zone=10 +datum=WGS84 +units=m +no_defs").
[[nodiscard]] std::string crs_proj_string(std::string_view crs);

}  // namespace relief
