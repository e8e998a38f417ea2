#pragma once
// RoadModel: the single source of road geometry downstream of the profile fit — reference
// lines, elevation, lanes, links and junctions, in the local frame. The OpenDRIVE file is its
// serialisation (export/opendrive_writer.h) and reading an .xodr yields one
// (roads/opendrive_reader.h), so every later stage (SUMO lanes, meshes, co-simulation queries)
// evaluates one surface S(road, s, t) -> (x, y, z) (road_surface.h).
//
// Conventions are OpenDRIVE's: s along the reference line from its start, t to its left; lane
// ids 1, 2, ... on the left (positive t), -1, -2, ... on the right, 0 the centre lane (no width);
// right lanes drive along the reference line (right-hand traffic).

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "relief/geometry/cubic_profile.h"
#include "relief/geometry/geo_frame.h"
#include "relief/geometry/plan_view.h"
#include "relief/roads/highway_class.h"

namespace relief {

struct RoadMark {
  enum class Type { none, solid, broken, solid_solid, solid_broken, broken_solid };
  Type type = Type::none;
  std::string color = "standard";  ///< "standard" (white), "yellow"
  double width_m = 0.12;
};

struct LaneModel {
  int id = 0;                      ///< OpenDRIVE lane id (see above)
  std::string type = "driving";    ///< "driving", "shoulder", "sidewalk", "border", "none"
  CubicProfile width;              ///< in ds from the lane section's start
  RoadMark mark;                   ///< mark on the lane's outer border
  std::optional<int> predecessor;  ///< lane id in the predecessor road / section
  std::optional<int> successor;
};

struct LaneSection {
  double s = 0.0;
  std::vector<LaneModel> left;   ///< ids 1, 2, ... (innermost first)
  std::vector<LaneModel> right;  ///< ids -1, -2, ... (innermost first)
  RoadMark centre_mark;          ///< on the centre lane (lane 0)
};

struct RoadLink {
  enum class Element { road, junction };
  enum class Contact { start, end };
  Element element = Element::road;
  int id = -1;                       ///< road or junction id
  Contact contact = Contact::start;  ///< for roads: which end of that road we touch
};

struct ModelRoad {
  int id = -1;  ///< OpenDRIVE road id
  std::string name;
  int junction = -1;  ///< -1, or the junction this connecting road belongs to
  PlanView plan;
  CubicProfile elevation;             ///< z(s), metres
  CubicProfile superelevation;        ///< radians (roll), 0 unless configured
  CubicProfile lane_offset;           ///< t of the centre lane, metres
  std::vector<LaneSection> sections;  ///< sorted by s, first at s = 0
  std::optional<RoadLink> predecessor;
  std::optional<RoadLink> successor;
  std::string type = "town";  ///< OpenDRIVE road type
  std::optional<double> speed_mps;
  int source_road = -1;  ///< RoadNetwork road it came from (-1: connecting road)
  std::vector<std::int64_t> osm_way_ids;
  std::optional<HighwayClass> highway;  ///< the OSM highway class (connecting roads: none)

  [[nodiscard]] double length() const { return plan.length(); }
};

struct JunctionConnection {
  int id = 0;
  int incoming_road = -1;
  int connecting_road = -1;
  RoadLink::Contact contact = RoadLink::Contact::start;  ///< end of the connecting road at the incoming road
  std::vector<std::pair<int, int>> lane_links;           ///< incoming lane id -> connecting lane id
};

struct JunctionModel {
  int id = -1;
  std::string name;
  std::vector<JunctionConnection> connections;
  std::vector<int> source_junctions;  ///< RoadNetwork junctions it came from (several where joined)
  bool traffic_signal = false;        ///< OSM signals it (SUMO gives it a traffic light)
};

struct RoadModel {
  GeoFrame frame;
  std::string name;
  std::vector<ModelRoad> roads;  ///< index == position; ids need not equal indices
  std::vector<JunctionModel> junctions;

  /// Index of the road with OpenDRIVE id `id`, or -1. Constant time where road k has id k + 1
  /// (models relief builds), else a scan.
  [[nodiscard]] int road_index(int id) const;
};

/// " (OSM way W)", W the first OSM way the road was drawn from, or "" for a road with none: for
/// messages naming a road.
[[nodiscard]] std::string osm_way_note(const ModelRoad& road);

}  // namespace relief
