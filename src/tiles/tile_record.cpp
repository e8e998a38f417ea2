#include "tiles/tile_record.h"

#include <algorithm>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "relief/core/atomic_file.h"
#include "relief/core/file_hash.h"

namespace relief::detail {

std::optional<TileRecord> read_tile_record(const std::filesystem::path& tile_dir) {
  std::ifstream in(tile_dir / kTileRecordFile);
  if (!in) return std::nullopt;
  try {
    const nlohmann::json j = nlohmann::json::parse(in);
    TileRecord r;
    r.key = j.at("key").get<std::string>();
    r.x = j.at("x").get<int>();
    r.y = j.at("y").get<int>();
    r.status = j.at("status").get<std::string>();
    r.seconds = j.at("seconds").get<double>();
    r.peak_rss_mb = j.value("peak_rss_mb", 0.0);
    r.window_ways = j.at("window").at("ways").get<std::size_t>();
    r.window_nodes = j.at("window").at("nodes").get<std::size_t>();
    r.window_chain_ways = j.at("window").value("chain_ways", std::size_t{0});
    r.window_neighbour_ways = j.at("window").value("neighbour_ways", std::size_t{0});
    if (j.contains("holds")) {
      const auto& h = j.at("holds");
      r.holds_from = h.at("from").get<std::vector<std::string>>();
      r.holds_missing = h.at("missing").get<std::vector<std::string>>();
      r.held_variables = h.at("held_variables").get<std::size_t>();
      r.holds_mismatched = h.at("mismatched_roads").get<std::size_t>();
    }
    r.failed_gates = j.at("failed_gates").get<std::vector<std::string>>();
    r.halo_gates = j.at("halo_gates").get<std::vector<std::string>>();
    return r;
  } catch (const std::exception&) {
    return std::nullopt;  // a damaged record: the tile is built again
  }
}

void write_tile_record(const std::filesystem::path& tile_dir, const TileRecord& record,
                       const RunReport& report) {
  nlohmann::json j;
  j["key"] = record.key;
  j["x"] = record.x;
  j["y"] = record.y;
  j["status"] = record.status;
  j["seconds"] = record.seconds;
  j["peak_rss_mb"] = record.peak_rss_mb;
  j["window"] = {{"ways", record.window_ways},
                 {"nodes", record.window_nodes},
                 {"chain_ways", record.window_chain_ways},
                 {"neighbour_ways", record.window_neighbour_ways}};
  j["holds"] = {{"from", record.holds_from},
                {"missing", record.holds_missing},
                {"held_variables", record.held_variables},
                {"mismatched_roads", record.holds_mismatched}};
  j["failed_gates"] = record.failed_gates;
  j["halo_gates"] = record.halo_gates;
  j["gates"] = nlohmann::json::object();
  for (const Gate& g : report.gates) {
    j["gates"][g.name] = {
        {"value", g.value}, {"threshold", g.threshold}, {"passed", g.passed}, {"where", g.where}};
  }
  j["network"] = {{"roads", report.network.roads},
                  {"junctions", report.network.junctions},
                  {"length_km", report.network.length_km}};
  write_file_atomically(tile_dir / kTileRecordFile, j.dump(1) + "\n");
}

DependencyState dependency_state(const std::filesystem::path& dir, const TileManifest& manifest,
                                 const TileSpec& tile) {
  DependencyState out;
  out.key = tile_key(manifest, tile);
  std::vector<const TileSpec*> deps = tile_dependencies(manifest, tile);
  if (deps.empty()) return out;
  std::stable_sort(deps.begin(), deps.end(),
                   [](const TileSpec* a, const TileSpec* b) { return tile_phase(*a) < tile_phase(*b); });
  std::string keys = out.key;
  for (const TileSpec* d : deps) {
    const std::string name = std::to_string(d->x) + "," + std::to_string(d->y);
    const std::filesystem::path there = tile_dir(dir, d->x, d->y);
    const std::optional<TileRecord> record = read_tile_record(there);
    if (!record || !std::filesystem::exists(there / kHoldsFile)) {
      out.missing_names.push_back(name);
      keys += " " + name + ":missing";
      continue;
    }
    out.built.push_back(d);
    out.built_names.push_back(name);
    keys += " " + name + ":" + record->key;
  }
  out.key = sha256_hex(keys);
  return out;
}

}  // namespace relief::detail
