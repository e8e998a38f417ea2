#include "relief/terrain/dem_writer.h"

#include <cmath>
#include <filesystem>
#include <random>
#include <system_error>

#include "relief/core/errors.h"
#include "terrain/gdal_dataset.h"

namespace relief {
namespace {

void check_grid_shape(double dx, double dy, int width, int height) {
  if (!(dx > 0.0) || !(dy > 0.0) || width <= 0 || height <= 0) {
    throw InvalidInput("a DEM grid needs positive pixel sizes and dimensions (got dx " + std::to_string(dx) +
                       ", dy " + std::to_string(dy) + ", " + std::to_string(width) + " x " +
                       std::to_string(height) + " pixels)");
  }
}

// path + ".tmp-N.tif" beside the target (the .tif keeps tools that sniff extensions happy).
std::string temporary_name(const std::string& path) {
  static thread_local std::mt19937_64 rng{std::random_device{}()};
  return path + ".tmp-" + std::to_string(rng() % 1000000000ULL) + ".tif";
}

void remove_quietly(const std::string& path) {
  std::error_code ec;
  std::filesystem::remove(path, ec);
  std::filesystem::remove(path + ".aux.xml", ec);  // GDAL's side-car, should it have made one
}

// Int16 holds whole values in -32768..32767: refuse what rounding cannot bring there (GDAL
// would clamp it silently).
void check_int16(const std::string& path, const DemGrid& grid) {
  const auto fits = [](double v) {
    return std::isfinite(v) && std::round(v) >= -32768.0 && std::round(v) <= 32767.0;
  };
  if (grid.nodata && !fits(*grid.nodata)) {
    throw InvalidInput("Int16 DEM '" + path + "': nodata " + std::to_string(*grid.nodata) +
                       " does not fit in -32768..32767");
  }
  for (std::size_t i = 0; i < grid.values.size(); ++i) {
    if (!fits(grid.values[i])) {
      throw InvalidInput("Int16 DEM '" + path + "': value " + std::to_string(grid.values[i]) + " at pixel " +
                         std::to_string(i % static_cast<std::size_t>(grid.width)) + ", " +
                         std::to_string(i / static_cast<std::size_t>(grid.width)) +
                         " does not fit in -32768..32767");
    }
  }
}

void write_grid(const std::string& path, const DemGrid& grid) {
  auto dataset =
      gdal::Dataset::create_geotiff(path, grid.width, grid.height, grid.data_type == DemDataType::int16);
  // North-up: row 0 at the north edge y0, rows going south by dy.
  dataset.set_geo_transform({grid.x0, grid.dx, 0.0, grid.y0, 0.0, -grid.dy});
  dataset.set_crs(grid.crs);
  if (grid.nodata) dataset.set_nodata(*grid.nodata);
  if (!grid.unit_type.empty()) dataset.set_unit_type(grid.unit_type);
  dataset.write_band(grid.values);
  dataset.close();
}

}  // namespace

DemGrid make_dem_grid(std::string crs, double x0, double y0, double dx, double dy, int width, int height,
                      const std::function<double(double, double)>& f) {
  check_grid_shape(dx, dy, width, height);
  DemGrid grid;
  grid.crs = std::move(crs);
  grid.x0 = x0;
  grid.y0 = y0;
  grid.dx = dx;
  grid.dy = dy;
  grid.width = width;
  grid.height = height;
  grid.values.reserve(static_cast<std::size_t>(width) * height);
  for (int row = 0; row < height; ++row) {
    for (int col = 0; col < width; ++col) {
      const Vec2 c = grid.cell_centre(col, row);
      grid.values.push_back(f(c.x(), c.y()));
    }
  }
  return grid;
}

void write_geotiff(const std::string& path, const DemGrid& grid) {
  check_grid_shape(grid.dx, grid.dy, grid.width, grid.height);
  if (grid.values.size() != static_cast<std::size_t>(grid.width) * grid.height) {
    throw InvalidInput("DEM grid for '" + path + "' has " + std::to_string(grid.values.size()) +
                       " values for " + std::to_string(grid.width) + " x " + std::to_string(grid.height) +
                       " pixels");
  }
  if (grid.data_type == DemDataType::int16) check_int16(path, grid);
  const std::string temporary = temporary_name(path);
  try {
    write_grid(temporary, grid);
  } catch (...) {
    remove_quietly(temporary);
    throw;
  }
  std::error_code ec;
  std::filesystem::rename(temporary, path, ec);
  if (ec) {
    remove_quietly(temporary);
    throw IoError("cannot move the finished GeoTIFF onto '" + path + "': " + ec.message());
  }
}

}  // namespace relief
