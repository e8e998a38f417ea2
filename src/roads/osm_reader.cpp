#include "relief/roads/osm_reader.h"

#include <algorithm>
#include <map>
#include <new>
#include <sstream>
#include <string>
#include <system_error>
#include <tuple>
#include <utility>

#include <osmium/handler.hpp>
#include <osmium/handler/node_locations_for_ways.hpp>
#include <osmium/index/map/flex_mem.hpp>
#include <osmium/io/any_input.hpp>
#include <osmium/osm/box.hpp>
#include <osmium/osm/node.hpp>
#include <osmium/osm/way.hpp>
#include <osmium/visitor.hpp>

#include "relief/core/diagnostic_codes.h"
#include "relief/core/errors.h"

namespace relief {

namespace {

using LocationIndex = osmium::index::map::FlexMem<osmium::unsigned_object_id_type, osmium::Location>;
// Negative ids (unsaved JOSM edits) get their own index instead of being lost.
using LocationHandler = osmium::handler::NodeLocationsForWays<LocationIndex, LocationIndex>;

std::string quoted(const std::filesystem::path& path) {
  return "'" + path.string() + "'";
}

// Collects traffic signals and the road ways, split at missing nodes, while libosmium reads.
class RoadHandler : public osmium::handler::Handler {
 public:
  RoadHandler(const OsmReadOptions& options, Diagnostics& diagnostics, OsmRoads& roads)
      : options_(options), diagnostics_(diagnostics), roads_(roads) {}

  [[nodiscard]] std::int64_t min_node_id() const { return min_node_id_; }

  void node(const osmium::Node& node) {
    min_node_id_ = std::min<std::int64_t>(min_node_id_, node.id());
    const char* highway = node.tags()["highway"];
    if (highway != nullptr && std::string_view(highway) == "traffic_signals") {
      roads_.traffic_signals.insert(node.id());
    }
  }

  void way(const osmium::Way& way) {
    ++roads_.ways_read;
    if (way.tags()["highway"] == nullptr) return;
    ++roads_.highway_ways;

    std::map<std::string, std::string, std::less<>> tags;
    for (const osmium::Tag& tag : way.tags()) tags.emplace(tag.key(), tag.value());
    std::string warnings;
    const auto parsed = parse_way_tags(tags, &warnings);
    if (!parsed || (!options_.include_non_motor && !is_motor_road(parsed->attributes.highway))) {
      ++roads_.ways_skipped_class;
      return;
    }
    if (!warnings.empty()) {
      Diagnostic d;
      d.severity = Severity::warning;
      d.code = codes::kOsmTagValue;
      d.message = "way " + std::to_string(way.id()) + ": " + warnings;
      d.osm_way_id = way.id();
      diagnostics_.report(std::move(d));
    }

    // Node refs in traffic direction (oneway=-1 reversed); an invalid location is a missing node.
    std::vector<const osmium::NodeRef*> refs;
    refs.reserve(way.nodes().size());
    for (const osmium::NodeRef& ref : way.nodes()) refs.push_back(&ref);
    if (parsed->reversed) std::reverse(refs.begin(), refs.end());

    // Runs of present nodes; consecutive repeats of one node collapsed.
    std::vector<OsmWay> parts(1);
    std::size_t missing = 0;
    for (const osmium::NodeRef* ref : refs) {
      if (!ref->location().valid()) {
        ++missing;
        report_missing(way.id(), ref->ref());
        if (!parts.back().node_ids.empty()) parts.emplace_back();
        continue;
      }
      OsmWay& part = parts.back();
      if (!part.node_ids.empty() && part.node_ids.back() == ref->ref()) continue;
      part.node_ids.push_back(ref->ref());
      part.nodes.push_back({ref->location().lon(), ref->location().lat()});
    }
    if (missing > 0) {
      ++roads_.ways_with_missing_nodes;
      roads_.missing_node_refs += missing;
    }

    // After collapsing repeats, two node ids mean two distinct nodes.
    bool kept = false;
    for (OsmWay& part : parts) {
      if (part.node_ids.size() < 2) continue;
      part.id = way.id();
      part.attributes = parsed->attributes;
      roads_.ways.push_back(std::move(part));
      kept = true;
    }
    if (!kept && missing == 0) {
      Diagnostic d;
      d.severity = Severity::warning;
      d.code = codes::kOsmDegenerateWay;
      d.message = "way " + std::to_string(way.id()) + " has fewer than two distinct nodes; skipped";
      d.osm_way_id = way.id();
      diagnostics_.report(std::move(d));
    }
  }

 private:
  void report_missing(std::int64_t way_id, std::int64_t node_id) {
    Diagnostic d;
    d.severity = Severity::warning;
    d.code = codes::kOsmMissingNode;
    d.message = "way " + std::to_string(way_id) + " references node " + std::to_string(node_id) +
                ", which is not in the file; the way is split there";
    d.osm_way_id = way_id;
    d.osm_node_id = node_id;
    diagnostics_.report(std::move(d));
  }

  const OsmReadOptions& options_;
  Diagnostics& diagnostics_;
  OsmRoads& roads_;
  std::int64_t min_node_id_ = 0;
};

// Parameters [t0, t1] of the part of segment a->b inside `box` (Liang-Barsky), or nullopt when
// the segment misses the box. Boundary points count as inside.
std::optional<std::pair<double, double>> clip_segment(const LonLat& a, const LonLat& b,
                                                      const LonLatBox& box) {
  const double dx = b.lon_deg - a.lon_deg;
  const double dy = b.lat_deg - a.lat_deg;
  const double p[4] = {-dx, dx, -dy, dy};
  const double q[4] = {a.lon_deg - box.min_lon, box.max_lon - a.lon_deg, a.lat_deg - box.min_lat,
                       box.max_lat - a.lat_deg};
  double t0 = 0.0;
  double t1 = 1.0;
  for (int i = 0; i < 4; ++i) {
    if (p[i] == 0.0) {
      if (q[i] < 0.0) return std::nullopt;  // parallel to this edge and outside it
      continue;
    }
    const double r = q[i] / p[i];
    if (p[i] < 0.0) {
      if (r > t1) return std::nullopt;
      t0 = std::max(t0, r);
    } else {
      if (r < t0) return std::nullopt;
      t1 = std::min(t1, r);
    }
  }
  return std::make_pair(t0, t1);
}

// Cuts ways at the edge of `box`, keeping each inside run as its own OsmWay. A crossing node is
// keyed by its segment's node pair (lower id first) and parameter along it, so two ways sharing
// the segment get the same synthetic id; parameters are computed in that normalised direction
// so that they are bit-identical for both.
std::vector<OsmWay> clip_ways(const std::vector<OsmWay>& ways, const LonLatBox& box,
                              std::int64_t first_synthetic_id) {
  std::map<std::tuple<std::int64_t, std::int64_t, double>, std::int64_t> crossing_ids;
  std::int64_t next_id = first_synthetic_id;
  std::vector<OsmWay> out;

  for (const OsmWay& way : ways) {
    OsmWay run;
    run.id = way.id;
    run.attributes = way.attributes;
    const auto flush = [&] {
      if (run.node_ids.size() >= 2) out.push_back(run);
      run.node_ids.clear();
      run.nodes.clear();
    };
    const auto append = [&](std::int64_t id, const LonLat& pos) {
      if (!run.node_ids.empty() && run.node_ids.back() == id) return;
      run.node_ids.push_back(id);
      run.nodes.push_back(pos);
    };

    for (std::size_t i = 0; i + 1 < way.node_ids.size(); ++i) {
      // Normalised segment lo -> hi (lower node id first).
      const bool swapped = way.node_ids[i] > way.node_ids[i + 1];
      const std::size_t lo = swapped ? i + 1 : i;
      const std::size_t hi = swapped ? i : i + 1;
      const auto t = clip_segment(way.nodes[lo], way.nodes[hi], box);
      if (!t) {
        flush();
        continue;
      }
      // The node at normalised parameter s: an original end or a (shared) crossing node.
      const auto point = [&](double s) -> std::pair<std::int64_t, LonLat> {
        if (s <= 0.0) return {way.node_ids[lo], way.nodes[lo]};
        if (s >= 1.0) return {way.node_ids[hi], way.nodes[hi]};
        const LonLat& a = way.nodes[lo];
        const LonLat& b = way.nodes[hi];
        const LonLat p{std::clamp(a.lon_deg + s * (b.lon_deg - a.lon_deg), box.min_lon, box.max_lon),
                       std::clamp(a.lat_deg + s * (b.lat_deg - a.lat_deg), box.min_lat, box.max_lat)};
        const auto key = std::make_tuple(way.node_ids[lo], way.node_ids[hi], s);
        auto [it, inserted] = crossing_ids.emplace(key, next_id);
        if (inserted) --next_id;
        return {it->second, p};
      };
      // In the way's direction: enter at the start parameter, leave at the end parameter.
      const double enter = swapped ? t->second : t->first;
      const double leave = swapped ? t->first : t->second;
      const bool enters_by_crossing = swapped ? enter < 1.0 : enter > 0.0;
      const bool leaves_by_crossing = swapped ? leave > 0.0 : leave < 1.0;
      if (enters_by_crossing) flush();
      const auto [enter_id, enter_pos] = point(enter);
      append(enter_id, enter_pos);
      const auto [leave_id, leave_pos] = point(leave);
      append(leave_id, leave_pos);
      if (leaves_by_crossing) flush();
    }
    flush();
  }
  return out;
}

}  // namespace

bool builds_way(const std::map<std::string, std::string, std::less<>>& tags, const OsmReadOptions& options) {
  const auto highway = tags.find("highway");
  if (highway == tags.end()) return false;
  const auto parsed = parse_way_tags(tags, nullptr);
  return parsed && (options.include_non_motor || is_motor_road(parsed->attributes.highway));
}

OsmRoads read_osm(const std::filesystem::path& path, const OsmReadOptions& options,
                  Diagnostics& diagnostics) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    throw IoError("cannot open OSM file " + quoted(path) + ": " +
                  (std::filesystem::exists(path, ec) ? "not a regular file" : "no such file"));
  }

  OsmRoads roads;
  RoadHandler handler(options, diagnostics, roads);
  try {
    const osmium::io::File file(path.string());
    if (file.format() == osmium::io::file_format::unknown) {
      throw InvalidInput("OSM file " + quoted(path) +
                         " has an unknown format: expected .osm, .osm.gz, .osm.bz2 or .osm.pbf");
    }
    osmium::io::Reader reader(file, osmium::osm_entity_bits::node | osmium::osm_entity_bits::way,
                              osmium::io::read_meta::no);
    const osmium::Box box = reader.header().box();
    if (box.valid()) {
      roads.header_bounds = LonLatBox{box.bottom_left().lon(), box.bottom_left().lat(), box.top_right().lon(),
                                      box.top_right().lat()};
    }
    LocationIndex positive_ids;
    LocationIndex negative_ids;
    LocationHandler locations(positive_ids, negative_ids);
    locations.ignore_errors();  // missing nodes become invalid locations, handled per way
    osmium::apply(reader, locations, handler);
    // A truncated compressed stream may only be detected when the reader finishes.
    reader.close();
  } catch (const Error&) {
    throw;
  } catch (const osmium::unsupported_file_format_error& e) {
    throw InvalidInput("OSM file " + quoted(path) + " has an unsupported format: " + e.what());
  } catch (const std::bad_alloc&) {
    throw;
  } catch (const std::system_error& e) {
    throw IoError("cannot read OSM file " + quoted(path) + ": " + e.what());
  } catch (const std::exception& e) {
    // osmium::xml_error, pbf_error, gzip_error, bzip2_error, io_error and the decompressors'
    // std::runtime_error all mean the content is unusable.
    throw InvalidInput("OSM file " + quoted(path) + " is malformed or truncated: " + e.what());
  }

  if (options.bbox) {
    const std::int64_t first_synthetic_id = std::min<std::int64_t>(-1, handler.min_node_id() - 1);
    roads.ways = clip_ways(roads.ways, *options.bbox, first_synthetic_id);
  }

  if (roads.ways.empty()) {
    std::ostringstream what;
    what << "OSM file " << quoted(path) << " contains no roads"
         << (options.bbox ? " inside the clip box" : "") << " (" << roads.ways_read << " ways, "
         << roads.highway_ways << " with a highway tag, " << roads.ways_skipped_class
         << " of classes not built"
         << (options.include_non_motor ? ")" : "; footways and paths need include_non_motor)");
    throw InvalidInput(what.str());
  }

  bool first = true;
  for (const OsmWay& way : roads.ways) {
    for (const LonLat& p : way.nodes) {
      if (first) {
        roads.bounds = {p.lon_deg, p.lat_deg, p.lon_deg, p.lat_deg};
        first = false;
      }
      roads.bounds.min_lon = std::min(roads.bounds.min_lon, p.lon_deg);
      roads.bounds.min_lat = std::min(roads.bounds.min_lat, p.lat_deg);
      roads.bounds.max_lon = std::max(roads.bounds.max_lon, p.lon_deg);
      roads.bounds.max_lat = std::max(roads.bounds.max_lat, p.lat_deg);
    }
  }
  return roads;
}

}  // namespace relief
