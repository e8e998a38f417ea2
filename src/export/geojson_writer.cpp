#include "relief/export/geojson_writer.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <iomanip>

#include "relief/core/number_format.h"
#include "relief/geometry/crs_transform.h"
#include "relief/geometry/polyline.h"
#include "relief/roads/validation.h"

namespace relief {
namespace {

// Writes a JSON string literal (names may contain quotes or non-ASCII text).
std::string quoted(const std::string& text) {
  return nlohmann::json(text).dump();
}

}  // namespace

void write_geojson(std::ostream& out, const RoadNetwork& network, const std::vector<RoadProfile>& profiles) {
  const CrsTransform to_wgs84(network.frame.crs(), "EPSG:4326");
  const Vec2& origin = network.frame.origin();

  out << "{\"type\":\"FeatureCollection\",\n\"attribution\":" << quoted(kOsmAttribution)
      << ",\n\"relief_frame\":{\"crs\":" << quoted(network.frame.crs()) << ",\"origin\":[" << std::fixed
      << std::setprecision(3) << origin.x() << "," << origin.y()
      << "],\"proj\":" << quoted(network.frame.proj_string()) << "},\n\"features\":[";
  bool first = true;
  std::vector<Vec2> lonlat;
  std::string coords;
  for (std::size_t r = 0; r < network.roads.size(); ++r) {
    const Road& road = network.roads[r];
    const RoadProfile& p = profiles[r];
    if (!p.has_height) continue;
    lonlat.assign(p.xy.begin(), p.xy.end());
    for (Vec2& q : lonlat) q += origin;
    to_wgs84.apply(lonlat);

    const WayAttributes& a = road.attributes;
    const std::vector<double> grades = segment_grades_percent(p);
    const double max_grade = grades.empty() ? 0.0 : *std::max_element(grades.begin(), grades.end());
    out << (first ? "\n" : ",\n");
    first = false;
    out << std::setprecision(3) << "{\"type\":\"Feature\",\"id\":" << road.id
        << ",\"properties\":{\"id\":" << road.id << ",\"class\":" << quoted(std::string(to_string(a.highway)))
        << ",\"name\":" << quoted(a.name) << ",\"lanes\":" << (a.lanes_forward + a.lanes_backward)
        << ",\"lanes_forward\":" << a.lanes_forward << ",\"lanes_backward\":" << a.lanes_backward
        << ",\"oneway\":" << (a.oneway ? "true" : "false") << ",\"bridge\":" << (a.bridge ? "true" : "false")
        << ",\"tunnel\":" << (a.tunnel ? "true" : "false") << ",\"layer\":" << a.layer
        << ",\"maxspeed_kmh\":";
    if (a.maxspeed_mps) {
      out << std::setprecision(1) << *a.maxspeed_mps * 3.6;
    } else {
      out << "null";
    }
    out << ",\"roundabout\":" << (a.roundabout ? "true" : "false") << std::setprecision(3)
        << ",\"length_m\":" << p.s.back() << ",\"max_grade_percent\":" << std::setprecision(2) << max_grade
        << ",\"start_junction\":" << road.start_junction << ",\"end_junction\":" << road.end_junction
        << ",\"osm_way_ids\":[";
    for (std::size_t i = 0; i < road.osm_way_ids.size(); ++i) out << (i ? "," : "") << road.osm_way_ids[i];
    out << "]},\"geometry\":{\"type\":\"LineString\",\"coordinates\":[";
    coords.clear();
    for (std::size_t i = 0; i < lonlat.size(); ++i) {
      coords += i ? ",[" : "[";
      append_fixed(coords, lonlat[i].x(), 7);
      coords += ',';
      append_fixed(coords, lonlat[i].y(), 7);
      coords += ',';
      append_fixed(coords, p.z[i], 3);
      coords += ']';
    }
    out << coords;
    out << "]}}";
  }
  out << "\n]}\n";
}

}  // namespace relief
