#pragma once
// Road attributes taken from OSM way tags, normalised: one-ways point forward (oneway=-1 ways
// are reversed by the reader), lanes are per direction, units are SI.

#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "relief/roads/highway_class.h"

namespace relief {

struct WayAttributes {
  HighwayClass highway = HighwayClass::residential;
  bool oneway = false;        ///< traffic only in the way's (normalised) direction
  int lanes_forward = 1;      ///< lanes in the direction of the way
  int lanes_backward = 1;     ///< lanes against it (0 for one-ways)
  bool lanes_tagged = false;  ///< lanes came from tags, not class defaults
  double lane_width_m = 3.0;  ///< from `width` / total lanes, else the class default
  bool width_tagged = false;
  bool bridge = false;  ///< bridge=* other than "no"
  bool tunnel = false;  ///< tunnel=* other than "no" (building_passage, culvert count)
  int layer = 0;
  std::optional<double> maxspeed_mps;  ///< from `maxspeed` ("25 mph", "50", "50 km/h")
  std::string name;
  bool roundabout = false;  ///< junction=roundabout (or circular); implies oneway
  /// `turn:lanes` per lane, left to right in the direction of travel ("left", "through;right",
  /// "none", ...), for the lanes along the way and against it; empty when untagged or when the
  /// tag's lane count does not match the lanes.
  std::vector<std::string> turn_forward;
  std::vector<std::string> turn_backward;

  friend bool operator==(const WayAttributes&, const WayAttributes&) = default;
};

/// Result of interpreting one way's tags.
struct ParsedWay {
  WayAttributes attributes;
  bool reversed = false;  ///< oneway=-1: the node list must be reversed
};

/// Interprets the tags of a way that has a `highway` tag relief models. `tags` maps key -> value.
/// Returns nullopt when the highway value is not modelled. Unparseable values (lanes=foo,
/// width=wide) fall back to defaults; `warnings` receives one short text per such value
/// (appended, "; "-separated).
/// - oneway: yes/true/1; -1/reverse (reversed = true); no/false/0. Absent: implied by
///   highway=motorway and junction=roundabout|circular.
/// - lanes: lanes:forward / lanes:backward (swapped for oneway=-1; a missing one is `lanes`
///   minus the other), else `lanes` (one-way: all forward; two-way: forward (n+1)/2, backward
///   n/2, at least 1 each), else default_lanes_per_direction (one-ways: 0 backward).
/// - lane_width_m: `width` / total lanes when that gives 2..6 m, else the class default.
/// - bridge / tunnel: any value but "no"; layer: integer, else 0 with a warning.
[[nodiscard]] std::optional<ParsedWay> parse_way_tags(
    const std::map<std::string, std::string, std::less<>>& tags, std::string* warnings = nullptr);

/// The movements a `turn:lanes` entry allows: "left", "through", "right" (slight turns count as
/// both a turn and through, "none" and "" as through, merges as through, "reverse" as none).
[[nodiscard]] bool lane_allows(std::string_view turn_entry, std::string_view movement);

/// Parses a speed: "25 mph" -> 11.176, "50" (km/h) -> 13.889, "50 km/h", "10 knots"; nullopt for
/// "none", "signals", "walk", "US:urban" and anything unparseable.
[[nodiscard]] std::optional<double> parse_speed_mps(std::string_view value);
/// Parses a length: "3.5", "3.5 m", "12'", "12 ft", "12'6\"" -> metres; nullopt when unparseable.
[[nodiscard]] std::optional<double> parse_length_m(std::string_view value);

}  // namespace relief
