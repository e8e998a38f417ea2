#include "relief/roads/osm_reader.h"

#include <algorithm>
#include <map>
#include <new>
#include <set>
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

    parts = split_retraces(std::move(parts), way.id());

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
  // A way drawn out to a node and straight back (... X, Y, X ...) has no reference line through
  // Y (its two legs lie on each other): the stretch X-Y becomes a part of its own, drawn once,
  // and the way goes on from X. A stretch retraced over several nodes comes apart into one part
  // per segment, joined at its nodes like the way was.
  std::vector<OsmWay> split_retraces(std::vector<OsmWay> parts, std::int64_t way_id) {
    std::vector<OsmWay> out;
    std::set<std::pair<std::int64_t, std::int64_t>> spurs;
    for (OsmWay& part : parts) {
      OsmWay main;
      for (std::size_t i = 0; i < part.node_ids.size(); ++i) {
        const std::int64_t id = part.node_ids[i];
        const std::size_t n = main.node_ids.size();
        if (n >= 2 && main.node_ids[n - 2] == id) {
          const std::int64_t tip = main.node_ids[n - 1];
          if (spurs.insert({std::min(id, tip), std::max(id, tip)}).second) {
            OsmWay spur;
            spur.node_ids = {id, tip};
            spur.nodes = {main.nodes[n - 2], main.nodes[n - 1]};
            out.push_back(std::move(spur));
            report_turn_back(way_id, tip, id);
          }
          main.node_ids.pop_back();
          main.nodes.pop_back();
          continue;
        }
        main.node_ids.push_back(id);
        main.nodes.push_back(part.nodes[i]);
      }
      out.push_back(std::move(main));
    }
    return out;
  }

  void report_turn_back(std::int64_t way_id, std::int64_t tip, std::int64_t from) {
    Diagnostic d;
    d.severity = Severity::warning;
    d.code = codes::kOsmWayTurnsBack;
    d.message = "way " + std::to_string(way_id) + " turns straight back at node " + std::to_string(tip) +
                " (drawn from node " + std::to_string(from) +
                " out to it and back): the stretch is built once, a way of its own";
    d.osm_way_id = way_id;
    d.osm_node_id = tip;
    diagnostics_.report(std::move(d));
  }

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

// Ways drawn over the nodes of another (JOSM's "duplicated ways" and "overlapping ways": a
// street drawn twice, a route or an area outline along a street): two roads on one ground,
// between the same nodes, whose junctions swallowed the street between them. Each segment
// (a pair of consecutive nodes, either direction) is built once, by the way of the higher
// class (then the lower id); the later way is cut where it runs over it and keeps the rest.
std::vector<OsmWay> drop_overlaps(std::vector<OsmWay> ways, Diagnostics& diagnostics) {
  std::vector<std::size_t> order(ways.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return std::tie(ways[a].attributes.highway, ways[a].id) <
           std::tie(ways[b].attributes.highway, ways[b].id);
  });
  std::map<std::pair<std::int64_t, std::int64_t>, std::int64_t> owner;  // segment -> way id
  std::vector<std::vector<OsmWay>> kept(ways.size());
  for (const std::size_t w : order) {
    const OsmWay& way = ways[w];
    std::map<std::int64_t, std::size_t> over;  // way id -> segments of it this way runs over
    OsmWay run;
    const auto close_run = [&] {
      if (run.node_ids.size() >= 2) kept[w].push_back(run);
      run = OsmWay{};
      run.id = way.id;
      run.attributes = way.attributes;
    };
    close_run();
    for (std::size_t k = 0; k + 1 < way.node_ids.size(); ++k) {
      const std::int64_t a = way.node_ids[k], b = way.node_ids[k + 1];
      const auto [it, fresh] = owner.try_emplace({std::min(a, b), std::max(a, b)}, way.id);
      if (!fresh && it->second != way.id) {
        ++over[it->second];
        close_run();
        continue;
      }
      if (run.node_ids.empty()) {
        run.node_ids.push_back(a);
        run.nodes.push_back(way.nodes[k]);
      }
      run.node_ids.push_back(b);
      run.nodes.push_back(way.nodes[k + 1]);
    }
    close_run();
    for (const auto& [other, segments] : over) {
      Diagnostic d;
      d.severity = Severity::warning;
      d.code = codes::kOsmOverlappingWays;
      d.message = "way " + std::to_string(way.id) + " runs over " + std::to_string(segments) +
                  " segment(s) of way " + std::to_string(other) + " (the same nodes): built once, as way " +
                  std::to_string(other) +
                  (kept[w].empty() ? "; nothing of it is left" : "; the rest of it is kept");
      d.osm_way_id = way.id;
      diagnostics.report(std::move(d));
    }
  }
  std::vector<OsmWay> out;
  out.reserve(ways.size());
  for (auto& parts : kept) {
    for (OsmWay& part : parts) out.push_back(std::move(part));
  }
  return out;
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

  roads.ways = drop_overlaps(std::move(roads.ways), diagnostics);
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
