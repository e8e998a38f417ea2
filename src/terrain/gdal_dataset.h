#pragma once
// Private GDAL adapter of the terrain module: the only place that talks to GDAL. Every GDAL
// failure becomes a relief::IoError / InvalidInput / ProjectionError here, with the file and
// GDAL's own message (CPLGetLastErrorMsg); GDAL never prints to stderr from within relief.
// Nothing of GDAL leaks out of this header: handles are opaque pointers.

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "relief/terrain/dem_source.h"

namespace relief::gdal {

/// GDAL's affine geotransform: x = gt[0] + col*gt[1] + row*gt[2], y = gt[3] + col*gt[4] + row*gt[5]
/// (col, row at pixel corners).
using GeoTransform = std::array<double, 6>;

/// Facts about band 1 that decide how its raw values become metres.
struct BandFacts {
  std::optional<double> nodata;  ///< raw nodata value, when the band has one
  double scale = 1.0;            ///< raw * scale + offset = value in `unit_type`
  double offset = 0.0;
  std::string unit_type;  ///< as the raster states it ("m", "ft", "" when unstated)
};

/// A window of band 1 in pixels: columns [col0, col0 + cols), rows [row0, row0 + rows).
struct PixelWindow {
  int col0 = 0;
  int row0 = 0;
  int cols = 0;
  int rows = 0;
  [[nodiscard]] bool empty() const { return cols <= 0 || rows <= 0; }
};

/// An open GDAL dataset (RAII over GDALDatasetH). Move-only.
class Dataset {
 public:
  /// Opens a raster read-only; `path` may be any GDAL path, /vsizip/... included.
  /// Throws IoError when the file does not exist or cannot be read ("cannot open DEM 'path': ..."),
  /// InvalidInput when it is readable but not a raster GDAL understands, or has no band.
  [[nodiscard]] static Dataset open_raster(const std::string& path);

  /// Creates a one-band GeoTIFF of `width` x `height` pixels, Float64 or (int16) Int16 samples
  /// (GTiff driver chosen explicitly, so the file name's extension does not matter). Throws IoError.
  [[nodiscard]] static Dataset create_geotiff(const std::string& path, int width, int height,
                                              bool int16 = false);

  ~Dataset();
  Dataset(Dataset&& other) noexcept;
  Dataset& operator=(Dataset&& other) noexcept;
  Dataset(const Dataset&) = delete;
  Dataset& operator=(const Dataset&) = delete;

  [[nodiscard]] const std::string& path() const { return path_; }
  [[nodiscard]] int width() const;
  [[nodiscard]] int height() const;

  /// The geotransform; throws InvalidInput when the raster has none (not georeferenced).
  [[nodiscard]] GeoTransform geo_transform() const;
  /// WKT2 of the raster's CRS; throws InvalidInput when the raster has none.
  [[nodiscard]] std::string crs_wkt() const;
  /// "EPSG:4269" when the CRS has an authority code, else the CRS's name.
  [[nodiscard]] std::string crs_identifier() const;
  [[nodiscard]] BandFacts band_facts() const;

  /// Reads `window` of band 1 as doubles, row-major, raw values (no nodata, scale or unit
  /// handling). Throws IoError when GDAL cannot read it (corrupt file).
  [[nodiscard]] std::vector<double> read_window(const PixelWindow& window) const;

  // Writing (datasets made by create_geotiff).
  void set_geo_transform(const GeoTransform& gt);
  /// `crs` is anything OSRSetFromUserInput accepts ("EPSG:32610", WKT, PROJ string);
  /// throws ProjectionError when it is unknown.
  void set_crs(const std::string& crs);
  void set_nodata(double nodata);
  void set_unit_type(const std::string& unit_type);
  /// Writes all of band 1 (row-major, width*height values; GDAL rounds them to an integer band).
  void write_band(const std::vector<double>& values);
  /// Flushes and closes the file; throws IoError when GDAL reports an error while doing so.
  void close();

 private:
  Dataset(void* handle, std::string path) : handle_(handle), path_(std::move(path)) {}
  void* handle_ = nullptr;  // GDALDatasetH
  std::string path_;
};

/// What relief learns from an open raster (everything in DemInfo except the transformation
/// fields, which depend on the frame). Applies options.unit, else the raster's unit type.
/// Throws InvalidInput for rotated/sheared rasters or a unit type relief does not know.
[[nodiscard]] DemInfo describe_dem(const Dataset& dataset, std::optional<VerticalUnit> unit);

}  // namespace relief::gdal
