#include "relief/export/sumo_mapping.h"

#include <nlohmann/json.hpp>

#include <string>

#include "relief/core/number_format.h"

namespace relief {

namespace {

// A JSON string literal, quoted and escaped.
std::string quoted(const std::string& text) {
  return nlohmann::json(text).dump();
}

}  // namespace

void write_sumo_mapping(std::ostream& out, const SumoPlainNetwork& net) {
  std::string s = "{\n  \"frame\": {\"crs\": " + quoted(net.frame.crs());
  s += ", \"origin\": [";
  append_fixed(s, net.frame.origin().x(), 3);
  s += ", ";
  append_fixed(s, net.frame.origin().y(), 3);
  s += "]},\n  \"lanes\": [";
  bool first = true;
  for (const SumoEdge& e : net.edges) {
    for (const SumoLane& l : e.lanes) {
      s += first ? "\n" : ",\n";
      first = false;
      s += "    {\"sumo_lane\": " + quoted(e.id + "_" + std::to_string(l.index)) +
           ", \"odr_road\": " + std::to_string(e.odr_road) + ", \"odr_lane\": " + std::to_string(l.odr_lane) +
           ", \"along_s\": " + (e.along_s ? "true" : "false") + ", \"osm_ways\": [";
      for (std::size_t i = 0; i < e.osm_way_ids.size(); ++i)
        s += (i > 0 ? ", " : "") + std::to_string(e.osm_way_ids[i]);
      s += "]}";
    }
  }
  s += "\n  ],\n  \"connections\": [";
  first = true;
  for (const SumoConnection& c : net.connections) {
    if (c.odr_road < 0) continue;
    s += first ? "\n" : ",\n";
    first = false;
    s += "    {\"from_lane\": " + quoted(c.from + "_" + std::to_string(c.from_lane)) +
         ", \"to_lane\": " + quoted(c.to + "_" + std::to_string(c.to_lane)) +
         ", \"odr_road\": " + std::to_string(c.odr_road) + ", \"odr_lane\": " + std::to_string(c.odr_lane) +
         "}";
  }
  s += "\n  ]\n}\n";
  out << s;
}

}  // namespace relief
