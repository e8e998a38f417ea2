#pragma once
// Traffic counts given per OSM way, as count stations report them, put onto the SUMO edges of a
// relief build: a CSV with the header `osm_way,direction,count` (one row per station and
// direction; the count over the demand's interval). The direction is the way the counted
// traffic travels: NB, SB, EB, WB (or N, S, E, W, NE, ..., or a compass bearing in degrees), or
// `both` for a count of the two directions together, which is split evenly between them. A
// row goes onto every edge built from its way that travels within 60 degrees of its direction
// (a way split at junctions gives several edges, each carrying the count).

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "relief/demand/net_edges.h"

namespace relief {

struct CountRow {
  std::int64_t osm_way = 0;
  std::optional<double> bearing_deg;  ///< none: both directions
  double count = 0.0;
  int line = 0;  ///< in the CSV, for messages
};

/// Reads the counts. Throws IoError when the file cannot be read, InvalidInput naming the file
/// and line for a missing header column, a count that is not a number >= 0, an unknown
/// direction.
[[nodiscard]] std::vector<CountRow> read_counts_csv(const std::filesystem::path& path);

struct EdgeCount {
  std::string edge;
  double count = 0.0;
};

struct CountsOnEdges {
  std::vector<EdgeCount> edges;        ///< sorted by edge id; one entry per edge (counts summed)
  std::vector<std::string> unmatched;  ///< a message per row no edge took
};

/// The rows put onto the edges (net_edges.h, with their OSM ways).
[[nodiscard]] CountsOnEdges counts_on_edges(const std::vector<CountRow>& rows,
                                            const std::vector<NetEdge>& edges);

/// SUMO's edge data (`<data><interval><edge id entered/>`) for routeSampler.py.
void write_edge_counts(std::ostream& out, const CountsOnEdges& counts, double begin_s, double end_s);

}  // namespace relief
