#pragma once
// The text forms of BuildOptions' values, as a command line or a configuration file gives them:
// lists ("glb,obj"), KEY=VALUE items ("truck=15", "ground_holes=0") and boxes. One room for
// their syntax, so that every front end parses them alike and the CLI holds no parser.
//
// Each function throws OptionError (a kind of InvalidInput) whose message quotes the offending
// text and says what was expected; the caller adds which option it came from.

#include <map>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "relief/export/mesh_writer.h"
#include "relief/export/quality_gates.h"
#include "relief/geometry/types.h"
#include "relief/pipeline/build.h"

namespace relief {

/// The whole of `text` as a finite number ("12", "-2.5", "1e3"); nullopt for anything else
/// ("", "12 %", "nan", "inf").
[[nodiscard]] std::optional<double> parse_finite_number(std::string_view text);

/// The items of a list separated by `separator`, split as std::getline splits them:
/// "a,,b" -> {"a", "", "b"}, "a," -> {"a"}, "" -> {}.
[[nodiscard]] std::vector<std::string> split_list(std::string_view text, char separator = ',');

/// "all" -> every Output; otherwise a comma-separated list of xodr, sumo, mesh, geojson,
/// report, html ("" -> none). Throws OptionError naming the first unknown item.
[[nodiscard]] std::set<Output> parse_outputs(std::string_view text);

/// A comma-separated list of glb, obj, fbx. Throws OptionError naming the first unknown item.
[[nodiscard]] std::set<MeshFormat> parse_mesh_formats(std::string_view text);

/// Applies one "CLASS=PERCENT" (SUMO vehicle class, finite percent > 0) to a table of
/// SumoOptions::max_grade_percent; "CLASS=none" drops CLASS from it. Throws OptionError on any
/// other form; `max_grade_percent` is then unchanged.
void apply_vclass_max_grade(std::map<std::string, double>& max_grade_percent, std::string_view item);

/// Applies one "NAME=VALUE" (a gate of GateThresholds::names(), a finite VALUE) to `gates`.
/// Throws OptionError on another form or an unknown name; `gates` is then unchanged.
void apply_gate_threshold(GateThresholds& gates, std::string_view item);

/// "MIN_LON,MIN_LAT,MAX_LON,MAX_LAT" in degrees, min < max, within [-180, 180] x [-90, 90].
/// Throws OptionError otherwise.
[[nodiscard]] LonLatBox parse_lon_lat_box(std::string_view text);

/// "LON,LAT" in degrees within [-180, 180] x [-90, 90]. Throws OptionError otherwise.
[[nodiscard]] LonLat parse_lon_lat(std::string_view text);

}  // namespace relief
