#include "relief/export/sight_writer.h"

#include "export/sight_json.h"

#include <algorithm>
#include <iomanip>

#include <nlohmann/json.hpp>

#include "relief/core/number_format.h"
#include "relief/geometry/crs_transform.h"

namespace relief {
namespace {

std::string quoted(const std::string& text) {
  return nlohmann::json(text).dump();
}

/// Local frame points to lon/lat.
std::vector<Vec2> to_lonlat(const CrsTransform& to_wgs84, const GeoFrame& frame,
                            const std::vector<Vec3>& points) {
  std::vector<Vec2> out;
  out.reserve(points.size());
  for (const Vec3& p : points) out.emplace_back(p.head<2>() + frame.origin());
  to_wgs84.apply(out);
  return out;
}

}  // namespace

SightSummary summarize_sight(const SightResult& result, const RoadModel& model, const GeoFrame& frame,
                             const SightOptions& options, std::size_t worst_count) {
  SightSummary s;
  s.options = options;
  s.km_checked = result.km_checked;
  s.km_short = result.km_short;
  s.by_class = result.by_class;
  s.stretches = result.stretches.size();
  s.stations = result.station_count;
  s.rays = result.rays;
  s.obstacle_triangles = result.obstacle_triangles;
  const CrsTransform to_wgs84(frame.crs(), "EPSG:4326");
  for (std::size_t k = 0; k < std::min(worst_count, result.stretches.size()); ++k) {
    const SightStretch& st = result.stretches[k];
    const ModelRoad& road = model.roads[static_cast<std::size_t>(st.road)];
    SightPlace p;
    p.road = road.id;
    p.name = road.name;
    p.osm_way_ids = road.osm_way_ids;
    p.road_class = st.road_class;
    p.lane = st.lane;
    p.s_from = st.s_from;
    p.s_to = st.s_to;
    p.available_m = st.available_m;
    p.required_m = st.required_m;
    p.speed_mps = st.speed_mps;
    p.grade_percent = st.grade * 100.0;
    p.obstacle = to_string(st.obstacle);
    const Vec2 ll = to_lonlat(to_wgs84, frame, {st.points[st.points.size() / 2]}).front();
    p.lon = ll.x();
    p.lat = ll.y();
    s.worst.push_back(std::move(p));
  }
  return s;
}

void write_sight_geojson(std::ostream& out, const SightResult& result, const RoadModel& model,
                         const GeoFrame& frame) {
  const CrsTransform to_wgs84(frame.crs(), "EPSG:4326");
  out << "{\"type\":\"FeatureCollection\",\"name\":\"sight distance short of the stopping sight distance\","
         "\n\"features\":[";
  bool first = true;
  for (const SightStretch& st : result.stretches) {
    const ModelRoad& road = model.roads[static_cast<std::size_t>(st.road)];
    const std::vector<Vec2> ll = to_lonlat(to_wgs84, frame, st.points);
    out << (first ? "\n" : ",\n");
    first = false;
    out << std::fixed << "{\"type\":\"Feature\",\"properties\":{\"road\":" << road.id
        << ",\"name\":" << quoted(road.name) << ",\"osm_way_ids\":[";
    for (std::size_t i = 0; i < road.osm_way_ids.size(); ++i) out << (i ? "," : "") << road.osm_way_ids[i];
    out << "],\"class\":" << quoted(st.road_class) << ",\"lane\":" << st.lane << ",\"direction\":\""
        << (st.lane < 0 ? "forward" : "backward") << "\"" << std::setprecision(2)
        << ",\"s_from\":" << st.s_from << ",\"s_to\":" << st.s_to << ",\"length_m\":" << st.length_m()
        << ",\"available_m\":" << st.available_m << ",\"required_m\":" << st.required_m
        << ",\"speed_kmh\":" << st.speed_mps * 3.6 << ",\"grade_percent\":" << st.grade * 100.0
        << ",\"obstacle\":\"" << to_string(st.obstacle) << "\"";
    if (st.obstacle != SightObstacle::none) {
      const Vec2 o = to_lonlat(to_wgs84, frame, {st.obstacle_point}).front();
      out << std::setprecision(7) << ",\"obstacle_lonlat\":[" << o.x() << "," << o.y() << "]";
    }
    out << "},\"geometry\":{\"type\":\"LineString\",\"coordinates\":[";
    for (std::size_t i = 0; i < ll.size(); ++i)
      out << (i ? "," : "") << std::setprecision(7) << "[" << ll[i].x() << "," << ll[i].y()
          << std::setprecision(2) << "," << st.points[i].z() << "]";
    out << "]}}";
  }
  out << "\n]}\n";
}

nlohmann::ordered_json sight_json(const SightSummary& s) {
  using Json = nlohmann::ordered_json;
  Json by_class = Json::object();
  for (const auto& [cls, f] : s.by_class)
    by_class[cls] = {{"km_checked", round_to(f.km_checked, 1e-3)}, {"km_short", round_to(f.km_short, 1e-3)}};
  Json worst = Json::array();
  for (const SightPlace& p : s.worst)
    worst.push_back({{"road", p.road},
                     {"name", p.name},
                     {"osm_way_ids", p.osm_way_ids},
                     {"class", p.road_class},
                     {"lane", p.lane},
                     {"s_from", round_to(p.s_from, 0.01)},
                     {"s_to", round_to(p.s_to, 0.01)},
                     {"available_m", round_to(p.available_m, 0.01)},
                     {"required_m", round_to(p.required_m, 0.01)},
                     {"speed_kmh", round_to(p.speed_mps * 3.6, 0.1)},
                     {"grade_percent", round_to(p.grade_percent, 0.01)},
                     {"obstacle", p.obstacle},
                     {"lonlat", {round_to(p.lon, 1e-7), round_to(p.lat, 1e-7)}}});
  return {{"file", s.file},
          {"eye_height_m", s.options.eye_height_m},
          {"object_height_m", s.options.object_height_m},
          {"reaction_s", s.options.reaction_s},
          {"deceleration_mps2", s.options.deceleration_mps2},
          {"step_m", s.options.step_m},
          {"km_checked", round_to(s.km_checked, 1e-3)},
          {"km_short", round_to(s.km_short, 1e-3)},
          {"by_class", by_class},
          {"stretches", s.stretches},
          {"worst", worst},
          {"stations", s.stations},
          {"rays", s.rays},
          {"obstacle_triangles", s.obstacle_triangles},
          {"seconds", round_to(s.seconds, 1e-3)}};
}

std::string sight_summary_json(const SightSummary& s) {
  return sight_json(s).dump(2) + "\n";
}

}  // namespace relief
