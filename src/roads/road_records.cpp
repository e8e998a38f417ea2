#include "roads/road_records.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>
#include <string>
#include <utility>

#include "relief/core/diagnostic_codes.h"
#include "relief/geometry/cubic_profile.h"
#include "relief/roads/highway_class.h"
#include "roads/junction_planes.h"
#include "roads/lane_layout.h"

namespace relief::detail {

double slope_at(const RoadProfile& p, double s, double h) {
  const double lo = std::max(p.s.front(), s - h), hi = std::min(p.s.back(), s + h);
  if (hi - lo < 1e-9) return 0.0;
  return (height_at_station(p, hi) - height_at_station(p, lo)) / (hi - lo);
}

namespace {

std::string road_type(HighwayClass c) {
  switch (c) {
    case HighwayClass::motorway:
    case HighwayClass::motorway_link:
      return "motorway";
    case HighwayClass::trunk:
    case HighwayClass::trunk_link:
      return "rural";
    case HighwayClass::footway:
    case HighwayClass::path:
    case HighwayClass::steps:
    case HighwayClass::pedestrian:
      return "pedestrian";
    case HighwayClass::cycleway:
      return "bicycle";
    default:
      return "town";
  }
}

// Counts a road whose corners were rounded to its minimum radius, and reports it where its
// reference line departs from the OSM way by more than the plan tolerance.
void note_rounded_corners(const ReferenceLineReport& fit_report, const Road& road, int model_id,
                          const RoadModelOptions& options, Diagnostics& diagnostics, RoadModelStats& stats) {
  if (fit_report.corners_widened > 0 || fit_report.vertices_merged > 0) {
    ++stats.corners_rounded;
    stats.max_corner_departure_m = std::max(stats.max_corner_departure_m, fit_report.max_departure_m);
    if (fit_report.max_departure_m > options.plan_tolerance_m) {
      std::ostringstream msg;
      msg.precision(2);
      msg << std::fixed << "road " << model_id << ": "
          << fit_report.corners_widened + fit_report.vertices_merged
          << " sharp corner(s) rounded to the minimum radius " << minimum_radius(road, options)
          << " m; the reference line departs from the OSM way by up to " << fit_report.max_departure_m
          << " m";
      Diagnostic d;
      d.severity = Severity::info;
      d.code = codes::kModelCornerRounded;
      d.message = msg.str();
      d.road_id = model_id;
      if (!road.osm_way_ids.empty()) d.osm_way_id = road.osm_way_ids.front();
      diagnostics.report(std::move(d));
    }
  }
}

// Elevation: the fitted profile's stations inside the trimmed part [s0, s1] of the polyline
// (`length` long), on the reference line (`kept_s` polyline s of its vertices, `ref_s` their
// reference-line s); `leaving` the road's shared slopes at untrimmed ends.
CubicProfile elevation_records(const RoadProfile& p, const PlanView& plan, double s0, double s1,
                               double length, const std::vector<double>& kept_s,
                               const std::vector<double>& ref_s, const std::array<double, 2>& leaving,
                               const RoadModelOptions& options, RoadModelStats& stats) {
  std::vector<double> es{0.0}, ez{height_at_station(p, s0)};
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.s[i] <= s0 + 1e-6 || p.s[i] >= s1 - 1e-6) continue;
    const double rs = map_station(kept_s, ref_s, p.s[i]);
    if (rs - es.back() < 1e-6) continue;
    es.push_back(rs);
    ez.push_back(p.z[i]);
  }
  const double end_s = plan.length();
  if (end_s - es.back() < 1e-6) {
    es.pop_back();
    ez.pop_back();
  }
  es.push_back(end_s);
  ez.push_back(height_at_station(p, s1));
  // End slopes along the reference line; untrimmed ends take the junction's shared slope.
  const double g0 = s0 > 0.0 ? slope_at(p, s0) : leaving[0];
  const double g1 = s1 < length ? slope_at(p, s1) : -leaving[1];
  CubicProfile elevation =
      fit_grade_bounded_profile(es, ez, options.elevation_tolerance_m, std::make_pair(g0, g1));
  for (std::size_t i = 0; i < es.size(); ++i) {
    stats.max_elevation_deviation_m =
        std::max(stats.max_elevation_deviation_m, std::abs(elevation.value(es[i]) - ez[i]));
  }
  return elevation;
}

}  // namespace

double map_station(const std::vector<double>& from, const std::vector<double>& to, double s) {
  if (s <= from.front()) return to.front();
  if (s >= from.back()) return to.back();
  const auto it = std::upper_bound(from.begin(), from.end(), s);
  const auto i = static_cast<std::size_t>(it - from.begin());
  const double t = (s - from[i - 1]) / (from[i] - from[i - 1]);
  return to[i - 1] + t * (to[i] - to[i - 1]);
}

std::vector<std::array<double, 2>> leaving_slopes(const RoadNetwork& network,
                                                  const std::vector<RoadProfile>& profiles) {
  // Slopes at the road ends, "leaving the junction" (downhill away from it is negative). Where
  // two roads meet head to tail (an attribute change), both take the mean so that the elevation
  // is C1 across the link: leaving slopes of a smooth pass-through are opposite.
  std::vector<std::array<double, 2>> leaving(network.roads.size(), {0.0, 0.0});
  for (const Road& road : network.roads) {
    const RoadProfile& p = profiles[road.id];
    if (!p.has_height) continue;
    leaving[road.id] = {slope_at(p, 0.0), -slope_at(p, p.s.back())};
  }
  for (const Junction& j : network.junctions) {
    if (j.kind != JunctionKind::attribute_change || j.ends.size() != 2) continue;
    const RoadEnd& e0 = j.ends[0];
    const RoadEnd& e1 = j.ends[1];
    if (!profiles[e0.road].has_height || !profiles[e1.road].has_height) continue;
    double& l0 = leaving[e0.road][e0.at_start ? 0 : 1];
    double& l1 = leaving[e1.road][e1.at_start ? 0 : 1];
    const double mean = 0.5 * (l0 - l1);
    l0 = mean;
    l1 = -mean;
  }
  return leaving;
}

void add_model_roads(const JunctionEnds& ends, const std::vector<std::array<double, 2>>& leaving,
                     const std::vector<Vec2>& planes, RoadModelBuild& out, Diagnostics& diagnostics) {
  const RoadNetwork& network = ends.network;
  const RoadModelOptions& options = ends.options;
  RoadModel& model = out.model;
  for (const Road& road : network.roads) {
    const RoadProfile& p = ends.profiles[road.id];
    if (!p.has_height) {
      ++out.stats.roads_skipped;
      continue;
    }
    if (ends.clusters.absorbed[road.id]) continue;  // inside a joined junction
    const double length = ends.cumulative[road.id].back();
    const double s0 = ends.trim[road.id][0];
    const double s1 = length - ends.trim[road.id][1];
    if (s1 - s0 < kMinRoadLength) {
      ++out.stats.roads_skipped;
      diagnostics.report(Severity::warning, codes::kOpendriveRoadTooShort,
                         "road " + std::to_string(road.id) + " (" + std::to_string(length) +
                             " m) has no length left between its junctions; left out of the OpenDRIVE");
      continue;
    }
    std::vector<double> kept_s, ref_s;
    ReferenceLineReport fit_report;
    ModelRoad m;
    m.plan = ends.fit_part(road, kept_s, ref_s, &fit_report);
    m.id = static_cast<int>(model.roads.size()) + 1;
    note_rounded_corners(fit_report, road, m.id, options, diagnostics, out.stats);
    m.name = road.attributes.name;
    m.source_road = road.id;
    m.osm_way_ids = road.osm_way_ids;
    m.highway = road.attributes.highway;
    m.type = road_type(road.attributes.highway);
    m.speed_mps = road.attributes.maxspeed_mps ? *road.attributes.maxspeed_mps
                                               : default_speed_mps(road.attributes.highway);
    m.elevation =
        elevation_records(p, m.plan, s0, s1, length, kept_s, ref_s, leaving[road.id], options, out.stats);
    // A dead end meets no plane: its roll is free (end_rolls).
    const auto roll_at = [&](int junction, double heading) -> std::optional<double> {
      if (network.junctions[static_cast<std::size_t>(junction)].kind == JunctionKind::dead_end)
        return std::nullopt;
      return plane_roll(planes[static_cast<std::size_t>(junction)], heading);
    };
    m.superelevation = end_rolls(m.plan.length(), roll_at(road.start_junction, m.plan.at(0.0).heading),
                                 roll_at(road.end_junction, m.plan.at(m.plan.length()).heading));
    add_lanes(m, road.attributes);
    out.model_road_of[road.id] = static_cast<int>(model.roads.size());
    model.roads.push_back(std::move(m));
    ++out.stats.roads;
  }
}

}  // namespace relief::detail
