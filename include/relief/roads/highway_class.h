#pragma once
// OSM `highway` classes relief builds roads from, and their defaults.

#include <optional>
#include <string_view>

namespace relief {

enum class HighwayClass {
  motorway,
  motorway_link,
  trunk,
  trunk_link,
  primary,
  primary_link,
  secondary,
  secondary_link,
  tertiary,
  tertiary_link,
  unclassified,
  residential,
  service,
  living_street,
  // Skipped unless OsmReadOptions::include_non_motor is set:
  pedestrian,
  track,
  footway,
  path,
  cycleway,
  steps,
  bridleway,
};

/// Parses an OSM highway value ("residential"); nullopt for values relief does not model
/// (construction, proposed, platform, ...).
[[nodiscard]] std::optional<HighwayClass> parse_highway_class(std::string_view value);
[[nodiscard]] std::string_view to_string(HighwayClass cls);
/// True for the classes built by default (motorway ... living_street and the links).
[[nodiscard]] bool is_motor_road(HighwayClass cls);
/// True for the ways only people walk or ride a horse on (pedestrian, footway, path, steps,
/// bridleway): no vehicle climbs them, and in mountains they climb as steeply as the slope.
[[nodiscard]] bool is_foot_way(HighwayClass cls);
/// Default lane width in metres (motorway 3.65 ... service 2.75, footway 1.5).
[[nodiscard]] double default_lane_width_m(HighwayClass cls);
/// Default lanes per direction when the way has no `lanes` tag.
[[nodiscard]] int default_lanes_per_direction(HighwayClass cls);
/// Default speed in m/s when the way has no usable `maxspeed` (US urban values).
[[nodiscard]] double default_speed_mps(HighwayClass cls);

}  // namespace relief
