#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <span>
#include <sstream>

#include "relief/core/atomic_file.h"
#include "relief/core/errors.h"
#include "relief/core/file_hash.h"
#include "relief/export/report_writer.h"
#include "relief/geometry/crs_transform.h"
#include "relief/tiles/tiles.h"
#include "tiles/osm_window.h"
#include "tiles/segment_cells.h"

namespace relief {
namespace {

constexpr int kManifestVersion = 2;
constexpr const char* kManifestFile = "manifest.json";

LonLatBox bounds_of(const std::vector<LonLat>& points) {
  LonLatBox box{points.front().lon_deg, points.front().lat_deg, points.front().lon_deg,
                points.front().lat_deg};
  for (const LonLat& p : points) {
    box.min_lon = std::min(box.min_lon, p.lon_deg);
    box.min_lat = std::min(box.min_lat, p.lat_deg);
    box.max_lon = std::max(box.max_lon, p.lon_deg);
    box.max_lat = std::max(box.max_lat, p.lat_deg);
  }
  return box;
}

// WGS84 box around a local box: its border sampled every 1/16 of a side (a projected square is
// not a lon/lat rectangle), widened by 1 % of the halo for the curvature between samples.
LonLatBox lon_lat_box(const CrsTransform& to_wgs84, const GeoFrame& frame, const Aabb2& local,
                      double margin_m) {
  LonLatBox box{180.0, 90.0, -180.0, -90.0};
  constexpr int kSteps = 16;
  const Vec2 size = local.max - local.min;
  for (int i = 0; i <= kSteps; ++i) {
    const double f = static_cast<double>(i) / kSteps;
    for (const Vec2& p : {Vec2(local.min.x() + f * size.x(), local.min.y()),
                          Vec2(local.min.x() + f * size.x(), local.max.y()),
                          Vec2(local.min.x(), local.min.y() + f * size.y()),
                          Vec2(local.max.x(), local.min.y() + f * size.y())}) {
      const Vec2 ll = to_wgs84.apply(frame.to_crs(p));
      box.min_lon = std::min(box.min_lon, ll.x());
      box.min_lat = std::min(box.min_lat, ll.y());
      box.max_lon = std::max(box.max_lon, ll.x());
      box.max_lat = std::max(box.max_lat, ll.y());
    }
  }
  const double dlat = margin_m / 111e3;
  const double dlon = dlat / std::max(0.05, std::cos((box.min_lat + box.max_lat) * M_PI / 360.0));
  return {box.min_lon - dlon, box.min_lat - dlat, box.max_lon + dlon, box.max_lat + dlat};
}

nlohmann::json box_json(const Aabb2& b) {
  return {b.min.x(), b.min.y(), b.max.x(), b.max.y()};
}

}  // namespace

const TileSpec* TileManifest::find(int x, int y) const {
  for (const TileSpec& t : tiles) {
    if (t.x == x && t.y == y) return &t;
  }
  return nullptr;
}

std::string TileManifest::to_json() const {
  nlohmann::json j;
  j["manifest_version"] = kManifestVersion;
  j["relief_version"] = relief_version();
  j["name"] = name;
  j["frame"] = {{"crs", frame.crs()},
                {"origin", {frame.origin().x(), frame.origin().y()}},
                {"centre_lon_lat", {frame_centre.lon_deg, frame_centre.lat_deg}}};
  j["tile_size_m"] = tile_size_m;
  j["halo_m"] = halo_m;
  j["hold_neighbours"] = hold_neighbours;
  j["grid_origin"] = {grid_origin.x(), grid_origin.y()};
  j["inputs"] = nlohmann::json::array();
  for (const TileInput& in : inputs)
    j["inputs"].push_back({{"role", in.role}, {"path", in.path}, {"sha256", in.sha256}});
  j["build_args"] = build_args;
  j["tiles"] = nlohmann::json::array();
  for (const TileSpec& t : tiles) {
    j["tiles"].push_back(
        {{"x", t.x},
         {"y", t.y},
         {"core", box_json(t.core)},
         {"window_lon_lat", {t.window.min_lon, t.window.min_lat, t.window.max_lon, t.window.max_lat}},
         {"road_nodes", t.road_nodes},
         {"phase", tile_phase(t)},
         {"crossing_ways", t.crossing_ways}});
  }
  return j.dump(1) + "\n";
}

TileManifest TileManifest::from_json(std::string_view text, std::string_view source) {
  try {
    const nlohmann::json j = nlohmann::json::parse(text);
    if (j.at("manifest_version").get<int>() != kManifestVersion) {
      throw InvalidInput(std::string(source) + ": manifest version " + j.at("manifest_version").dump() +
                         " is not " + std::to_string(kManifestVersion) + "; plan the tiles again");
    }
    TileManifest m;
    m.name = j.at("name").get<std::string>();
    const auto& f = j.at("frame");
    m.frame = GeoFrame(f.at("crs").get<std::string>(),
                       Vec2(f.at("origin")[0].get<double>(), f.at("origin")[1].get<double>()));
    m.frame_centre = {f.at("centre_lon_lat")[0].get<double>(), f.at("centre_lon_lat")[1].get<double>()};
    m.tile_size_m = j.at("tile_size_m").get<double>();
    m.halo_m = j.at("halo_m").get<double>();
    m.hold_neighbours = j.at("hold_neighbours").get<bool>();
    m.grid_origin = Vec2(j.at("grid_origin")[0].get<double>(), j.at("grid_origin")[1].get<double>());
    for (const auto& in : j.at("inputs")) {
      m.inputs.push_back({in.at("path").get<std::string>(), in.at("sha256").get<std::string>(),
                          in.at("role").get<std::string>()});
    }
    m.build_args = j.at("build_args").get<std::vector<std::string>>();
    for (const auto& t : j.at("tiles")) {
      TileSpec s;
      s.x = t.at("x").get<int>();
      s.y = t.at("y").get<int>();
      const auto& c = t.at("core");
      s.core =
          Aabb2{Vec2(c[0].get<double>(), c[1].get<double>()), Vec2(c[2].get<double>(), c[3].get<double>())};
      const auto& w = t.at("window_lon_lat");
      s.window = {w[0].get<double>(), w[1].get<double>(), w[2].get<double>(), w[3].get<double>()};
      s.road_nodes = t.at("road_nodes").get<std::size_t>();
      s.crossing_ways = t.at("crossing_ways").get<std::vector<std::int64_t>>();
      m.tiles.push_back(s);
    }
    return m;
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    throw InvalidInput(std::string(source) + " is not a relief tile manifest: " + e.what());
  }
}

TileManifest read_manifest(const std::filesystem::path& dir) {
  const std::filesystem::path path = dir / kManifestFile;
  std::ifstream in(path);
  if (!in) throw IoError("cannot read " + path.string() + ": plan the tiles first (relief tiles plan)");
  std::stringstream text;
  text << in.rdbuf();
  return TileManifest::from_json(text.str(), path.string());
}

void write_manifest(const std::filesystem::path& dir, const TileManifest& manifest) {
  std::filesystem::create_directories(dir);
  write_file_atomically(dir / kManifestFile, manifest.to_json());
}

std::filesystem::path tile_dir(const std::filesystem::path& dir, int x, int y) {
  return dir / "tiles" / (std::to_string(x) + "_" + std::to_string(y));
}

std::string tile_key(const TileManifest& manifest, const TileSpec& tile) {
  // The running program's own bytes, hashed once per process: a rebuilt relief builds its tiles
  // again, whatever its version string says (about 20 ms for relief's 8 MB).
  static const std::string program = [] {
    try {
      return sha256_of_file("/proc/self/exe");
    } catch (const Error&) {
      return std::string("unknown");
    }
  }();
  nlohmann::json j;
  j["relief_version"] = relief_version();
  j["program_sha256"] = program;
  j["frame"] = {manifest.frame.crs(), manifest.frame.origin().x(), manifest.frame.origin().y()};
  j["grid"] = {manifest.tile_size_m, manifest.halo_m, manifest.grid_origin.x(), manifest.grid_origin.y()};
  j["hold_neighbours"] = manifest.hold_neighbours;
  j["tile"] = {tile.x, tile.y};
  j["crossing_ways"] = tile.crossing_ways;
  // What a window holds (osm_window.h): a tile built under another rule is built again.
  j["window"] =
      "ways in the window; their structure chains, with the ways within the halo of them; "
      "two rings of the ways that join them; the ways crossing the window";
  j["inputs"] = nlohmann::json::array();
  for (const TileInput& in : manifest.inputs) j["inputs"].push_back(in.sha256);
  j["build_args"] = manifest.build_args;
  return sha256_hex(j.dump());
}

int tile_phase(const TileSpec& tile) {
  return (tile.x & 1) + 2 * (tile.y & 1);
}

std::vector<const TileSpec*> tile_dependencies(const TileManifest& manifest, const TileSpec& tile) {
  std::vector<const TileSpec*> out;
  if (!manifest.hold_neighbours) return out;
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      const TileSpec* n = (dx == 0 && dy == 0) ? nullptr : manifest.find(tile.x + dx, tile.y + dy);
      if (n != nullptr && tile_phase(*n) < tile_phase(tile)) out.push_back(n);
    }
  }
  return out;
}

std::vector<const TileSpec*> build_order(const TileManifest& manifest) {
  std::vector<const TileSpec*> order;
  for (const TileSpec& t : manifest.tiles) order.push_back(&t);
  std::stable_sort(order.begin(), order.end(),
                   [](const TileSpec* a, const TileSpec* b) { return tile_phase(*a) < tile_phase(*b); });
  return order;
}

TileManifest plan_tiles(const TilePlanOptions& options) {
  if (!(std::isfinite(options.tile_size_m) && options.tile_size_m > 0.0)) {
    throw OptionError("tile size " + std::to_string(options.tile_size_m) + " m is not a finite number > 0");
  }
  if (!(std::isfinite(options.halo_m) && options.halo_m >= 0.0)) {
    throw OptionError("halo " + std::to_string(options.halo_m) + " m is not a finite number >= 0");
  }
  std::error_code ec;
  if (!std::filesystem::is_regular_file(options.osm_path, ec)) {
    throw IoError("cannot open OSM file " + options.osm_path.string() + ": no such file");
  }
  detail::RoadWays roads = detail::read_road_ways(options.osm_path, options.osm);
  if (roads.nodes.empty())
    throw InvalidInput("OSM file " + options.osm_path.string() + " contains no roads relief builds");

  TileManifest m;
  m.name = options.name.empty() ? default_name(options.osm_path) : options.name;
  m.frame_centre = options.frame_centre ? *options.frame_centre : bounds_of(roads.nodes).centre();
  m.frame = options.crs ? GeoFrame::in_crs(*options.crs, m.frame_centre) : GeoFrame::utm_at(m.frame_centre);
  m.tile_size_m = options.tile_size_m;
  m.halo_m = options.halo_m;
  m.hold_neighbours = options.hold_neighbours;
  m.build_args = options.build_args;

  // Project in one batch, count per grid cell (multiples of the tile size in the local frame).
  const CrsTransform to_frame("EPSG:4326", m.frame.crs());
  const auto project = [&](std::vector<LonLat>& points) {
    std::vector<Vec2> local(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) local[i] = Vec2(points[i].lon_deg, points[i].lat_deg);
    points = {};
    to_frame.apply(std::span<Vec2>(local));
    for (Vec2& p : local) p = m.frame.to_local(p);
    return local;
  };
  const double size = m.tile_size_m;
  const auto cell_of = [&](double v) { return static_cast<long long>(std::floor(v / size)); };
  std::map<std::pair<long long, long long>, std::size_t> cells;  // (row, column) -> nodes
  for (const Vec2& p : project(roads.nodes)) {
    if (p.allFinite()) ++cells[{cell_of(p.y()), cell_of(p.x())}];
  }
  // A tile owns a road by its reference line's midpoint, which may lie where the road has no
  // node (a long segment across a cell): every cell a segment passes within 1 m of is a tile.
  // A segment that crosses a window without a node in it (longer than the halo) is listed for
  // that tile, whose window takes its way.
  const std::vector<Vec2> points = project(roads.points);
  std::map<std::pair<long long, long long>, std::vector<std::int64_t>> crossing;  // (row, column) -> ways
  const double halo = m.halo_m;
  for (std::size_t w = 0; w < roads.way_ids.size(); ++w) {
    std::set<std::pair<long long, long long>> crossed, with_node;
    for (std::size_t k = roads.offsets[w]; k < roads.offsets[w + 1]; ++k) {
      const Vec2& p = points[k];
      if (!p.allFinite()) continue;
      for (long long r = cell_of(p.y() - halo); r <= cell_of(p.y() + halo); ++r)
        for (long long c = cell_of(p.x() - halo); c <= cell_of(p.x() + halo); ++c) with_node.insert({r, c});
      if (k + 1 == roads.offsets[w + 1] || !points[k + 1].allFinite()) continue;
      detail::cells_near_segment(p, points[k + 1], size, 1.0, [&](long long c, long long r) {
        cells.try_emplace({r, c}, 0);
      });
      detail::cells_near_segment(p, points[k + 1], size, halo, [&](long long c, long long r) {
        crossed.insert({r, c});
      });
    }
    for (const auto& cell : crossed)
      if (!with_node.contains(cell)) crossing[cell].push_back(roads.way_ids[w]);
  }
  roads = {};
  long long min_row = cells.begin()->first.first, min_col = cells.begin()->first.second;
  for (const auto& [cell, count] : cells) min_col = std::min(min_col, cell.second);
  m.grid_origin = m.tile_size_m * Vec2(static_cast<double>(min_col), static_cast<double>(min_row));
  const CrsTransform to_wgs84(m.frame.crs(), "EPSG:4326");
  for (const auto& [cell, count] : cells) {
    TileSpec t;
    t.x = static_cast<int>(cell.second - min_col);
    t.y = static_cast<int>(cell.first - min_row);
    const Vec2 lo = m.tile_size_m * Vec2(static_cast<double>(cell.second), static_cast<double>(cell.first));
    t.core = Aabb2{lo, lo + Vec2::Constant(m.tile_size_m)};
    Aabb2 window = t.core;
    window.min -= Vec2::Constant(m.halo_m);
    window.max += Vec2::Constant(m.halo_m);
    t.window = lon_lat_box(to_wgs84, m.frame, window, 0.01 * m.halo_m + 1.0);
    t.road_nodes = count;
    if (const auto it = crossing.find(cell); it != crossing.end()) {
      t.crossing_ways = it->second;
      std::sort(t.crossing_ways.begin(), t.crossing_ways.end());
    }
    m.tiles.push_back(t);
  }
  // Absolute: the tiles are built wherever their builder runs (tile_build reads the OSM from here).
  m.inputs.push_back(
      {absolute_input_path(options.osm_path.string()), sha256_of_file(options.osm_path), "osm"});
  for (const std::string& dem : options.dem_paths)
    m.inputs.push_back({absolute_input_path(dem), sha256_of_file(dem), "dem"});
  return m;
}

}  // namespace relief
