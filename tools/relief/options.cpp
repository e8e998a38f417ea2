#include "options.h"

#include <iostream>

#include "commands.h"
#include "relief/core/errors.h"
#include "relief/pipeline/option_text.h"

namespace relief::cli {

namespace {

// A validator for a finite number above 0 (strictly) or from 0 on.
CLI::Validator finite_from_zero(bool strictly) {
  const std::string range = strictly ? "> 0" : ">= 0";
  return CLI::Validator(
      [strictly, range](std::string& text) -> std::string {
        const std::optional<double> value = parse_finite_number(text);
        if (value && (strictly ? *value > 0.0 : *value >= 0.0)) return {};
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

void parse_for(const std::string& option, const std::function<void()>& apply) {
  try {
    apply();
  } catch (const InvalidInput& e) {
    throw CLI::ValidationError(option, e.what());
  }
}

void add_input_options(CLI::App& app, BuildOptions& options) {
  app.add_option_function<std::string>(
         "--osm", [&options](const std::string& path) { options.osm_path = path; },
         "OpenStreetMap file (.osm, .osm.gz, .osm.bz2, .osm.pbf)")
      ->required();
  app.add_option("--dem", options.dem_paths,
                 "DEM raster(s) GDAL can read; repeat for a mosaic (first valid wins)")
      ->required();
  app.add_option_function<std::string>(
      "--crs",
      [&options](const std::string& crs) {
        if (!crs.empty()) options.crs = crs;
      },
      "metric CRS of the local frame (default: WGS84 UTM zone of the data)");
  app.add_option_function<std::string>(
      "--origin",
      [&options](const std::string& text) {
        if (!text.empty()) parse_for("--origin", [&] { options.frame_centre = parse_lon_lat(text); });
      },
      "centre of the local frame, LON,LAT (default: the centre of the roads; builds that share it share one "
      "frame)");
  app.add_option_function<std::string>(
      "--dem-unit",
      [&options](const std::string& text) {
        if (text.empty()) return;
        options.dem.unit = parse_vertical_unit(text);
        if (!options.dem.unit)
          throw CLI::ValidationError("--dem-unit", "'" + text + "' is not one of m, ft, us-ft");
      },
      "vertical unit of the DEM(s) when their metadata is wrong or silent: m, ft, us-ft");
  app.add_option("--ground-filter", options.dem.ground_filter_m,
                 "the DEM is a surface model (DSM: buildings, trees): take everything narrower than M metres "
                 "standing out of the ground by over 2 m (or sunk into it) back to the ground; 0 = off")
      ->capture_default_str()
      ->check(finite_non_negative());
  add_enum_option(app, "--interp", options.dem.interpolation, &parse_interpolation,
                  "one of bilinear, idw, nearest",
                  "DEM interpolation: bilinear, idw (the seed paper's), nearest");
  app.add_option_function<std::string>(
      "--bbox",
      [&options](const std::string& text) {
        if (!text.empty()) parse_for("--bbox", [&] { options.osm.bbox = parse_lon_lat_box(text); });
      },
      "clip the roads to MIN_LON,MIN_LAT,MAX_LON,MAX_LAT (ways are cut at the edge)");
  app.add_flag("--include-paths", options.osm.include_non_motor,
               "also build footways, paths, cycleways, steps, tracks");
  app.add_option("--spacing", options.sampling.spacing_m, "elevation sample spacing along roads, metres")
      ->capture_default_str()
      ->check(finite_positive());
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
