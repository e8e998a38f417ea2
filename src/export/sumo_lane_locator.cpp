#include "export/sumo_lane_locator.h"

#include <algorithm>
#include <sstream>

#include "relief/core/errors.h"

namespace relief::detail {

Polyline3 parse_shape(const char* text, bool* missing_z) {
  Polyline3 out;
  std::istringstream in(text);
  for (std::string token; in >> token;) {
    Vec3 p = Vec3::Zero();
    std::replace(token.begin(), token.end(), ',', ' ');
    std::istringstream xyz(token);
    xyz >> p.x() >> p.y();
    if (!(xyz >> p.z())) {
      p.z() = 0.0;
      if (missing_z) *missing_z = true;
    }
    out.push_back(p);
  }
  return out;
}

std::optional<int> param_int(const pugi::xml_node& node, const char* key) {
  for (const pugi::xml_node& p : node.children("param")) {
    if (std::string_view(p.attribute("key").as_string()) == key) return p.attribute("value").as_int();
  }
  return std::nullopt;
}

pugi::xml_node load_net(pugi::xml_document& doc, std::string_view net_xml, const std::string& file) {
  const pugi::xml_parse_result parsed = doc.load_buffer(net_xml.data(), net_xml.size());
  if (!parsed) throw InvalidInput("'" + file + "' is not XML: " + parsed.description());
  const pugi::xml_node net = doc.child("net");
  if (!net) throw InvalidInput("'" + file + "' is not a SUMO network (no <net> element)");
  return net;
}

std::optional<LaneRoad> connecting_lane(const RoadModel& model, const LaneRoad& from, const LaneRoad& to) {
  if (!from.lane || !to.lane) return std::nullopt;
  for (const JunctionModel& junction : model.junctions) {
    for (const JunctionConnection& c : junction.connections) {
      if (c.incoming_road != from.road) continue;
      const int ci = model.road_index(c.connecting_road);
      if (ci < 0) continue;
      const ModelRoad& conn = model.roads[static_cast<std::size_t>(ci)];
      const bool along_s = c.contact == RoadLink::Contact::start;
      const std::optional<RoadLink>& exit = along_s ? conn.successor : conn.predecessor;
      if (!exit || exit->element != RoadLink::Element::road || exit->id != to.road) continue;
      for (const auto& [in_lane, conn_lane] : c.lane_links) {
        if (in_lane != *from.lane || conn.sections.empty()) continue;
        const LaneSection& sec = conn.sections.front();
        for (const LaneModel& l : conn_lane < 0 ? sec.right : sec.left) {
          if (l.id != conn_lane) continue;
          if ((along_s ? l.successor : l.predecessor) == *to.lane) return LaneRoad{conn.id, conn_lane, true};
        }
      }
    }
  }
  const int fi = model.road_index(from.road);
  if (fi < 0) return std::nullopt;
  const ModelRoad& road = model.roads[static_cast<std::size_t>(fi)];
  const auto links_to = [&](const std::optional<RoadLink>& link) {
    return link && link->element == RoadLink::Element::road && link->id == to.road;
  };
  if (from.road == to.road || links_to(road.predecessor) || links_to(road.successor)) return from;
  return std::nullopt;
}

}  // namespace relief::detail
