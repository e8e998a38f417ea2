#include "relief/export/opendrive_writer.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <set>
#include <string>
#include <string_view>

#include "relief/core/errors.h"
#include "relief/core/number_format.h"
#include "relief/core/xml_writer.h"
#include "relief/export/geojson_writer.h"

namespace relief {
namespace {

// Enumerations of the ASAM schemas (OpenDRIVE_1.4H.xsd, opendrive_17_*.xsd, 1.8.1/OpenDRIVE_*.xsd)
// for the values the model carries as free text: a value outside them would not validate.
constexpr std::array kRoadTypes14{"unknown",  "rural",      "motorway", "town",
                                  "lowSpeed", "pedestrian", "bicycle"};
constexpr std::array kRoadTypes17{"townExpressway", "townCollector", "townArterial",
                                  "townPrivate",    "townLocal",     "townPlayStreet"};
constexpr std::array kLaneTypes14{
    "none",       "driving", "stop",          "shoulder", "biking",   "sidewalk", "border",
    "restricted", "parking", "bidirectional", "median",   "special1", "special2", "special3",
    "roadWorks",  "tram",    "rail",          "entry",    "exit",     "offRamp",  "onRamp"};
constexpr std::array kLaneTypes17{"curb", "connectingRamp", "bus", "taxi", "HOV", "mwyEntry", "mwyExit"};
constexpr std::array kLaneTypes18{"shared", "walking", "slipLane"};
constexpr std::array kColors14{"standard", "blue", "green", "red", "white", "yellow"};
constexpr std::array kColors17{"orange", "violet"};
constexpr std::array kColors18{"black"};

template <std::size_t N>
bool contains(const std::array<const char*, N>& list, std::string_view value) {
  return std::any_of(list.begin(), list.end(), [&](const char* v) { return value == v; });
}

bool valid_road_type(std::string_view t, int minor) {
  return contains(kRoadTypes14, t) || (minor >= 7 && contains(kRoadTypes17, t));
}
bool valid_lane_type(std::string_view t, int minor) {
  return contains(kLaneTypes14, t) || (minor >= 7 && contains(kLaneTypes17, t)) ||
         (minor >= 8 && contains(kLaneTypes18, t));
}
bool valid_color(std::string_view c, int minor) {
  return contains(kColors14, c) || (minor >= 7 && contains(kColors17, c)) ||
         (minor >= 8 && contains(kColors18, c));
}

const char* mark_type_name(RoadMark::Type type) {
  switch (type) {
    case RoadMark::Type::none:
      return "none";
    case RoadMark::Type::solid:
      return "solid";
    case RoadMark::Type::broken:
      return "broken";
    case RoadMark::Type::solid_solid:
      return "solid solid";
    case RoadMark::Type::solid_broken:
      return "solid broken";
    case RoadMark::Type::broken_solid:
      return "broken solid";
  }
  return "none";
}

const char* geometry_element(PlanGeometry::Kind kind) {
  switch (kind) {
    case PlanGeometry::Kind::line:
      return "line";
    case PlanGeometry::Kind::arc:
      return "arc";
    case PlanGeometry::Kind::spiral:
      return "spiral";
    case PlanGeometry::Kind::param_poly3:
      return "paramPoly3";
  }
  return "line";
}

const char* contact_name(RoadLink::Contact c) {
  return c == RoadLink::Contact::start ? "start" : "end";
}

// Builds the document in one string through XmlWriter: numbers are checked and printed at a
// fixed precision. `where_` names the road or junction being written for error messages.
class XodrWriter {
 public:
  XodrWriter(const RoadModel& model, const OpenDriveOptions& options)
      : model_(model), options_(options), xml_(out_, {.indent = 2}) {}

  std::string run();

 private:
  void header();
  void road(const ModelRoad& road);
  void plan_view(const ModelRoad& road);
  void profile(const char* element, const char* s_name, const CubicProfile& profile);
  void lane_section(const LaneSection& section);
  void lane(const LaneModel& lane);
  void road_mark(const RoadMark& mark);
  void junction(const JunctionModel& junction);

  void start(const char* name) {
    xml_.start(name);
    element_ = name;
  }
  void end(const char* name) { xml_.end(name); }
  void attr(const char* name, std::string_view text) { xml_.attribute(name, text); }
  void attr(const char* name, double value);
  /// Polynomial coefficients: the shortest text that reads back exactly (they span many
  /// orders of magnitude; fixed decimals would lose d at 1e-9 over hundreds of metres).
  void attr_coefficient(const char* name, double value);
  void attr_int(const char* name, long long value) { xml_.attribute_int(name, value); }
  void user_data(std::string_view code, std::string_view value) {
    start("userData");
    attr("code", code);
    attr("value", value);
    end("userData");
  }
  void attr_positive(const char* name, double value);  // schema type t_grZero
  void poly(const Poly3& p);
  void check_finite(const char* name, double value) const;
  [[noreturn]] void fail(const std::string& what) const;

  const RoadModel& model_;
  const OpenDriveOptions& options_;
  std::string out_;
  XmlWriter xml_;
  std::string where_ = "header";
  std::string element_;
};

void XodrWriter::fail(const std::string& what) const {
  throw InvalidInput("OpenDRIVE writer: " + where_ + ": " + what);
}

void XodrWriter::check_finite(const char* name, double value) const {
  if (!std::isfinite(value)) {
    fail("<" + element_ + "> attribute '" + name + "' is not a finite number");
  }
}

void XodrWriter::attr(const char* name, double value) {
  check_finite(name, value);
  xml_.attribute_fixed(name, value, options_.decimals);
}

void XodrWriter::attr_coefficient(const char* name, double value) {
  check_finite(name, value);
  xml_.attribute_shortest(name, value);
}

void XodrWriter::attr_positive(const char* name, double value) {
  // Must stay > 0 once printed at the chosen precision.
  if (std::isfinite(value) && !(value >= 0.5 * std::pow(10.0, -options_.decimals))) {
    fail("<" + element_ + "> attribute '" + name + "' must be positive at " +
         std::to_string(options_.decimals) + " decimals");
  }
  attr(name, value);
}

void XodrWriter::poly(const Poly3& p) {
  attr("a", p.a);
  attr_coefficient("b", p.b);
  attr_coefficient("c", p.c);
  attr_coefficient("d", p.d);
}

std::string XodrWriter::run() {
  if (options_.rev_minor != 4 && options_.rev_minor != 7 && options_.rev_minor != 8) {
    throw InvalidInput("OpenDRIVE writer: revision 1." + std::to_string(options_.rev_minor) +
                       " is not supported (1.4, 1.7 or 1.8)");
  }
  if (options_.decimals < 0 || options_.decimals > 17) {
    throw InvalidInput("OpenDRIVE writer: decimals must be in [0, 17], got " +
                       std::to_string(options_.decimals));
  }
  if (model_.roads.empty()) throw InvalidInput("OpenDRIVE writer: the model has no roads");
  for (const ModelRoad& r : model_.roads) {
    if (r.plan.records().empty()) {
      throw InvalidInput("OpenDRIVE writer: road " + std::to_string(r.id) + " has no planView geometry");
    }
  }
  out_.reserve(4096 + model_.roads.size() * 4096);
  xml_.declaration();
  start("OpenDRIVE");
  header();
  for (const ModelRoad& r : model_.roads) road(r);
  for (const JunctionModel& j : model_.junctions) junction(j);
  end("OpenDRIVE");
  xml_.finish();
  return std::move(out_);
}

void XodrWriter::header() {
  // Bounds of the reference lines, sampled every metre and at every record start and the end.
  Aabb2 box;
  for (const ModelRoad& r : model_.roads) {
    where_ = "road " + std::to_string(r.id);
    const double length = r.plan.length();
    if (!std::isfinite(length)) fail("planView length is not a finite number");
    for (const PlanGeometry& g : r.plan.records()) box.extend(g.start);
    const auto steps = static_cast<long long>(std::floor(length));
    for (long long i = 0; i <= steps; ++i) box.extend(r.plan.at(static_cast<double>(i)).position);
    box.extend(r.plan.at(length).position);
  }
  where_ = "header";

  const std::string& name = options_.name.empty() ? model_.name : options_.name;
  start("header");
  attr_int("revMajor", 1);
  attr_int("revMinor", options_.rev_minor);
  attr("name", name);
  attr("version", "1");
  if (!options_.date.empty()) attr("date", options_.date);
  attr("north", box.max.y());
  attr("south", box.min.y());
  attr("east", box.max.x());
  attr("west", box.min.x());
  attr("vendor", options_.vendor);

  // The ODbL attribution, readable by anyone who opens the file (a comment is valid anywhere).
  const std::string attribution = kOsmAttribution;
  xml_.comment(attribution);

  // geoReference: the PROJ string as CDATA.
  start("geoReference");
  xml_.cdata(model_.frame.proj_string());
  end("geoReference");
  if (options_.rev_minor >= 7) {
    // Coordinates are already in the frame of the geoReference: no further offset.
    start("offset");
    attr("x", 0.0);
    attr("y", 0.0);
    attr("z", 0.0);
    attr("hdg", 0.0);
    end("offset");
  }
  if (options_.rev_minor >= 8) {
    start("license");
    attr("name", "Open Data Commons Open Database License 1.0");
    attr("resource", "https://opendatacommons.org/licenses/odbl/1-0/");
    attr("spdxid", "ODbL-1.0");
    attr("text", attribution);
    end("license");
  }
  user_data("attribution", attribution);
  // relief's own frame (CRS and origin), so that reading the file back restores it exactly.
  user_data("relief:crs", model_.frame.crs());
  std::string origin;
  const Vec2& o = model_.frame.origin();
  if (!std::isfinite(o.x()) || !std::isfinite(o.y())) fail("the frame origin is not finite");
  append_fixed(origin, o.x(), 3);
  origin += ' ';
  append_fixed(origin, o.y(), 3);
  user_data("relief:origin", origin);
  end("header");
}

void XodrWriter::road(const ModelRoad& r) {
  where_ = "road " + std::to_string(r.id);
  const int minor = options_.rev_minor;
  if (!valid_road_type(r.type, minor))
    fail("road type '" + r.type + "' is not an OpenDRIVE 1." + std::to_string(minor) + " road type");
  if (r.sections.empty()) fail("no lane section");
  if (r.sections.front().s != 0.0) fail("the first lane section does not start at s = 0");
  for (std::size_t i = 1; i < r.sections.size(); ++i) {
    if (!(r.sections[i].s > r.sections[i - 1].s)) fail("lane sections are not sorted by s");
  }

  start("road");
  attr("name", r.name);
  attr_positive("length", r.plan.length());
  attr_int("id", r.id);
  attr_int("junction", r.junction);

  if (r.predecessor || r.successor) {
    start("link");
    const auto link = [&](const char* tag, const RoadLink& l) {
      start(tag);
      attr("elementType", l.element == RoadLink::Element::road ? "road" : "junction");
      attr_int("elementId", l.id);
      if (l.element == RoadLink::Element::road) attr("contactPoint", contact_name(l.contact));
      end(tag);
    };
    if (r.predecessor) link("predecessor", *r.predecessor);
    if (r.successor) link("successor", *r.successor);
    end("link");
  }

  start("type");
  attr("s", 0.0);
  attr("type", r.type);
  if (r.speed_mps) {
    start("speed");
    if (!(*r.speed_mps >= 0.0)) fail("<speed> is negative or not a number");
    if (minor == 4) {
      // 1.4 allows only a whole number: km/h keeps posted limits exact.
      attr_int("max", std::llround(*r.speed_mps * 3.6));
      attr("unit", "km/h");
    } else {
      attr("max", *r.speed_mps);
      attr("unit", "m/s");
    }
    end("speed");
  }
  end("type");

  plan_view(r);

  // Elevation and superelevation: an empty profile is the constant 0, written as one record.
  start("elevationProfile");
  profile("elevation", "s", r.elevation.empty() ? CubicProfile::constant(0.0) : r.elevation);
  end("elevationProfile");
  start("lateralProfile");
  profile("superelevation", "s", r.superelevation.empty() ? CubicProfile::constant(0.0) : r.superelevation);
  end("lateralProfile");
  start("lanes");
  profile("laneOffset", "s", r.lane_offset);
  for (const LaneSection& section : r.sections) lane_section(section);
  end("lanes");
  // Where the road came from in OSM, as additional data other readers skip: a region merged from
  // tiles builds its SUMO network (edge types, OSM mapping) from these (tiles/).
  if (!r.osm_way_ids.empty()) {
    std::string ways;
    for (const std::int64_t w : r.osm_way_ids) {
      if (!ways.empty()) ways += ' ';
      ways += std::to_string(w);
    }
    user_data("relief:osm_ways", ways);
  }
  if (r.highway) user_data("relief:highway", std::string(to_string(*r.highway)));
  end("road");
}

void XodrWriter::plan_view(const ModelRoad& r) {
  start("planView");
  for (const PlanGeometry& g : r.plan.records()) {
    start("geometry");
    attr("s", g.s);
    attr("x", g.start.x());
    attr("y", g.start.y());
    attr("hdg", g.heading);
    attr_positive("length", g.length);
    const char* kind = geometry_element(g.kind);
    start(kind);
    switch (g.kind) {
      case PlanGeometry::Kind::line:
        break;
      case PlanGeometry::Kind::arc:
        attr_coefficient("curvature", g.curvature);
        break;
      case PlanGeometry::Kind::spiral:
        attr_coefficient("curvStart", g.curvature_start);
        attr_coefficient("curvEnd", g.curvature_end);
        break;
      case PlanGeometry::Kind::param_poly3:
        attr("aU", g.u.a);
        attr_coefficient("bU", g.u.b);
        attr_coefficient("cU", g.u.c);
        attr_coefficient("dU", g.u.d);
        attr("aV", g.v.a);
        attr_coefficient("bV", g.v.b);
        attr_coefficient("cV", g.v.c);
        attr_coefficient("dV", g.v.d);
        attr("pRange", g.normalized ? "normalized" : "arcLength");
        break;
    }
    end(kind);
    end("geometry");
  }
  end("planView");
}

void XodrWriter::profile(const char* element, const char* s_name, const CubicProfile& p) {
  for (const CubicPiece& piece : p.pieces()) {
    start(element);
    attr(s_name, piece.s);
    poly(piece.poly);
    end(element);
  }
}

void XodrWriter::lane_section(const LaneSection& section) {
  std::set<int> ids;
  for (const auto* side : {&section.left, &section.right}) {
    for (const LaneModel& l : *side) {
      if (!ids.insert(l.id).second)
        fail("lane id " + std::to_string(l.id) + " appears twice in one lane section");
    }
  }
  start("laneSection");
  attr("s", section.s);
  // Lanes in the order of the standard's examples: left 2, 1, centre 0, right -1, -2.
  if (!section.left.empty()) {
    std::vector<const LaneModel*> lanes;
    for (const LaneModel& l : section.left) {
      if (l.id <= 0) fail("left lane id " + std::to_string(l.id) + " is not positive");
      lanes.push_back(&l);
    }
    std::sort(lanes.begin(), lanes.end(),
              [](const LaneModel* a, const LaneModel* b) { return a->id > b->id; });
    start("left");
    for (const LaneModel* l : lanes) lane(*l);
    end("left");
  }
  start("center");
  start("lane");
  attr_int("id", 0);
  attr("type", "none");
  attr("level", "false");
  road_mark(section.centre_mark);
  end("lane");
  end("center");
  if (!section.right.empty()) {
    std::vector<const LaneModel*> lanes;
    for (const LaneModel& l : section.right) {
      if (l.id >= 0) fail("right lane id " + std::to_string(l.id) + " is not negative");
      lanes.push_back(&l);
    }
    std::sort(lanes.begin(), lanes.end(),
              [](const LaneModel* a, const LaneModel* b) { return a->id > b->id; });
    start("right");
    for (const LaneModel* l : lanes) lane(*l);
    end("right");
  }
  end("laneSection");
}

void XodrWriter::lane(const LaneModel& l) {
  if (!valid_lane_type(l.type, options_.rev_minor)) {
    fail("lane " + std::to_string(l.id) + ": type '" + l.type + "' is not an OpenDRIVE 1." +
         std::to_string(options_.rev_minor) + " lane type");
  }
  start("lane");
  attr_int("id", l.id);
  attr("type", l.type);
  attr("level", "false");
  if (l.predecessor || l.successor) {
    start("link");
    if (l.predecessor) {
      start("predecessor");
      attr_int("id", *l.predecessor);
      end("predecessor");
    }
    if (l.successor) {
      start("successor");
      attr_int("id", *l.successor);
      end("successor");
    }
    end("link");
  }
  // A lane without width records has width 0; 1.4 requires at least one record.
  profile("width", "sOffset", l.width.empty() ? CubicProfile::constant(0.0) : l.width);
  road_mark(l.mark);
  end("lane");
}

void XodrWriter::road_mark(const RoadMark& mark) {
  if (!valid_color(mark.color, options_.rev_minor))
    fail("road mark color '" + mark.color + "' is not an OpenDRIVE colour");
  start("roadMark");
  attr("sOffset", 0.0);
  attr("type", mark_type_name(mark.type));
  attr("weight", "standard");
  attr("color", mark.color);
  if (!(mark.width_m >= 0.0) && std::isfinite(mark.width_m)) fail("road mark width is negative");
  attr("width", mark.width_m);
  end("roadMark");
}

void XodrWriter::junction(const JunctionModel& j) {
  where_ = "junction " + std::to_string(j.id);
  if (j.connections.empty()) fail("no connection (OpenDRIVE requires at least one)");
  start("junction");
  attr("name", j.name);
  attr_int("id", j.id);
  for (const JunctionConnection& c : j.connections) {
    start("connection");
    attr_int("id", c.id);
    attr_int("incomingRoad", c.incoming_road);
    attr_int("connectingRoad", c.connecting_road);
    attr("contactPoint", contact_name(c.contact));
    for (const auto& [from, to] : c.lane_links) {
      start("laneLink");
      attr_int("from", from);
      attr_int("to", to);
      end("laneLink");
    }
    end("connection");
  }
  if (j.traffic_signal) user_data("relief:traffic_signal", "true");
  end("junction");
}

}  // namespace

void write_opendrive(std::ostream& out, const RoadModel& model, const OpenDriveOptions& options) {
  const std::string text = XodrWriter(model, options).run();
  out.write(text.data(), static_cast<std::streamsize>(text.size()));
}

}  // namespace relief
