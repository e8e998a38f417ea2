#pragma once
// The sight-distance pass's outputs: the GeoJSON layer of the stretches whose sight distance
// falls short (NAME.sight.geojson, WGS84) and the summary report.json and report.html carry.

#include <cstddef>
#include <cstdint>
#include <map>
#include <ostream>
#include <string>
#include <vector>

#include "relief/geometry/geo_frame.h"
#include "relief/roads/road_model.h"
#include "relief/sight/sight_distance.h"

namespace relief {

/// One short stretch, located.
struct SightPlace {
  int road = -1;  ///< OpenDRIVE road id
  std::string name;
  std::vector<std::int64_t> osm_way_ids;
  std::string road_class;
  int lane = 0;
  double s_from = 0.0, s_to = 0.0;
  double available_m = 0.0, required_m = 0.0, speed_mps = 0.0, grade_percent = 0.0;
  std::string obstacle;         ///< road, terrain
  double lon = 0.0, lat = 0.0;  ///< the stretch's middle point
};

struct SightSummary {
  std::string file;  ///< NAME.sight.geojson
  SightOptions options;
  double km_checked = 0.0;  ///< lane-km, each lane and direction
  double km_short = 0.0;
  std::map<std::string, SightClassFigures> by_class;
  std::size_t stretches = 0;
  std::vector<SightPlace> worst;  ///< up to 10, smallest available / required first
  std::size_t stations = 0;
  std::size_t rays = 0;
  std::size_t obstacle_triangles = 0;
  double seconds = 0.0;
};

/// The summary of `result` (computed on `model` in `frame`), with its `worst_count` worst places.
[[nodiscard]] SightSummary summarize_sight(const SightResult& result, const RoadModel& model,
                                           const GeoFrame& frame, const SightOptions& options,
                                           std::size_t worst_count = 10);

/// The short stretches as a GeoJSON FeatureCollection of LineStrings in WGS84 (lon, lat,
/// height in the frame), each with: road, name, osm_way_ids, class, lane, direction ("forward"
/// along the road's reference line or "backward"), s_from, s_to, length_m, available_m,
/// required_m, speed_kmh, grade_percent, obstacle, obstacle_lonlat.
void write_sight_geojson(std::ostream& out, const SightResult& result, const RoadModel& model,
                         const GeoFrame& frame);

/// The summary as JSON: report.json's "sight" object (file, the AASHTO parameters, km_checked,
/// km_short, by_class{class: {km_checked, km_short}}, stretches, worst[{road, name, osm_way_ids,
/// class, lane, s_from, s_to, available_m, required_m, speed_kmh, grade_percent, obstacle,
/// lonlat}], stations, rays, obstacle_triangles, seconds).
[[nodiscard]] std::string sight_summary_json(const SightSummary& s);

}  // namespace relief
