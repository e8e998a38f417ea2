#pragma once
// The edges of a relief build's SUMO net as the demand tools need them: shape with heights,
// length, speed limit, the vehicle classes kept off, and the OSM ways each came from (read from
// NAME.sumo_mapping.json beside NAME.net.xml).

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "relief/geometry/types.h"

namespace relief {

struct NetEdge {
  std::string id;
  std::vector<Vec3> shape;  ///< the first lane's centre, in travel direction
  double length_m = 0.0;
  double speed_mps = 0.0;
  std::vector<std::string> disallow;      ///< of the first lane
  std::vector<std::int64_t> osm_way_ids;  ///< from the mapping; empty for an edge it does not list
  /// The normal edges a connection of the net leads to from this one (a vehicle can turn into).
  std::vector<std::string> successors;

  /// Compass bearing of the edge from its first to its last point, degrees clockwise from north.
  [[nodiscard]] double bearing_deg() const;
  /// Rise over run between its ends (the mean grade along it; > 0 climbs).
  [[nodiscard]] double mean_grade() const;
  [[nodiscard]] bool allows(const std::string& vclass) const;
};

/// The normal edges of `net` (internal edges left out), with the OSM ways of
/// NAME.sumo_mapping.json beside it when that file exists. Throws IoError / InvalidInput naming
/// the file.
[[nodiscard]] std::vector<NetEdge> read_net_edges(const std::filesystem::path& net);

}  // namespace relief
