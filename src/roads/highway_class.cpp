#include "relief/roads/highway_class.h"

#include <array>
#include <utility>

namespace relief {

namespace {

constexpr double kMph = 0.44704;    // 1 mph in m/s (exact)
constexpr double kKmh = 1.0 / 3.6;  // 1 km/h in m/s

// Defaults of one class: lanes per direction, lane width (m), speed (m/s).
struct ClassDefaults {
  HighwayClass cls;
  std::string_view name;
  int lanes_per_direction;
  double lane_width_m;
  double speed_mps;
};

// One row per HighwayClass, in enum order (checked by the static_assert below).
constexpr std::array<ClassDefaults, 21> kClasses{{
    {HighwayClass::motorway, "motorway", 2, 3.65, 65 * kMph},
    {HighwayClass::motorway_link, "motorway_link", 1, 3.5, 25 * kMph},
    {HighwayClass::trunk, "trunk", 2, 3.5, 45 * kMph},
    {HighwayClass::trunk_link, "trunk_link", 1, 3.5, 25 * kMph},
    {HighwayClass::primary, "primary", 2, 3.5, 35 * kMph},
    {HighwayClass::primary_link, "primary_link", 1, 3.5, 25 * kMph},
    {HighwayClass::secondary, "secondary", 1, 3.25, 30 * kMph},
    {HighwayClass::secondary_link, "secondary_link", 1, 3.5, 25 * kMph},
    {HighwayClass::tertiary, "tertiary", 1, 3.25, 25 * kMph},
    {HighwayClass::tertiary_link, "tertiary_link", 1, 3.5, 25 * kMph},
    {HighwayClass::unclassified, "unclassified", 1, 3.0, 25 * kMph},
    {HighwayClass::residential, "residential", 1, 3.0, 25 * kMph},
    {HighwayClass::service, "service", 1, 2.75, 15 * kMph},
    {HighwayClass::living_street, "living_street", 1, 2.75, 10 * kMph},
    {HighwayClass::pedestrian, "pedestrian", 1, 1.5, 5 * kKmh},
    {HighwayClass::track, "track", 1, 1.5, 5 * kKmh},
    {HighwayClass::footway, "footway", 1, 1.5, 5 * kKmh},
    {HighwayClass::path, "path", 1, 1.5, 5 * kKmh},
    {HighwayClass::cycleway, "cycleway", 1, 1.5, 5 * kKmh},
    {HighwayClass::steps, "steps", 1, 1.5, 5 * kKmh},
    {HighwayClass::bridleway, "bridleway", 1, 1.5, 5 * kKmh},
}};

constexpr bool rows_in_enum_order() {
  for (std::size_t i = 0; i < kClasses.size(); ++i) {
    if (static_cast<std::size_t>(kClasses[i].cls) != i) return false;
  }
  return static_cast<std::size_t>(HighwayClass::bridleway) + 1 == kClasses.size();
}
static_assert(rows_in_enum_order(), "kClasses must list every HighwayClass in enum order");

const ClassDefaults& row(HighwayClass cls) {
  return kClasses[static_cast<std::size_t>(cls)];
}

}  // namespace

std::optional<HighwayClass> parse_highway_class(std::string_view value) {
  // Exact, case-sensitive match as in OSM; everything else (construction, proposed, platform,
  // bus_stop, elevator, corridor, raceway, road, ...) is not modelled.
  for (const auto& r : kClasses) {
    if (r.name == value) return r.cls;
  }
  return std::nullopt;
}

std::string_view to_string(HighwayClass cls) {
  return row(cls).name;
}

bool is_motor_road(HighwayClass cls) {
  return static_cast<int>(cls) <= static_cast<int>(HighwayClass::living_street);
}

bool is_foot_way(HighwayClass cls) {
  return cls == HighwayClass::pedestrian || cls == HighwayClass::footway || cls == HighwayClass::path ||
         cls == HighwayClass::steps || cls == HighwayClass::bridleway;
}

double default_lane_width_m(HighwayClass cls) {
  return row(cls).lane_width_m;
}

int default_lanes_per_direction(HighwayClass cls) {
  return row(cls).lanes_per_direction;
}

double default_speed_mps(HighwayClass cls) {
  return row(cls).speed_mps;
}

}  // namespace relief
