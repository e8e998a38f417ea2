#pragma once
// Writes a regular grid of heights as a GeoTIFF. Used to make the synthetic DEMs of the tests
// and fixtures (analytic surfaces with known answers).

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "relief/geometry/types.h"

namespace relief {

/// Sample type of the band written. SRTM and most national DEMs are Int16 whole metres with
/// nodata -32768; relief's own synthetic DEMs default to Float64 so that analytic surfaces
/// come back exactly.
enum class DemDataType { float64, int16 };

/// A north-up grid. Cell (col, row) covers x in [x0 + col*dx, x0 + (col+1)*dx] and
/// y in [y0 - (row+1)*dy, y0 - row*dy]; its value applies at the cell centre.
struct DemGrid {
  std::string crs = "EPSG:32610";
  double x0 = 0.0;  ///< west edge (CRS units)
  double y0 = 0.0;  ///< north edge (CRS units)
  double dx = 1.0;  ///< pixel width, > 0
  double dy = 1.0;  ///< pixel height, > 0
  int width = 0;
  int height = 0;
  std::vector<double> values;    ///< row-major, row 0 is the northernmost
  std::optional<double> nodata;  ///< written as the band's nodata value
  std::string unit_type;         ///< band unit type ("m", "ft", or empty: unstated)
  DemDataType data_type = DemDataType::float64;

  /// Centre of cell (col, row) in CRS units.
  [[nodiscard]] Vec2 cell_centre(int col, int row) const {
    return {x0 + (col + 0.5) * dx, y0 - (row + 0.5) * dy};
  }
};

/// Grid whose value at each cell centre is f(x, y) (CRS units). Throws InvalidInput unless
/// dx, dy, width and height are > 0.
[[nodiscard]] DemGrid make_dem_grid(std::string crs, double x0, double y0, double dx, double dy, int width,
                                    int height, const std::function<double(double, double)>& f);

/// Writes `grid` as a GeoTIFF of grid.data_type (atomically: to `path`.tmp-N.tif, then renamed;
/// the temporary is removed on failure). Int16 values are rounded to the nearest integer.
/// Throws IoError (cannot create, write or rename), ProjectionError (grid.crs unknown),
/// InvalidInput (values.size() != width * height, a non-positive size, or for Int16 a value or
/// nodata that is not finite or lies outside -32768..32767 after rounding).
void write_geotiff(const std::string& path, const DemGrid& grid);

}  // namespace relief
