#pragma once
// Demand between zones (an OD matrix): traffic analysis zones given as GeoJSON polygons in
// WGS84 (RFC 7946; a feature's zone id is its property "id", else "name"), each becoming a SUMO
// TAZ of the edges whose middle lies inside it; and the matrix as a CSV with the header
// `origin,destination,count` (zone ids, vehicles over the demand's interval), for SUMO's
// od2trips (tazRelation format).

#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include "relief/demand/net_edges.h"
#include "relief/geometry/types.h"

namespace relief {

/// Where a SUMO net lies: net coordinates are the projection's plus netOffset.
struct NetLocation {
  Vec2 offset = Vec2::Zero();  ///< netOffset: net coordinates = projected + offset
  std::string projection;      ///< projParameter (a PROJ string)
};

/// The net's <location>. Throws InvalidInput when it has none or no projection ("!").
[[nodiscard]] NetLocation read_net_location(const std::filesystem::path& net);

struct Zone {
  std::string id;
  std::vector<std::vector<Vec2>> rings;  ///< in net coordinates; inside by the even-odd rule
  std::vector<std::string> edges;        ///< whose middle lies inside
};

/// The zones of a GeoJSON file, in the net's coordinates. Throws IoError for an unreadable file,
/// InvalidInput (the file and the feature) for a feature that is not a Polygon or MultiPolygon,
/// has no id, or repeats one.
[[nodiscard]] std::vector<Zone> read_zones_geojson(const std::filesystem::path& path, const NetLocation& net);

/// Puts every edge into the zones its middle (half its length along its shape) lies in.
void assign_edges(std::vector<Zone>& zones, const std::vector<NetEdge>& edges);

/// SUMO's TAZ file: one <taz> per zone with edges.
void write_taz(std::ostream& out, const std::vector<Zone>& zones);

struct OdRow {
  std::string origin, destination;
  double count = 0.0;
  int line = 0;
  std::string vtype = "car";  ///< the vehicle type of relief demand's types: "car" or "truck"
};

/// Reads the matrix: the header origin,destination,count and an optional column `class`
/// (`car` or `passenger`, or `truck`; without the column every row is cars). Throws IoError / InvalidInput
/// naming the file and line.
[[nodiscard]] std::vector<OdRow> read_od_csv(const std::filesystem::path& path);

/// SUMO's tazRelation data for od2trips (--tazrelation-files).
void write_taz_relations(std::ostream& out, const std::vector<OdRow>& rows, double begin_s, double end_s);

}  // namespace relief
