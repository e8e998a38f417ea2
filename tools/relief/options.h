#pragma once
// Command-line options shared by `build` and `info`, and their translation into BuildOptions.

#include <CLI/CLI.hpp>

#include <optional>
#include <string>
#include <vector>

#include "relief/pipeline/build.h"

namespace relief::cli {

struct InputArgs {
  std::string osm;
  std::vector<std::string> dems;
  std::string crs;
  std::string dem_unit;
  std::string interp = "bilinear";
  std::string bbox;
  bool include_paths = false;
  double spacing_m = 1.0;

  /// Registers --osm, --dem, --crs, --dem-unit, --interp, --bbox, --include-paths, --spacing.
  void add_to(CLI::App& app);
  /// Fills the input part of `options`; throws CLI::ValidationError on a malformed value.
  void apply_to(BuildOptions& options) const;
};

/// Accepts a finite number > 0 (CLI::PositiveNumber lets "nan" and "inf" through, and states
/// its range as 0 to 1.8e308 written out in full).
[[nodiscard]] const CLI::Validator& finite_positive();
/// Accepts a finite number >= 0.
[[nodiscard]] const CLI::Validator& finite_non_negative();

/// Parses "min_lon,min_lat,max_lon,max_lat".
[[nodiscard]] LonLatBox parse_bbox(const std::string& text);

/// Runs `body`, mapping relief's exceptions to exit codes and printing their message:
/// InvalidInput/IoError/ProjectionError -> 3, CLI::ValidationError and OptionError (an option
/// value the input makes unusable) -> 2, anything else -> 1.
int run_reporting_errors(const std::function<int()>& body);

}  // namespace relief::cli
