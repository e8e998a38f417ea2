#pragma once
// The SUMO network of a RoadModel (nodes, edges, connections; written as SUMO's plain XML by
// export/sumo_plain_xml.h), from the same fitted geometry as the OpenDRIVE: edge shapes are the roads' centre
// lines in 3D, the internal junction lanes are the OpenDRIVE connecting roads, so SUMO's lanes lie on the
// OpenDRIVE surface. netconvert (export/sumo_tools.h) turns the plain files into a .net.xml
// (junction shapes, right of way, traffic-light programs) with its height fixing turned off.
//
// Ids: the edge along OpenDRIVE road R is "R" (its right lanes), the edge against it "-R"
// (its left lanes) — the scheme of netconvert's own OpenDRIVE import, without the section
// suffix since relief's roads have one lane section. SUMO lane index 0 is the outermost
// OpenDRIVE lane of the edge's side. Every edge carries params odr.road / odr.lanes, every
// connection the connecting road, and sumo_mapping.json lists every lane (export/sumo_mapping.h).

#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "relief/core/diagnostics.h"
#include "relief/roads/highway_class.h"
#include "relief/roads/road_model.h"

namespace relief {

/// What SUMO needs about a model road that the RoadModel does not carry.
struct SumoRoadInfo {
  HighwayClass highway = HighwayClass::residential;
};

struct SumoOptions {
  /// Largest distance between an edge / internal-lane polyline and the OpenDRIVE curve it
  /// follows, in plan and in height (the polylines are the curves sampled every metre, then
  /// simplified to this tolerance).
  double shape_tolerance_m = 0.01;
  double junction_inset_m = 0.05;  ///< junction outlines stay this far inside the road ends
  /// A road that loops back to its own junction becomes two edges per direction (SUMO has no
  /// self-loops); one shorter than this is left out (turning circles) and reported.
  double min_loop_length_m = 30.0;
  /// A dead-end road shorter than this (a stub its junction's room used up) gets no edge, and
  /// is reported: netconvert drew the lane of a 1 m one on past the road's end, off the
  /// OpenDRIVE surface (0.18 m below it), where no vehicle fits anyway.
  double min_dead_end_length_m = 2.0;
  /// Vehicle classes kept off lanes steeper than a grade (percent): written as `disallow`.
  std::map<std::string, double> max_grade_percent = {
      {"truck", 15.0}, {"trailer", 10.0}, {"bus", 20.0}, {"coach", 15.0}};
  /// OpenDRIVE junction ids that get a traffic light.
  std::set<int> signalled_junctions;
  /// Per OpenDRIVE road, the grade cap (fraction) its profile was fitted to; a connecting road's
  /// entry below 0 (or missing) takes the larger cap of the roads it joins. The check of the net
  /// takes a rise as a height step only where it is steeper than its road's cap (see
  /// check_sumo_net). Empty: the street cap everywhere.
  std::vector<double> grade_caps;
};

struct SumoNode {
  std::string id;
  Vec3 position = Vec3::Zero();
  std::string type;   ///< "priority", "traffic_light", "dead_end"
  int junction = -1;  ///< OpenDRIVE junction id, -1 for a road-to-road link or a dead end
  /// Junction outline (3D, open ring) through the corners of the road ends, pulled in by a few
  /// centimetres so that netconvert does not cut the edges (a cut edge takes the node's z).
  Polyline3 shape;
};

struct SumoLane {
  int index = 0;     ///< SUMO lane index (0 = rightmost in the direction of travel)
  int odr_lane = 0;  ///< OpenDRIVE lane id
  double width_m = 3.0;
  Polyline3 shape;  ///< the OpenDRIVE lane centre in travel direction (a custom lane shape for netconvert)
};

struct SumoEdge {
  std::string id;
  std::string from, to;  ///< node ids
  int odr_road = -1;
  std::vector<std::int64_t> osm_way_ids;  ///< the OSM ways the road was built from
  bool along_s = true;                    ///< drives along the OpenDRIVE road's s (right lanes)
  Polyline3 shape;  ///< left border of the leftmost lane (spreadType "right"), in travel direction
  std::string name;
  std::string type;  ///< "highway.residential", ...
  int priority = 1;
  double speed_mps = 13.89;
  std::vector<SumoLane> lanes;  ///< by SUMO index
  double max_grade_percent = 0.0;
  std::vector<std::string> disallow;  ///< vehicle classes kept off by grade
};

struct SumoConnection {
  std::string from, to;
  int from_lane = 0, to_lane = 0;  ///< SUMO lane indices
  int odr_road = -1;               ///< OpenDRIVE connecting road (-1: a direct road-to-road link)
  int odr_lane = 0;
  Polyline3 shape;  ///< the internal lane's centre line (empty: netconvert's own)
};

struct SumoNetworkStats {
  std::size_t nodes = 0, edges = 0, connections = 0, traffic_lights = 0;
  std::map<std::string, std::size_t> restricted_edges;  ///< per vehicle class
  double max_edge_grade_percent = 0.0;
  /// Connections whose OpenDRIVE lane centre folds back (a bend tighter than the lane's offset):
  /// given to netconvert without a shape, so it draws its own curve.
  std::size_t internal_lanes_by_netconvert = 0;
};

struct SumoPlainNetwork {
  GeoFrame frame;
  std::vector<SumoNode> nodes;
  std::vector<SumoEdge> edges;
  std::vector<SumoConnection> connections;
  SumoNetworkStats stats;
};

/// Builds the plain network. `info` is parallel to model.roads (may be empty: residential).
/// Roads without lanes to drive are left out. Throws InvalidInput for options out of range.
[[nodiscard]] SumoPlainNetwork build_sumo_network(const RoadModel& model,
                                                  const std::vector<SumoRoadInfo>& info,
                                                  const SumoOptions& options, Diagnostics& diagnostics);

}  // namespace relief
