#pragma once
// Description of one elevation raster as relief sees it: where it is, its CRS, grid, vertical
// unit and nodata. Reading is done by DemSampler (dem_sampler.h); GDAL stays out of headers.

#include <cstddef>
#include <optional>
#include <string>

#include "relief/geometry/types.h"

namespace relief {

enum class VerticalUnit { metre, foot, us_survey_foot };

/// Metres per unit: 1, 0.3048, 1200/3937.
[[nodiscard]] double metres_per_unit(VerticalUnit unit);
/// "m", "ft", "us-ft".
[[nodiscard]] std::string to_string(VerticalUnit unit);
/// Parses "m", "metre", "meter", "ft", "foot", "feet", "us-ft", "us_survey_foot" (case-insensitive;
/// also plurals, "US survey foot" and "ftUS" as GDAL may report them). nullopt otherwise.
[[nodiscard]] std::optional<VerticalUnit> parse_vertical_unit(std::string_view text);

enum class Interpolation { bilinear, idw, nearest };
[[nodiscard]] std::string to_string(Interpolation interpolation);
[[nodiscard]] std::optional<Interpolation> parse_interpolation(std::string_view text);

/// What relief learned about one raster when opening it.
struct DemInfo {
  std::string path;
  std::string crs;                        ///< "EPSG:4269" or the CRS name
  std::string crs_wkt;                    ///< full WKT as GDAL reports it
  int width = 0;                          ///< pixels
  int height = 0;                         ///< pixels
  Vec2 pixel_size{0.0, 0.0};              ///< in CRS units (degrees or metres), both positive
  Aabb2 extent;                           ///< raster extent in its own CRS (x = lon/easting)
  std::optional<LonLatBox> extent_wgs84;  ///< the same, in WGS84 degrees
  VerticalUnit unit = VerticalUnit::metre;
  /// false: the raster said nothing and metres were assumed, or the user stated it.
  bool unit_from_metadata = false;
  bool unit_stated_by_user = false;
  std::optional<double> nodata;  ///< raw nodata value of band 1
  double scale = 1.0;            ///< band scale (applied before the unit)
  double offset = 0.0;           ///< band offset
  /// PROJ operation used from the local frame to this CRS (set by DemSampler).
  std::string transform_name;
  std::optional<double> transform_accuracy_m;
  std::string missing_grids;  ///< grids of a more accurate operation that are not installed
  /// Cells of the part read (area + margin) that DemSampler made voids (DemOptions): heights
  /// outside the plausible range, and one-cell spikes and pits. 0 when no pixel was read.
  std::size_t implausible_cells = 0;
  std::size_t spike_cells = 0;
  /// With DemOptions::ground_filter_m: cells of the part read set down to the ground (standing
  /// out of it: buildings, trees) and raised to it (narrow pits).
  std::size_t off_ground_cells = 0;
};

}  // namespace relief
