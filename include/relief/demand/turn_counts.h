#pragma once
// Turn counts given per OSM way, as intersection counts report them, put onto pairs of SUMO
// edges of a relief build: a CSV with the header `from_way,from_direction,to_way,to_direction,count`
// (one row per movement: the way the vehicles arrive on and the direction they travel on it,
// the way they leave on and the direction they travel then, and the vehicles over the demand's
// interval). Directions as for traffic counts (traffic_counts.h; `both` or an empty field: any).
// A row goes onto every pair of edges (one built from each way, each travelling within 60
// degrees of its direction) that the net connects; where several pairs match (a way meeting
// the other at two junctions), the count is split evenly between them.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "relief/demand/net_edges.h"

namespace relief {

struct TurnRow {
  std::int64_t from_way = 0, to_way = 0;
  std::optional<double> from_bearing_deg, to_bearing_deg;  ///< none: any direction
  double count = 0.0;
  int line = 0;  ///< in the CSV, for messages
};

/// Reads the turn counts. Throws IoError when the file cannot be read, InvalidInput naming the
/// file and line for a missing header column, a way that is not an integer, a count that is not
/// a number >= 0, an unknown direction.
[[nodiscard]] std::vector<TurnRow> read_turn_counts_csv(const std::filesystem::path& path);

struct TurnCount {
  std::string from, to;  ///< edge ids
  double count = 0.0;
};

struct TurnsOnEdges {
  std::vector<TurnCount> turns;        ///< sorted by (from, to); one entry per pair (counts summed)
  std::vector<std::string> unmatched;  ///< a message per row no pair took
};

/// The rows put onto connected pairs of edges (net_edges.h, with their OSM ways and successors).
[[nodiscard]] TurnsOnEdges turns_on_edges(const std::vector<TurnRow>& rows,
                                          const std::vector<NetEdge>& edges);

/// SUMO's edge relation data (`<data><interval><edgeRelation from to count/>`) for
/// routeSampler.py's --turn-files.
void write_turn_counts(std::ostream& out, const TurnsOnEdges& turns, double begin_s, double end_s);

}  // namespace relief
