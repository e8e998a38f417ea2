#include "tiles/osm_window.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <numeric>
#include <optional>
#include <osmium/io/any_input.hpp>
#include <osmium/io/any_output.hpp>
#include <osmium/memory/buffer.hpp>
#include <osmium/osm/node.hpp>
#include <osmium/osm/way.hpp>
#include <string>

#include "relief/core/errors.h"
#include "relief/roads/way_attributes.h"

namespace relief::detail {
namespace {

osmium::io::Reader open_reader(const std::filesystem::path& path, osmium::osm_entity_bits::type entities) {
  const osmium::io::File file(path.string());
  if (file.format() == osmium::io::file_format::unknown) {
    throw InvalidInput("OSM file " + path.string() +
                       " has an unknown format: expected .osm, .osm.gz, .osm.bz2 or .osm.pbf");
  }
  return osmium::io::Reader(file, entities, osmium::io::read_meta::no);
}

// Calls `visit` for every object of the kind asked for, buffer by buffer.
template <typename Object, typename Visit>
void for_each(const std::filesystem::path& path, osmium::osm_entity_bits::type entities, Visit&& visit) {
  try {
    osmium::io::Reader reader = open_reader(path, entities);
    while (osmium::memory::Buffer buffer = reader.read()) {
      for (const Object& object : buffer.select<Object>()) visit(object);
    }
    reader.close();
  } catch (const Error&) {
    throw;
  } catch (const std::bad_alloc&) {
    throw;
  } catch (const std::exception& e) {
    throw InvalidInput("OSM file " + path.string() + " is malformed or truncated: " + e.what());
  }
}

using TagMap = std::map<std::string, std::string, std::less<>>;

TagMap tag_map(const osmium::Way& way) {
  TagMap tags;
  for (const osmium::Tag& tag : way.tags()) tags.emplace(tag.key(), tag.value());
  return tags;
}

bool is_built(const osmium::Way& way, const OsmReadOptions& options) {
  if (way.tags()["highway"] == nullptr) return false;
  return builds_way(tag_map(way), options);
}

// A road the profile fit does not anchor to the DEM: a bridge or a tunnel as parse_way_tags
// reads them (WayAttributes::bridge, ::tunnel; profile_fit.cpp's is_structure).
bool is_structure(const osmium::Way& way) {
  if (way.tags()["bridge"] == nullptr && way.tags()["tunnel"] == nullptr) return false;
  const std::optional<ParsedWay> parsed = parse_way_tags(tag_map(way), nullptr);
  return parsed && (parsed->attributes.bridge || parsed->attributes.tunnel);
}

void sort_unique(std::vector<std::int64_t>& ids) {
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
}

bool contains(const std::vector<std::int64_t>& sorted, std::int64_t id) {
  return std::binary_search(sorted.begin(), sorted.end(), id);
}

// The region's structure chains: the connected components of the built bridge and tunnel ways,
// joined where two of them share a node. Holds only the structure ways' nodes (their ids, chain
// and position: 28 bytes a node), so its memory grows with the region's structures, not its
// roads.
class StructureChains {
 public:
  StructureChains(const std::filesystem::path& osm_path, const OsmReadOptions& options) {
    std::vector<std::pair<std::int64_t, std::uint32_t>> refs;  // (node, way)
    std::uint32_t ways = 0;
    for_each<osmium::Way>(osm_path, osmium::osm_entity_bits::way, [&](const osmium::Way& way) {
      if (!is_structure(way) || !is_built(way, options)) return;
      for (const osmium::NodeRef& ref : way.nodes()) refs.emplace_back(ref.ref(), ways);
      ++ways;
    });
    std::sort(refs.begin(), refs.end());
    // Union-find over the ways; a node shared by two ways joins them.
    std::vector<std::uint32_t> parent(ways);
    std::iota(parent.begin(), parent.end(), 0U);
    const auto find = [&](std::uint32_t a) {
      while (parent[a] != a) a = parent[a] = parent[parent[a]];
      return a;
    };
    for (std::size_t k = 1; k < refs.size(); ++k) {
      if (refs[k].first == refs[k - 1].first) parent[find(refs[k].second)] = find(refs[k - 1].second);
    }
    for (const auto& [node, way] : refs) {
      if (ids_.empty() || ids_.back() != node) {
        ids_.push_back(node);
        chain_.push_back(find(way));
      }
    }
    positions_.assign(ids_.size(), LonLat{std::nan(""), std::nan("")});
    chains_ = ways;
  }

  /// Number of chain ids (some unused: a chain is named by one of its ways).
  [[nodiscard]] std::size_t size() const { return chains_; }

  /// The chain node `id` belongs to (one at most: ways sharing a node are one chain).
  [[nodiscard]] std::optional<std::uint32_t> chain_at(std::int64_t id) const {
    const auto k = index(id);
    if (!k) return std::nullopt;
    return chain_[*k];
  }

  /// Records the position of node `id` when it is a structure node.
  void locate(std::int64_t id, const LonLat& p) {
    if (const auto k = index(id)) positions_[*k] = p;
  }

  /// Positions of the nodes of the chains marked in `taken` (located ones).
  [[nodiscard]] std::vector<LonLat> positions_of(const std::vector<std::uint8_t>& taken) const {
    std::vector<LonLat> out;
    for (std::size_t k = 0; k < ids_.size(); ++k) {
      if (taken[chain_[k]] && std::isfinite(positions_[k].lon_deg)) out.push_back(positions_[k]);
    }
    return out;
  }

 private:
  [[nodiscard]] std::optional<std::size_t> index(std::int64_t id) const {
    const auto it = std::lower_bound(ids_.begin(), ids_.end(), id);
    if (it == ids_.end() || *it != id) return std::nullopt;
    return static_cast<std::size_t>(it - ids_.begin());
  }

  std::vector<std::int64_t> ids_;  // the structure nodes, sorted
  std::vector<std::uint32_t> chain_;
  std::vector<LonLat> positions_;
  std::size_t chains_ = 0;
};

// Points within `radius_m` of any of a set of points (lon/lat, metres on a local sphere): a
// hash grid of cells `radius_m` wide.
class NearPoints {
 public:
  NearPoints(const std::vector<LonLat>& points, double radius_m) : radius_m_(radius_m) {
    if (points.empty()) return;
    double lat = 0.0;
    for (const LonLat& p : points) lat += p.lat_deg;
    lat /= static_cast<double>(points.size());
    m_per_lat_ = kMetresPerDegree;
    m_per_lon_ = kMetresPerDegree * std::cos(lat * std::numbers::pi / 180.0);
    cell_m_ = std::max(radius_m, 1.0);
    for (const LonLat& p : points) cells_[key(p)].push_back(p);
  }

  [[nodiscard]] bool near(const LonLat& p) const {
    if (cells_.empty()) return false;
    const auto [cx, cy] = key(p);
    for (std::int64_t dx = -1; dx <= 1; ++dx) {
      for (std::int64_t dy = -1; dy <= 1; ++dy) {
        const auto it = cells_.find({cx + dx, cy + dy});
        if (it == cells_.end()) continue;
        for (const LonLat& q : it->second) {
          const double ex = (p.lon_deg - q.lon_deg) * m_per_lon_, ey = (p.lat_deg - q.lat_deg) * m_per_lat_;
          if (ex * ex + ey * ey <= radius_m_ * radius_m_) return true;
        }
      }
    }
    return false;
  }

 private:
  static constexpr double kMetresPerDegree = 6371008.8 * std::numbers::pi / 180.0;
  [[nodiscard]] std::pair<std::int64_t, std::int64_t> key(const LonLat& p) const {
    return {static_cast<std::int64_t>(std::floor(p.lon_deg * m_per_lon_ / cell_m_)),
            static_cast<std::int64_t>(std::floor(p.lat_deg * m_per_lat_ / cell_m_))};
  }

  double radius_m_;
  double m_per_lat_ = 1.0, m_per_lon_ = 1.0, cell_m_ = 1.0;
  std::map<std::pair<std::int64_t, std::int64_t>, std::vector<LonLat>> cells_;
};

}  // namespace

RoadWays read_road_ways(const std::filesystem::path& osm_path, const OsmReadOptions& options) {
  RoadWays out;
  std::vector<std::int64_t> refs;
  for_each<osmium::Way>(osm_path, osmium::osm_entity_bits::way, [&](const osmium::Way& way) {
    if (!is_built(way, options)) return;
    out.way_ids.push_back(way.id());
    out.offsets.push_back(refs.size());
    for (const osmium::NodeRef& ref : way.nodes()) refs.push_back(ref.ref());
  });
  out.offsets.push_back(refs.size());
  std::vector<std::int64_t> ids = refs;
  sort_unique(ids);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<LonLat> at(ids.size(), LonLat{nan, nan});
  for_each<osmium::Node>(osm_path, osmium::osm_entity_bits::node, [&](const osmium::Node& node) {
    const auto it = std::lower_bound(ids.begin(), ids.end(), node.id());
    if (it != ids.end() && *it == node.id() && node.location().valid())
      at[static_cast<std::size_t>(it - ids.begin())] = {node.location().lon(), node.location().lat()};
  });
  out.points.reserve(refs.size());
  for (const std::int64_t ref : refs)
    out.points.push_back(
        at[static_cast<std::size_t>(std::lower_bound(ids.begin(), ids.end(), ref) - ids.begin())]);
  for (const LonLat& p : at)
    if (std::isfinite(p.lon_deg)) out.nodes.push_back(p);
  return out;
}

WindowCounts extract_window(const std::filesystem::path& osm_path, const LonLatBox& window, double halo_m,
                            const std::vector<std::int64_t>& crossing_ways, const OsmReadOptions& options,
                            const std::filesystem::path& out) {
  // The region's structure chains (a pass over the ways).
  StructureChains chains(osm_path, options);
  // The nodes inside the window; the structure nodes' positions (a pass over the nodes).
  std::vector<std::int64_t> inside;
  for_each<osmium::Node>(osm_path, osmium::osm_entity_bits::node, [&](const osmium::Node& node) {
    const osmium::Location& p = node.location();
    if (!p.valid()) return;
    chains.locate(node.id(), {p.lon(), p.lat()});
    if (p.lon() >= window.min_lon && p.lon() <= window.max_lon && p.lat() >= window.min_lat &&
        p.lat() <= window.max_lat) {
      inside.push_back(node.id());
    }
  });
  sort_unique(inside);
  // The ways with a node in the zone (first the window), whole. A structure chain one of them
  // touches (a structure way in the zone, or one's abutment) is taken whole, with the ground
  // within the halo of any of its nodes (its approaches and what fixes them), since the fit
  // spans a structure between all its abutments: the zone grows by those nodes and the ways are
  // read again. Chains that only ways of a chain's halo touch are taken whole only with more
  // than one level (README, tiles: two levels halve what is left on Portland at twice the cost).
  constexpr int kChainLevels = 1;
  std::vector<std::int64_t> zone = inside;
  std::vector<std::uint8_t> taken(chains.size(), 0);
  osmium::memory::Buffer ways(1 << 20, osmium::memory::Buffer::auto_grow::yes);
  WindowCounts counts;
  for (int level = 0;; ++level) {
    ways = osmium::memory::Buffer(1 << 20, osmium::memory::Buffer::auto_grow::yes);
    counts = WindowCounts{};
    std::vector<std::uint32_t> reached;
    for_each<osmium::Way>(osm_path, osmium::osm_entity_bits::way, [&](const osmium::Way& way) {
      if (!is_built(way, options)) return;
      const auto& refs = way.nodes();
      const bool crossing = contains(crossing_ways, way.id());
      if (!crossing && std::none_of(refs.begin(), refs.end(),
                                    [&](const osmium::NodeRef& r) { return contains(zone, r.ref()); }))
        return;
      ways.add_item(way);
      ways.commit();
      ++counts.ways;
      if (!crossing && std::none_of(refs.begin(), refs.end(),
                                    [&](const osmium::NodeRef& r) { return contains(inside, r.ref()); }))
        ++counts.chain_ways;
      for (const osmium::NodeRef& ref : refs) {
        if (const auto c = chains.chain_at(ref.ref()); c && !taken[*c]) reached.push_back(*c);
      }
    });
    if (reached.empty() || level == kChainLevels) break;
    for (const std::uint32_t c : reached) taken[c] = 1;
    // The zone: the window and every node within the halo of a taken chain's node.
    const NearPoints near(chains.positions_of(taken), halo_m);
    zone = inside;
    for_each<osmium::Node>(osm_path, osmium::osm_entity_bits::node, [&](const osmium::Node& node) {
      const osmium::Location& p = node.location();
      if (p.valid() && near.near({p.lon(), p.lat()})) zone.push_back(node.id());
    });
    sort_unique(zone);
  }
  inside = {};
  zone = {};
  // The ways' nodes.
  std::vector<std::int64_t> needed;
  std::vector<std::int64_t> way_ids;
  for (const osmium::Way& way : ways.select<osmium::Way>()) {
    way_ids.push_back(way.id());
    for (const osmium::NodeRef& ref : way.nodes()) needed.push_back(ref.ref());
  }
  sort_unique(needed);
  sort_unique(way_ids);
  // The ways that share a node with a taken way, in two rings: a road ends where another way
  // joins it, so a taken way is split into the same roads as in a whole build only with every
  // way that joins it (the first ring: else a long road a window sees one end of is one road
  // there and two elsewhere, and no tile owns the piece), and its junctions are the same kind and
  // join into the same clusters only with what joins those ways too (the second ring: the stubs
  // of a divided street's crossing, junction_clusters.h).
  constexpr int kNeighbourRings = 2;
  for (int ring = 0; ring < kNeighbourRings; ++ring) {
    std::vector<std::int64_t> added, added_ways;
    for_each<osmium::Way>(osm_path, osmium::osm_entity_bits::way, [&](const osmium::Way& way) {
      if (contains(way_ids, way.id()) || !is_built(way, options)) return;
      const auto& refs = way.nodes();
      if (std::none_of(refs.begin(), refs.end(),
                       [&](const osmium::NodeRef& r) { return contains(needed, r.ref()); }))
        return;
      ways.add_item(way);
      ways.commit();
      ++counts.ways;
      ++counts.neighbour_ways;
      added_ways.push_back(way.id());
      for (const osmium::NodeRef& ref : refs) added.push_back(ref.ref());
    });
    if (added.empty()) break;
    way_ids.insert(way_ids.end(), added_ways.begin(), added_ways.end());
    sort_unique(way_ids);
    needed.insert(needed.end(), added.begin(), added.end());
    sort_unique(needed);
  }
  // Those nodes with their tags (traffic signals), in the file's order.
  osmium::memory::Buffer nodes(1 << 20, osmium::memory::Buffer::auto_grow::yes);
  for_each<osmium::Node>(osm_path, osmium::osm_entity_bits::node, [&](const osmium::Node& node) {
    if (!contains(needed, node.id())) return;
    nodes.add_item(node);
    nodes.commit();
    ++counts.nodes;
  });
  // Through a temporary (its own name per process, the format told by its ".osm.pbf"): a build
  // of the same tile running beside this one never reads a half-written window.
  const std::filesystem::path temporary =
      out.parent_path() / ("window.tmp-" + std::to_string(::getpid()) + ".osm.pbf");
  try {
    osmium::io::Header header;
    header.set("generator", "relief tiles");
    header.add_box(osmium::Box(window.min_lon, window.min_lat, window.max_lon, window.max_lat));
    osmium::io::Writer writer(temporary.string(), header, osmium::io::overwrite::allow);
    writer(std::move(nodes));
    writer(std::move(ways));
    writer.close();
    std::filesystem::rename(temporary, out);
  } catch (const std::exception& e) {
    std::error_code ec;
    std::filesystem::remove(temporary, ec);
    throw IoError("cannot write " + out.string() + ": " + e.what());
  }
  return counts;
}

}  // namespace relief::detail
