// GDAL adapter: status codes and CPL errors become relief exceptions here, at the seam.
#include "terrain/gdal_dataset.h"

#include <cpl_conv.h>
#include <gdal.h>
#include <ogr_srs_api.h>

#include <cmath>
#include <memory>
#include <mutex>
#include <type_traits>
#include <utility>

#include "relief/core/errors.h"
#include "relief/geometry/crs_transform.h"

namespace relief::gdal {
namespace {

void ensure_registered() {
  static std::once_flag once;
  std::call_once(once, [] { GDALAllRegister(); });
}

// Silences GDAL's default stderr handler for the lifetime of the guard and clears the last
// error, so that CPLGetLastErrorMsg() afterwards describes this call only.
class QuietErrors {
 public:
  QuietErrors() {
    CPLErrorReset();
    CPLPushErrorHandler(CPLQuietErrorHandler);
  }
  ~QuietErrors() { CPLPopErrorHandler(); }
  QuietErrors(const QuietErrors&) = delete;
  QuietErrors& operator=(const QuietErrors&) = delete;
};

std::string last_error() {
  const char* message = CPLGetLastErrorMsg();
  return (message != nullptr && *message != '\0') ? message : "unknown GDAL error";
}

bool failed_since_reset() {
  return CPLGetLastErrorType() >= CE_Failure;
}

// True when the bytes of `path` can be read (GDAL virtual file systems included).
bool readable(const std::string& path) {
  VSILFILE* file = VSIFOpenL(path.c_str(), "rb");
  if (file == nullptr) return false;
  VSIFCloseL(file);
  return true;
}

GDALDatasetH as_dataset(void* handle) {
  return static_cast<GDALDatasetH>(handle);
}

struct SrsDeleter {
  void operator()(OGRSpatialReferenceH srs) const { OSRDestroySpatialReference(srs); }
};
using SrsPtr = std::unique_ptr<std::remove_pointer_t<OGRSpatialReferenceH>, SrsDeleter>;

}  // namespace

Dataset Dataset::open_raster(const std::string& path) {
  ensure_registered();
  QuietErrors quiet;
  GDALDatasetH handle = GDALOpenEx(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY | GDAL_OF_VERBOSE_ERROR,
                                   nullptr, nullptr, nullptr);
  if (handle == nullptr) {
    const std::string why = last_error();
    if (!readable(path)) throw IoError("cannot open DEM '" + path + "': " + why);
    throw InvalidInput("DEM '" + path + "' is not a raster GDAL can read: " + why);
  }
  Dataset dataset(handle, path);
  if (GDALGetRasterCount(handle) < 1) {
    throw InvalidInput("DEM '" + path + "' has no raster band");
  }
  return dataset;
}

Dataset Dataset::create_geotiff(const std::string& path, int width, int height, bool int16) {
  ensure_registered();
  QuietErrors quiet;
  GDALDriverH driver = GDALGetDriverByName("GTiff");
  if (driver == nullptr) throw IoError("cannot write '" + path + "': GDAL has no GTiff driver");
  const char* options[] = {"COMPRESS=DEFLATE", nullptr};
  GDALDatasetH handle = GDALCreate(driver, path.c_str(), width, height, 1, int16 ? GDT_Int16 : GDT_Float64,
                                   const_cast<char**>(options));
  if (handle == nullptr) throw IoError("cannot create '" + path + "': " + last_error());
  return Dataset(handle, path);
}

Dataset::~Dataset() {
  if (handle_ != nullptr) {
    QuietErrors quiet;
    GDALClose(as_dataset(handle_));
  }
}

Dataset::Dataset(Dataset&& other) noexcept
    : handle_(std::exchange(other.handle_, nullptr)), path_(std::move(other.path_)) {}

Dataset& Dataset::operator=(Dataset&& other) noexcept {
  if (this != &other) {
    Dataset old(std::move(*this));
    handle_ = std::exchange(other.handle_, nullptr);
    path_ = std::move(other.path_);
  }
  return *this;
}

int Dataset::width() const {
  return GDALGetRasterXSize(as_dataset(handle_));
}
int Dataset::height() const {
  return GDALGetRasterYSize(as_dataset(handle_));
}

GeoTransform Dataset::geo_transform() const {
  QuietErrors quiet;
  GeoTransform gt{};
  if (GDALGetGeoTransform(as_dataset(handle_), gt.data()) != CE_None) {
    throw InvalidInput("DEM '" + path_ + "' is not georeferenced (it has no geotransform)");
  }
  return gt;
}

std::string Dataset::crs_wkt() const {
  QuietErrors quiet;
  OGRSpatialReferenceH srs = GDALGetSpatialRef(as_dataset(handle_));
  if (srs == nullptr) {
    throw InvalidInput("DEM '" + path_ + "' has no coordinate reference system");
  }
  char* wkt = nullptr;
  const char* options[] = {"FORMAT=WKT2_2019", nullptr};
  if (OSRExportToWktEx(srs, &wkt, options) != OGRERR_NONE || wkt == nullptr) {
    CPLFree(wkt);
    throw InvalidInput("cannot express the CRS of DEM '" + path_ + "' as WKT: " + last_error());
  }
  std::string out = wkt;
  CPLFree(wkt);
  return out;
}

std::string Dataset::crs_identifier() const {
  QuietErrors quiet;
  OGRSpatialReferenceH srs = GDALGetSpatialRef(as_dataset(handle_));
  if (srs == nullptr) {
    throw InvalidInput("DEM '" + path_ + "' has no coordinate reference system");
  }
  // The authority of the root node (the CRS itself), e.g. EPSG:4269.
  const char* authority = OSRGetAuthorityName(srs, nullptr);
  const char* code = OSRGetAuthorityCode(srs, nullptr);
  if (authority != nullptr && code != nullptr) return std::string(authority) + ":" + code;
  const char* name = OSRGetName(srs);
  return name != nullptr ? name : "unnamed CRS";
}

BandFacts Dataset::band_facts() const {
  QuietErrors quiet;
  GDALRasterBandH band = GDALGetRasterBand(as_dataset(handle_), 1);
  BandFacts facts;
  int has = 0;
  const double nodata = GDALGetRasterNoDataValue(band, &has);
  if (has != 0) facts.nodata = nodata;
  const double scale = GDALGetRasterScale(band, &has);
  if (has != 0 && scale != 0.0) facts.scale = scale;
  const double offset = GDALGetRasterOffset(band, &has);
  if (has != 0) facts.offset = offset;
  const char* unit = GDALGetRasterUnitType(band);
  if (unit != nullptr) facts.unit_type = unit;
  return facts;
}

std::vector<double> Dataset::read_window(const PixelWindow& window) const {
  if (window.empty()) return {};
  QuietErrors quiet;
  std::vector<double> values(static_cast<std::size_t>(window.cols) * window.rows);
  GDALRasterBandH band = GDALGetRasterBand(as_dataset(handle_), 1);
  if (GDALRasterIO(band, GF_Read, window.col0, window.row0, window.cols, window.rows, values.data(),
                   window.cols, window.rows, GDT_Float64, 0, 0) != CE_None) {
    throw IoError("cannot read DEM '" + path_ + "': " + last_error());
  }
  return values;
}

void Dataset::set_geo_transform(const GeoTransform& gt) {
  QuietErrors quiet;
  GeoTransform copy = gt;
  if (GDALSetGeoTransform(as_dataset(handle_), copy.data()) != CE_None) {
    throw IoError("cannot write the geotransform of '" + path_ + "': " + last_error());
  }
}

void Dataset::set_crs(const std::string& crs) {
  QuietErrors quiet;
  const SrsPtr srs(OSRNewSpatialReference(nullptr));
  if (OSRSetFromUserInput(srs.get(), crs.c_str()) != OGRERR_NONE) {
    throw ProjectionError("unknown coordinate reference system '" + crs + "': " + last_error());
  }
  if (GDALSetSpatialRef(as_dataset(handle_), srs.get()) != CE_None) {
    throw IoError("cannot write the CRS of '" + path_ + "': " + last_error());
  }
}

void Dataset::set_nodata(double nodata) {
  QuietErrors quiet;
  if (GDALSetRasterNoDataValue(GDALGetRasterBand(as_dataset(handle_), 1), nodata) != CE_None) {
    throw IoError("cannot write the nodata value of '" + path_ + "': " + last_error());
  }
}

void Dataset::set_unit_type(const std::string& unit_type) {
  QuietErrors quiet;
  if (GDALSetRasterUnitType(GDALGetRasterBand(as_dataset(handle_), 1), unit_type.c_str()) != CE_None) {
    throw IoError("cannot write the unit type of '" + path_ + "': " + last_error());
  }
}

void Dataset::write_band(const std::vector<double>& values) {
  QuietErrors quiet;
  const int w = width();
  const int h = height();
  std::vector<double> copy = values;  // GDALRasterIO takes a non-const buffer
  GDALRasterBandH band = GDALGetRasterBand(as_dataset(handle_), 1);
  if (GDALRasterIO(band, GF_Write, 0, 0, w, h, copy.data(), w, h, GDT_Float64, 0, 0) != CE_None) {
    throw IoError("cannot write '" + path_ + "': " + last_error());
  }
}

void Dataset::close() {
  if (handle_ == nullptr) return;
  QuietErrors quiet;
  GDALClose(as_dataset(std::exchange(handle_, nullptr)));
  if (failed_since_reset()) throw IoError("cannot finish writing '" + path_ + "': " + last_error());
}

DemInfo describe_dem(const Dataset& dataset, std::optional<VerticalUnit> unit) {
  DemInfo info;
  info.path = dataset.path();
  const GeoTransform gt = dataset.geo_transform();
  if (gt[2] != 0.0 || gt[4] != 0.0) {
    throw InvalidInput("DEM '" + info.path + "' is rotated or sheared (geotransform rotation terms " +
                       std::to_string(gt[2]) + ", " + std::to_string(gt[4]) +
                       "); only north-up rasters are supported: warp it first (gdalwarp)");
  }
  if (gt[1] == 0.0 || gt[5] == 0.0) {
    throw InvalidInput("DEM '" + info.path + "' has a zero pixel size in its geotransform");
  }
  info.crs_wkt = dataset.crs_wkt();
  info.crs = dataset.crs_identifier();
  info.width = dataset.width();
  info.height = dataset.height();
  info.pixel_size = Vec2(std::abs(gt[1]), std::abs(gt[5]));
  info.extent.extend(Vec2(gt[0], gt[3]));
  info.extent.extend(Vec2(gt[0] + info.width * gt[1], gt[3] + info.height * gt[5]));
  try {
    info.extent_wgs84 = [&] {
      const Aabb2 box = CrsTransform(info.crs_wkt, "EPSG:4326").transform_bounds(info.extent);
      return LonLatBox{box.min.x(), box.min.y(), box.max.x(), box.max.y()};
    }();
  } catch (const ProjectionError&) {
    // A CRS without a path to WGS84 (e.g. a local engineering CRS): extent stays unknown.
  }

  const BandFacts facts = dataset.band_facts();
  info.nodata = facts.nodata;
  info.scale = facts.scale;
  info.offset = facts.offset;
  if (unit) {
    info.unit = *unit;
    info.unit_stated_by_user = true;
  } else if (!facts.unit_type.empty()) {
    const auto stated = parse_vertical_unit(facts.unit_type);
    if (!stated) {
      throw InvalidInput("DEM '" + info.path + "' states the vertical unit '" + facts.unit_type +
                         "', which relief does not know: state the unit (m, ft or us-ft) explicitly");
    }
    info.unit = *stated;
    info.unit_from_metadata = true;
  }
  return info;
}

}  // namespace relief::gdal
