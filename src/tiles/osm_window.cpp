#include "tiles/osm_window.h"

#include <unistd.h>

#include <algorithm>
#include <map>
#include <osmium/io/any_input.hpp>
#include <osmium/io/any_output.hpp>
#include <osmium/memory/buffer.hpp>
#include <osmium/osm/node.hpp>
#include <osmium/osm/way.hpp>
#include <string>

#include "relief/core/errors.h"

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

bool is_built(const osmium::Way& way, const OsmReadOptions& options) {
  if (way.tags()["highway"] == nullptr) return false;
  std::map<std::string, std::string, std::less<>> tags;
  for (const osmium::Tag& tag : way.tags()) tags.emplace(tag.key(), tag.value());
  return builds_way(tags, options);
}

void sort_unique(std::vector<std::int64_t>& ids) {
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
}

bool contains(const std::vector<std::int64_t>& sorted, std::int64_t id) {
  return std::binary_search(sorted.begin(), sorted.end(), id);
}

}  // namespace

std::vector<LonLat> road_node_positions(const std::filesystem::path& osm_path,
                                        const OsmReadOptions& options) {
  std::vector<std::int64_t> ids;
  for_each<osmium::Way>(osm_path, osmium::osm_entity_bits::way, [&](const osmium::Way& way) {
    if (!is_built(way, options)) return;
    for (const osmium::NodeRef& ref : way.nodes()) ids.push_back(ref.ref());
  });
  sort_unique(ids);
  std::vector<LonLat> positions;
  positions.reserve(ids.size());
  for_each<osmium::Node>(osm_path, osmium::osm_entity_bits::node, [&](const osmium::Node& node) {
    if (node.location().valid() && contains(ids, node.id())) {
      positions.push_back({node.location().lon(), node.location().lat()});
    }
  });
  return positions;
}

WindowCounts extract_window(const std::filesystem::path& osm_path, const LonLatBox& window,
                            const OsmReadOptions& options, const std::filesystem::path& out) {
  // Pass 1: the nodes inside the window.
  std::vector<std::int64_t> inside;
  for_each<osmium::Node>(osm_path, osmium::osm_entity_bits::node, [&](const osmium::Node& node) {
    const osmium::Location& p = node.location();
    if (p.valid() && p.lon() >= window.min_lon && p.lon() <= window.max_lon && p.lat() >= window.min_lat &&
        p.lat() <= window.max_lat) {
      inside.push_back(node.id());
    }
  });
  sort_unique(inside);
  // Pass 2: the road ways touching it, whole, and every node they need.
  osmium::memory::Buffer ways(1 << 20, osmium::memory::Buffer::auto_grow::yes);
  std::vector<std::int64_t> needed;
  WindowCounts counts;
  for_each<osmium::Way>(osm_path, osmium::osm_entity_bits::way, [&](const osmium::Way& way) {
    if (!is_built(way, options)) return;
    const auto& refs = way.nodes();
    if (std::none_of(refs.begin(), refs.end(),
                     [&](const osmium::NodeRef& r) { return contains(inside, r.ref()); }))
      return;
    ways.add_item(way);
    ways.commit();
    ++counts.ways;
    for (const osmium::NodeRef& ref : refs) needed.push_back(ref.ref());
  });
  inside = {};
  sort_unique(needed);
  // Pass 3: those nodes with their tags (traffic signals), in the file's order.
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
