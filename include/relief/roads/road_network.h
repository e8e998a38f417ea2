#pragma once
// The 2D road network in the local frame: roads between junctions, each keeping its OSM origin.

#include <cstdint>
#include <string_view>
#include <vector>

#include "relief/geometry/geo_frame.h"
#include "relief/geometry/types.h"
#include "relief/roads/way_attributes.h"

namespace relief {

/// A road end at a junction.
struct RoadEnd {
  int road = -1;
  bool at_start = true;  ///< true: the road's first point; false: its last

  friend bool operator==(const RoadEnd&, const RoadEnd&) = default;
};

enum class JunctionKind {
  intersection,      ///< three or more road ends
  attribute_change,  ///< two road ends whose attributes differ (bridge starts, lanes change)
  dead_end,          ///< one road end
};
[[nodiscard]] std::string_view to_string(JunctionKind kind);

struct Junction {
  int id = -1;
  std::int64_t osm_node_id = 0;
  Vec2 position = Vec2::Zero();  ///< local frame
  std::vector<RoadEnd> ends;
  JunctionKind kind = JunctionKind::dead_end;
  bool traffic_signal = false;
  bool roundabout = false;  ///< on a roundabout ring
};

/// A road between two junctions. Its polyline runs from junction `start_junction` to
/// `end_junction`; both ends are OSM nodes.
struct Road {
  int id = -1;
  Polyline2 points;                        ///< local frame, >= 2 distinct points
  std::vector<std::int64_t> osm_node_ids;  ///< parallel to `points`
  std::vector<std::int64_t> osm_way_ids;   ///< ways it came from, in order along the road
  WayAttributes attributes;
  int start_junction = -1;
  int end_junction = -1;
};

struct RoadNetwork {
  GeoFrame frame;
  std::vector<Road> roads;
  std::vector<Junction> junctions;
  std::size_t roundabouts = 0;  ///< connected rings of junction=roundabout roads

  [[nodiscard]] std::size_t count(JunctionKind kind) const;
};

}  // namespace relief
