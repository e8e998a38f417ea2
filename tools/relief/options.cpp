#include "options.h"

#include <cmath>
#include <iostream>
#include <sstream>

#include "commands.h"
#include "relief/core/errors.h"

namespace relief::cli {

namespace {

// A validator for a finite number above 0 (strictly) or from 0 on.
CLI::Validator finite_from_zero(bool strictly) {
  const std::string range = strictly ? "> 0" : ">= 0";
  return CLI::Validator(
      [strictly, range](std::string& text) -> std::string {
        try {
          std::size_t used = 0;
          const double value = std::stod(text, &used);
          if (used == text.size() && std::isfinite(value) && (strictly ? value > 0.0 : value >= 0.0))
            return {};
        } catch (const std::exception&) {
          // Not a number: the message below.
        }
        return "'" + text + "' is not a finite number " + range;
      },
      "FINITE " + range);
}

}  // namespace

const CLI::Validator& finite_positive() {
  static const CLI::Validator validator = finite_from_zero(true);
  return validator;
}

const CLI::Validator& finite_non_negative() {
  static const CLI::Validator validator = finite_from_zero(false);
  return validator;
}

void InputArgs::add_to(CLI::App& app) {
  app.add_option("--osm", osm, "OpenStreetMap file (.osm, .osm.gz, .osm.bz2, .osm.pbf)")->required();
  app.add_option("--dem", dems, "DEM raster(s) GDAL can read; repeat for a mosaic (first valid wins)")
      ->required();
  app.add_option("--crs", crs, "metric CRS of the local frame (default: WGS84 UTM zone of the data)");
  app.add_option("--dem-unit", dem_unit,
                 "vertical unit of the DEM(s) when their metadata is wrong or silent: m, ft, us-ft");
  app.add_option("--interp", interp, "DEM interpolation: bilinear (default), idw (the seed paper's), nearest")
      ->capture_default_str();
  app.add_option("--bbox", bbox,
                 "clip the roads to MIN_LON,MIN_LAT,MAX_LON,MAX_LAT (ways are cut at the edge)");
  app.add_flag("--include-paths", include_paths, "also build footways, paths, cycleways, steps, tracks");
  app.add_option("--spacing", spacing_m, "elevation sample spacing along roads, metres")
      ->capture_default_str()
      ->check(finite_positive());
}

LonLatBox parse_bbox(const std::string& text) {
  std::vector<double> v;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    try {
      std::size_t used = 0;
      v.push_back(std::stod(item, &used));
      if (used != item.size()) throw std::invalid_argument(item);
    } catch (const std::exception&) {
      throw CLI::ValidationError("--bbox", "'" + text + "' is not MIN_LON,MIN_LAT,MAX_LON,MAX_LAT");
    }
  }
  if (v.size() != 4 || v[0] >= v[2] || v[1] >= v[3] || v[0] < -180 || v[2] > 180 || v[1] < -90 || v[3] > 90) {
    throw CLI::ValidationError("--bbox",
                               "'" + text + "' is not MIN_LON,MIN_LAT,MAX_LON,MAX_LAT with min < max");
  }
  return {v[0], v[1], v[2], v[3]};
}

void InputArgs::apply_to(BuildOptions& options) const {
  options.osm_path = osm;
  options.dem_paths = dems;
  if (!crs.empty()) options.crs = crs;
  if (!dem_unit.empty()) {
    options.dem.unit = parse_vertical_unit(dem_unit);
    if (!options.dem.unit)
      throw CLI::ValidationError("--dem-unit", "'" + dem_unit + "' is not one of m, ft, us-ft");
  }
  const auto method = parse_interpolation(interp);
  if (!method)
    throw CLI::ValidationError("--interp", "'" + interp + "' is not one of bilinear, idw, nearest");
  options.dem.interpolation = *method;
  options.reference_dem.interpolation = Interpolation::bilinear;
  if (!bbox.empty()) options.osm.bbox = parse_bbox(bbox);
  options.osm.include_non_motor = include_paths;
  options.sampling.spacing_m = spacing_m;
}

int run_reporting_errors(const std::function<int()>& body) {
  try {
    return body();
  } catch (const CLI::ValidationError& e) {
    std::cerr << "relief: bad usage: " << e.what() << "\n";
    return kUsage;
  } catch (const OptionError& e) {
    std::cerr << "\nrelief: bad usage: " << e.what() << "\n";
    return kUsage;
  } catch (const InvalidInput& e) {
    std::cerr << "\nrelief: error: " << e.what() << "\n";
    return kBadInput;
  } catch (const IoError& e) {
    std::cerr << "\nrelief: error: " << e.what() << "\n";
    return kBadInput;
  } catch (const ProjectionError& e) {
    std::cerr << "\nrelief: error: " << e.what() << "\n";
    return kBadInput;
  } catch (const std::exception& e) {
    std::cerr << "\nrelief: internal error: " << e.what() << "\n";
    return kInternalError;
  }
}

}  // namespace relief::cli
