#include "relief/roads/opendrive_reader.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <iterator>
#include <pugixml.hpp>
#include <sstream>
#include <string>

#include "relief/core/errors.h"

namespace relief {
namespace {

std::string_view trimmed(std::string_view text) {
  const auto space = [](char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; };
  while (!text.empty() && space(text.front())) text.remove_prefix(1);
  while (!text.empty() && space(text.back())) text.remove_suffix(1);
  return text;
}

// Reads one document; `where_` names the road or junction being read for error messages.
class XodrReader {
 public:
  explicit XodrReader(std::string_view source) : source_(source) {}

  RoadModel read(std::string_view xml);

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw InvalidInput(source_ + ": " + (where_.empty() ? "" : where_ + ": ") + what);
  }
  [[noreturn]] void fail_attribute(const pugi::xml_node& node, const char* name,
                                   const std::string& what) const {
    fail(std::string("<") + node.name() + "> attribute '" + name + "' " + what);
  }

  double number(const pugi::xml_node& node, const char* name) const;
  double number_or(const pugi::xml_node& node, const char* name, double fallback) const;
  int integer(const pugi::xml_node& node, const char* name) const;
  int integer_or(const pugi::xml_node& node, const char* name, int fallback) const;
  [[nodiscard]] Poly3 poly(const pugi::xml_node& node) const;
  CubicProfile profile(const pugi::xml_node& parent, const char* element, const char* s_name) const;
  RoadLink::Contact contact(const pugi::xml_node& node, const char* name) const;

  [[nodiscard]] static GeoFrame frame(const pugi::xml_node& header);
  ModelRoad road(const pugi::xml_node& node);
  [[nodiscard]] PlanView plan_view(const pugi::xml_node& road) const;
  [[nodiscard]] PlanGeometry poly3_geometry(const pugi::xml_node& node, PlanGeometry g) const;
  [[nodiscard]] LaneSection lane_section(const pugi::xml_node& node) const;
  [[nodiscard]] LaneModel lane(const pugi::xml_node& node) const;
  [[nodiscard]] RoadMark road_mark(const pugi::xml_node& lane) const;
  JunctionModel junction(const pugi::xml_node& node);

  std::string source_;
  std::string where_;
};

double XodrReader::number(const pugi::xml_node& node, const char* name) const {
  const pugi::xml_attribute a = node.attribute(name);
  if (!a) fail_attribute(node, name, "is missing");
  std::string_view text = trimmed(a.value());
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  double value = 0.0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || ec != std::errc() || end != text.data() + text.size() || !std::isfinite(value)) {
    fail_attribute(node, name, "is not a finite number: '" + std::string(a.value()) + "'");
  }
  return value;
}

double XodrReader::number_or(const pugi::xml_node& node, const char* name, double fallback) const {
  return node.attribute(name) ? number(node, name) : fallback;
}

int XodrReader::integer(const pugi::xml_node& node, const char* name) const {
  const pugi::xml_attribute a = node.attribute(name);
  if (!a) fail_attribute(node, name, "is missing");
  std::string_view text = trimmed(a.value());
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  int value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || ec != std::errc() || end != text.data() + text.size()) {
    fail_attribute(node, name, "is not an integer: '" + std::string(a.value()) + "'");
  }
  return value;
}

int XodrReader::integer_or(const pugi::xml_node& node, const char* name, int fallback) const {
  const pugi::xml_attribute a = node.attribute(name);
  return a && !trimmed(a.value()).empty() ? integer(node, name) : fallback;
}

Poly3 XodrReader::poly(const pugi::xml_node& node) const {
  // Missing coefficients read as 0 (some writers leave out the zero ones).
  return Poly3{number_or(node, "a", 0.0), number_or(node, "b", 0.0), number_or(node, "c", 0.0),
               number_or(node, "d", 0.0)};
}

CubicProfile XodrReader::profile(const pugi::xml_node& parent, const char* element,
                                 const char* s_name) const {
  std::vector<CubicPiece> pieces;
  for (const pugi::xml_node n : parent.children(element))
    pieces.push_back({number_or(n, s_name, 0.0), poly(n)});
  if (pieces.empty()) return {};
  std::stable_sort(pieces.begin(), pieces.end(),
                   [](const CubicPiece& a, const CubicPiece& b) { return a.s < b.s; });
  try {
    return CubicProfile(std::move(pieces));
  } catch (const InvalidInput& e) {
    fail(std::string("<") + element + ">: " + e.what());
  }
}

RoadLink::Contact XodrReader::contact(const pugi::xml_node& node, const char* name) const {
  const std::string_view text = trimmed(node.attribute(name).value());
  if (text.empty() || text == "start") return RoadLink::Contact::start;
  if (text == "end") return RoadLink::Contact::end;
  fail_attribute(node, name, "is neither 'start' nor 'end': '" + std::string(text) + "'");
}

GeoFrame XodrReader::frame(const pugi::xml_node& header) {
  // relief's own records restore the frame exactly; otherwise the geoReference PROJ string
  // becomes the CRS, with origin 0 (the coordinates are in that CRS).
  std::string crs;
  std::string origin;
  for (const pugi::xml_node u : header.children("userData")) {
    const std::string_view code = u.attribute("code").value();
    if (code == "relief:crs") crs = u.attribute("value").value();
    if (code == "relief:origin") origin = u.attribute("value").value();
  }
  if (!crs.empty() && !origin.empty()) {
    std::istringstream in(origin);
    in.imbue(std::locale::classic());
    double x = 0.0;
    double y = 0.0;
    if ((in >> x >> y) && std::isfinite(x) && std::isfinite(y)) return GeoFrame(crs, Vec2(x, y));
  }
  const std::string proj(trimmed(header.child("geoReference").text().get()));
  if (!proj.empty()) return GeoFrame(proj, Vec2::Zero());
  return {};
}

PlanGeometry XodrReader::poly3_geometry(const pugi::xml_node& node, PlanGeometry g) const {
  // Deprecated poly3: v(u) = a + b u + c u^2 + d u^3 in the start frame, the curve's arc length
  // being the record length. As a normalized paramPoly3: u(p) = U p, v(p) = v(U p), where U
  // solves arclength(U) = length (Newton; d arclength / dU = sqrt(1 + v'(U)^2) >= 1).
  const Poly3 v = poly(node);
  const Poly3 identity{0.0, 1.0, 0.0, 0.0};
  double u_end = g.length;
  for (int iteration = 0; iteration < 60; ++iteration) {
    const double residual = param_poly3_length(identity, v, u_end) - g.length;
    const double slope = std::sqrt(1.0 + v.derivative(u_end) * v.derivative(u_end));
    const double step = residual / slope;
    u_end = std::max(u_end - step, 0.5 * u_end);
    if (std::abs(step) <= 1e-13 * std::max(1.0, g.length)) break;
  }
  if (!std::isfinite(u_end) || u_end <= 0.0) fail("<poly3> has no arc length parametrisation");
  g.kind = PlanGeometry::Kind::param_poly3;
  g.normalized = true;
  g.u = Poly3{0.0, u_end, 0.0, 0.0};
  g.v = Poly3{v.a, v.b * u_end, v.c * u_end * u_end, v.d * u_end * u_end * u_end};
  return g;
}

PlanView XodrReader::plan_view(const pugi::xml_node& road) const {
  const pugi::xml_node plan = road.child("planView");
  if (!plan) fail("no <planView>");
  std::vector<PlanGeometry> records;
  for (const pugi::xml_node n : plan.children("geometry")) {
    PlanGeometry g;
    g.s = number(n, "s");
    g.start = Vec2(number(n, "x"), number(n, "y"));
    g.heading = number(n, "hdg");
    g.length = number(n, "length");
    if (g.length < 0.0) fail_attribute(n, "length", "is negative");
    // Zero-length records (written by some tools at joints) carry no geometry.
    if (g.length <= 1e-12) continue;
    if (n.child("line")) {
      g.kind = PlanGeometry::Kind::line;
    } else if (const pugi::xml_node arc = n.child("arc")) {
      g.kind = PlanGeometry::Kind::arc;
      g.curvature = number(arc, "curvature");
    } else if (const pugi::xml_node spiral = n.child("spiral")) {
      g.kind = PlanGeometry::Kind::spiral;
      g.curvature_start = number(spiral, "curvStart");
      g.curvature_end = number(spiral, "curvEnd");
    } else if (const pugi::xml_node pp = n.child("paramPoly3")) {
      g.kind = PlanGeometry::Kind::param_poly3;
      g.u = Poly3{number_or(pp, "aU", 0.0), number_or(pp, "bU", 0.0), number_or(pp, "cU", 0.0),
                  number_or(pp, "dU", 0.0)};
      g.v = Poly3{number_or(pp, "aV", 0.0), number_or(pp, "bV", 0.0), number_or(pp, "cV", 0.0),
                  number_or(pp, "dV", 0.0)};
      const std::string_view range = trimmed(pp.attribute("pRange").value());
      if (range.empty() || range == "normalized") {
        g.normalized = true;
      } else if (range == "arcLength") {
        g.normalized = false;
      } else {
        fail_attribute(pp, "pRange", "is neither 'arcLength' nor 'normalized': '" + std::string(range) + "'");
      }
    } else if (const pugi::xml_node p3 = n.child("poly3")) {
      g = poly3_geometry(p3, g);
    } else {
      fail("<geometry> at s = " + std::to_string(g.s) + " has no line, arc, spiral, poly3 or paramPoly3");
    }
    records.push_back(g);
  }
  if (records.empty()) fail("<planView> has no geometry");
  std::stable_sort(records.begin(), records.end(),
                   [](const PlanGeometry& a, const PlanGeometry& b) { return a.s < b.s; });
  try {
    return PlanView(std::move(records));
  } catch (const InvalidInput& e) {
    fail(std::string("<planView>: ") + e.what());
  }
}

RoadMark XodrReader::road_mark(const pugi::xml_node& lane) const {
  RoadMark mark;
  const pugi::xml_node n = lane.child("roadMark");
  if (!n) return mark;
  const std::string_view type = trimmed(n.attribute("type").value());
  if (type == "solid") {
    mark.type = RoadMark::Type::solid;
  } else if (type == "broken" || type == "broken broken" || type == "botts dots") {
    mark.type = RoadMark::Type::broken;
  } else if (type == "solid solid") {
    mark.type = RoadMark::Type::solid_solid;
  } else if (type == "solid broken") {
    mark.type = RoadMark::Type::solid_broken;
  } else if (type == "broken solid") {
    mark.type = RoadMark::Type::broken_solid;
  } else {
    mark.type = RoadMark::Type::none;  // none, grass, curb, edge, custom: no painted line
  }
  const std::string_view color = trimmed(n.attribute("color").value());
  if (!color.empty()) mark.color = std::string(color);
  mark.width_m = number_or(n, "width", mark.width_m);
  return mark;
}

LaneModel XodrReader::lane(const pugi::xml_node& node) const {
  LaneModel l;
  l.id = integer(node, "id");
  const std::string_view type = trimmed(node.attribute("type").value());
  l.type = type.empty() ? "none" : std::string(type);
  if (const pugi::xml_node link = node.child("link")) {
    if (const pugi::xml_node p = link.child("predecessor")) l.predecessor = integer(p, "id");
    if (const pugi::xml_node s = link.child("successor")) l.successor = integer(s, "id");
  }
  if (node.child("border")) {
    fail("lane " + std::to_string(l.id) + ": <border> records are not supported (only <width>)");
  }
  l.width = profile(node, "width", "sOffset");
  l.mark = road_mark(node);
  return l;
}

LaneSection XodrReader::lane_section(const pugi::xml_node& node) const {
  LaneSection section;
  section.s = number_or(node, "s", 0.0);
  for (const pugi::xml_node n : node.child("left").children("lane")) {
    section.left.push_back(lane(n));
    if (section.left.back().id <= 0)
      fail("left lane id " + std::to_string(section.left.back().id) + " is not positive");
  }
  for (const pugi::xml_node n : node.child("right").children("lane")) {
    section.right.push_back(lane(n));
    if (section.right.back().id >= 0) {
      fail("right lane id " + std::to_string(section.right.back().id) + " is not negative");
    }
  }
  // Innermost first on both sides: 1, 2, ... and -1, -2, ...
  std::sort(section.left.begin(), section.left.end(),
            [](const LaneModel& a, const LaneModel& b) { return a.id < b.id; });
  std::sort(section.right.begin(), section.right.end(),
            [](const LaneModel& a, const LaneModel& b) { return a.id > b.id; });
  section.centre_mark = road_mark(node.child("center").child("lane"));
  return section;
}

ModelRoad XodrReader::road(const pugi::xml_node& node) {
  ModelRoad r;
  where_.clear();
  r.id = integer(node, "id");
  where_ = "road " + std::to_string(r.id);
  r.name = node.attribute("name").value();
  r.junction = integer_or(node, "junction", -1);

  if (const pugi::xml_node link = node.child("link")) {
    const auto read_link = [&](const pugi::xml_node& n) -> std::optional<RoadLink> {
      if (!n) return std::nullopt;
      RoadLink l;
      const std::string_view type = trimmed(n.attribute("elementType").value());
      if (type.empty() || type == "road") {
        l.element = RoadLink::Element::road;
      } else if (type == "junction") {
        l.element = RoadLink::Element::junction;
      } else {
        fail_attribute(n, "elementType", "is neither 'road' nor 'junction': '" + std::string(type) + "'");
      }
      l.id = integer(n, "elementId");
      l.contact = contact(n, "contactPoint");
      return l;
    };
    r.predecessor = read_link(link.child("predecessor"));
    r.successor = read_link(link.child("successor"));
  }

  if (const pugi::xml_node type = node.child("type")) {
    const std::string_view t = trimmed(type.attribute("type").value());
    if (!t.empty()) r.type = std::string(t);
    if (const pugi::xml_node speed = type.child("speed")) {
      const std::string_view max = trimmed(speed.attribute("max").value());
      if (max != "no limit" && max != "undefined" && !max.empty()) {
        const double value = number(speed, "max");
        const std::string_view unit = trimmed(speed.attribute("unit").value());
        if (unit.empty() || unit == "m/s") {
          r.speed_mps = value;
        } else if (unit == "km/h") {
          r.speed_mps = value / 3.6;
        } else if (unit == "mph") {
          r.speed_mps = value * 0.44704;
        } else {
          fail_attribute(speed, "unit", "is not a speed unit: '" + std::string(unit) + "'");
        }
      }
    }
  }

  r.plan = plan_view(node);
  r.elevation = profile(node.child("elevationProfile"), "elevation", "s");
  r.superelevation = profile(node.child("lateralProfile"), "superelevation", "s");
  const pugi::xml_node lanes = node.child("lanes");
  if (!lanes) fail("no <lanes>");
  r.lane_offset = profile(lanes, "laneOffset", "s");
  for (const pugi::xml_node n : lanes.children("laneSection")) r.sections.push_back(lane_section(n));
  if (r.sections.empty()) fail("<lanes> has no <laneSection>");
  std::stable_sort(r.sections.begin(), r.sections.end(),
                   [](const LaneSection& a, const LaneSection& b) { return a.s < b.s; });
  for (const pugi::xml_node u : node.children("userData")) {
    const std::string_view code = u.attribute("code").value();
    if (code == "relief:osm_ways") {
      std::istringstream in(u.attribute("value").value());
      in.imbue(std::locale::classic());
      for (std::int64_t way = 0; in >> way;) r.osm_way_ids.push_back(way);
      if (!in.eof()) fail_attribute(u, "value", "is not a list of OSM way ids");
    } else if (code == "relief:highway") {
      r.highway = parse_highway_class(trimmed(u.attribute("value").value()));
      if (!r.highway) fail_attribute(u, "value", "is not an OSM highway class relief builds");
    }
  }
  return r;
}

JunctionModel XodrReader::junction(const pugi::xml_node& node) {
  JunctionModel j;
  where_.clear();
  j.id = integer(node, "id");
  where_ = "junction " + std::to_string(j.id);
  j.name = node.attribute("name").value();
  for (const pugi::xml_node n : node.children("connection")) {
    JunctionConnection c;
    c.id = integer(n, "id");
    c.incoming_road = integer_or(n, "incomingRoad", -1);
    // Direct junctions (1.7+) name the road they join as linkedRoad.
    c.connecting_road =
        n.attribute("connectingRoad") ? integer(n, "connectingRoad") : integer_or(n, "linkedRoad", -1);
    c.contact = contact(n, "contactPoint");
    for (const pugi::xml_node ll : n.children("laneLink"))
      c.lane_links.emplace_back(integer(ll, "from"), integer(ll, "to"));
    j.connections.push_back(std::move(c));
  }
  for (const pugi::xml_node u : node.children("userData")) {
    if (std::string_view(u.attribute("code").value()) == "relief:traffic_signal")
      j.traffic_signal = std::string_view(u.attribute("value").value()) == "true";
  }
  return j;
}

RoadModel XodrReader::read(std::string_view xml) {
  pugi::xml_document doc;
  const pugi::xml_parse_result parsed =
      doc.load_buffer(xml.data(), xml.size(), pugi::parse_default, pugi::encoding_auto);
  if (!parsed) {
    fail(std::string("not well-formed XML (") + parsed.description() + " at byte " +
         std::to_string(parsed.offset) + ")");
  }
  const pugi::xml_node root = doc.child("OpenDRIVE");
  if (!root) fail("not an OpenDRIVE file (no <OpenDRIVE> root element)");
  const pugi::xml_node header = root.child("header");
  if (!header) fail("no <header>");

  RoadModel model;
  model.name = header.attribute("name").value();
  model.frame = frame(header);
  for (const pugi::xml_node n : root.children("road")) model.roads.push_back(road(n));
  for (const pugi::xml_node n : root.children("junction")) model.junctions.push_back(junction(n));
  where_.clear();
  if (model.roads.empty()) fail("no <road>");
  return model;
}

}  // namespace

RoadModel read_opendrive(const std::filesystem::path& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    throw IoError("cannot read OpenDRIVE file " + path.string() + ": it is a directory");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError("cannot open OpenDRIVE file " + path.string());
  const std::string content((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw IoError("cannot read OpenDRIVE file " + path.string());
  return XodrReader(path.string()).read(content);
}

RoadModel parse_opendrive(std::string_view xml, std::string_view source) {
  return XodrReader(source).read(xml);
}

}  // namespace relief
