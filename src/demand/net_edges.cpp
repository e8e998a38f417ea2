#include "relief/demand/net_edges.h"

#include <nlohmann/json.hpp>
#include <pugixml.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>
#include <unordered_map>

#include "relief/core/errors.h"
#include "relief/export/sumo_tools.h"

namespace relief {
namespace {

std::vector<Vec3> parse_shape(const char* text) {
  std::vector<Vec3> points;
  std::istringstream in(text);
  for (std::string point; in >> point;) {
    std::array<double, 3> c{0.0, 0.0, 0.0};
    std::size_t k = 0, start = 0;
    for (; k < 3; ++k) {
      const std::size_t comma = point.find(',', start);
      c[k] = std::stod(point.substr(start, comma - start));
      if (comma == std::string::npos) break;
      start = comma + 1;
    }
    points.emplace_back(c[0], c[1], c[2]);
  }
  return points;
}

}  // namespace

double NetEdge::bearing_deg() const {
  if (shape.size() < 2) return 0.0;
  const Vec3 d = shape.back() - shape.front();
  const double b = std::atan2(d.x(), d.y()) * 180.0 / std::numbers::pi;
  return b < 0.0 ? b + 360.0 : b;
}

double NetEdge::mean_grade() const {
  if (shape.size() < 2) return 0.0;
  double run = 0.0;
  for (std::size_t i = 0; i + 1 < shape.size(); ++i)
    run += std::hypot(shape[i + 1].x() - shape[i].x(), shape[i + 1].y() - shape[i].y());
  return run > 0.0 ? (shape.back().z() - shape.front().z()) / run : 0.0;
}

bool NetEdge::allows(const std::string& vclass) const {
  return std::find(disallow.begin(), disallow.end(), vclass) == disallow.end();
}

std::vector<NetEdge> read_net_edges(const std::filesystem::path& net) {
  pugi::xml_document doc;
  if (!std::filesystem::is_regular_file(net)) throw IoError("cannot read the net '" + net.string() + "'");
  const pugi::xml_parse_result parsed = doc.load_file(net.c_str());
  if (!parsed) throw InvalidInput("'" + net.string() + "' is not XML: " + parsed.description());
  std::vector<NetEdge> edges;
  for (const pugi::xml_node& edge : doc.child("net").children("edge")) {
    if (!edge.attribute("function").empty()) continue;
    const pugi::xml_node lane = edge.child("lane");
    NetEdge e;
    e.id = edge.attribute("id").as_string();
    e.shape = parse_shape(lane.attribute("shape").as_string());
    e.length_m = lane.attribute("length").as_double();
    e.speed_mps = lane.attribute("speed").as_double();
    std::istringstream disallow(lane.attribute("disallow").as_string());
    for (std::string v; disallow >> v;) e.disallow.push_back(v);
    edges.push_back(std::move(e));
  }
  if (edges.empty()) throw InvalidInput("'" + net.string() + "' has no edges");
  std::unordered_map<std::string, std::size_t> index;
  for (std::size_t i = 0; i < edges.size(); ++i) index.emplace(edges[i].id, i);
  for (const pugi::xml_node& c : doc.child("net").children("connection")) {
    const auto from = index.find(c.attribute("from").as_string());
    const std::string to = c.attribute("to").as_string();
    if (from == index.end() || !index.contains(to)) continue;  // internal lanes' connections
    std::vector<std::string>& next = edges[from->second].successors;
    if (std::find(next.begin(), next.end(), to) == next.end()) next.push_back(to);
  }
  const std::filesystem::path mapping = net.parent_path() / (sumo_net_name(net) + ".sumo_mapping.json");
  if (std::filesystem::is_regular_file(mapping)) {
    std::ifstream in(mapping);
    const nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
    if (j.is_discarded()) throw InvalidInput("'" + mapping.string() + "' is not JSON");
    std::unordered_map<std::string, std::vector<std::int64_t>> ways;
    for (const nlohmann::json& lane : j.value("lanes", nlohmann::json::array())) {
      const std::string id = lane.value("sumo_lane", "");
      const std::size_t cut = id.rfind('_');
      if (cut == std::string::npos || !lane.contains("osm_ways")) continue;
      ways.try_emplace(id.substr(0, cut), lane["osm_ways"].get<std::vector<std::int64_t>>());
    }
    for (NetEdge& e : edges)
      if (const auto it = ways.find(e.id); it != ways.end()) e.osm_way_ids = it->second;
  }
  return edges;
}

}  // namespace relief
