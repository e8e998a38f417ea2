#include <sys/resource.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "relief/core/atomic_file.h"
#include "relief/core/diagnostic_codes.h"
#include "relief/core/errors.h"
#include "relief/export/quality_gates.h"
#include "relief/tiles/tiles.h"
#include "tiles/osm_window.h"
#include "tiles/owner_surface.h"
#include "tiles/tile_holds.h"
#include "tiles/tile_record.h"

namespace relief {
namespace {

const TileInput& osm_input(const TileManifest& manifest) {
  for (const TileInput& in : manifest.inputs) {
    if (in.role == "osm") return in;
  }
  throw InvalidInput("the tile manifest names no OSM input");
}

// The place a failed gate names: the first "(x, y" of its text (quality_gates.cpp writes places
// as "(x, y)" or "(x, y, z)" in the local frame).
std::optional<Vec2> gate_place(const std::string& where) {
  for (std::size_t open = where.find('('); open != std::string::npos; open = where.find('(', open + 1)) {
    double x = 0.0, y = 0.0;
    if (std::sscanf(where.c_str() + open, "(%lf, %lf", &x, &y) == 2) return Vec2(x, y);
  }
  return std::nullopt;
}

}  // namespace

TileBuildResult build_tile(const std::filesystem::path& dir, const TileManifest& manifest, int x, int y,
                           BuildOptions options, Diagnostics& diagnostics, bool force) {
  const TileSpec* spec = manifest.find(x, y);
  if (spec == nullptr) {
    throw OptionError("tile " + std::to_string(x) + "," + std::to_string(y) +
                      " is not in the plan (only tiles with roads in their core are)");
  }
  const std::filesystem::path here = tile_dir(dir, x, y);
  // The dependencies' holds, in the order of their phases (an earlier tile's value stands where
  // two give one); their keys are in this tile's, so it is built again when one is.
  const detail::DependencyState deps = detail::dependency_state(dir, manifest, *spec);
  const std::string& key = deps.key;
  TileBuildResult result;
  if (!force) {
    if (const std::optional<detail::TileRecord> record = detail::read_tile_record(here)) {
      if (record->key == key) {
        result.status = "skipped";
        result.failed_gates = record->failed_gates;
        result.halo_gates = record->halo_gates;
        return result;
      }
    }
  }
  const auto started = std::chrono::steady_clock::now();
  std::filesystem::create_directories(here);
  std::filesystem::remove(here / detail::kTileRecordFile);  // a tile that fails keeps none
  // The outputs of an earlier build, and the temporaries of one that was killed, go.
  std::filesystem::remove_all(here / "out");
  std::filesystem::remove(here / detail::kHoldsFile);
  std::filesystem::remove(here / detail::kOwnedSurfaceFile);

  const std::filesystem::path window = here / "window.osm.pbf";
  const detail::WindowCounts counts = detail::extract_window(
      osm_input(manifest).path, spec->window, manifest.halo_m, spec->crossing_ways, options.osm, window);

  options.osm_path = window;
  options.out_dir = here / "out";
  options.name = manifest.name;
  options.crs = manifest.frame.crs();
  options.frame_centre = manifest.frame_centre;
  options.osm.bbox.reset();
  options.mesh_core_size_m = manifest.tile_size_m;
  options.mesh_core_column = std::llround(spec->core.min.x() / manifest.tile_size_m);
  options.mesh_core_row = std::llround(spec->core.min.y() / manifest.tile_size_m);
  options.mesh_tile_size_m = 0.0;
  options.carla_package = false;
  detail::TileHolds holds;
  for (const TileSpec* d : deps.built)
    detail::add_holds(holds, detail::read_holds(tile_dir(dir, d->x, d->y) / detail::kHoldsFile));
  std::size_t mismatched = 0;
  options.hold_profiles = [&](const RoadNetwork& network, const std::vector<RoadProfile>& raw) {
    return detail::index_holds(network, raw, holds, mismatched);
  };
  options.fitted = [&](const RoadNetwork& network, const ProfileFitResult& fit, const RoadModel& model) {
    detail::write_holds(here / detail::kHoldsFile, detail::tile_holds(network, fit, model, spec->core));
  };
  options.meshed = [&](const RoadModel& model, const Scene& scene) {
    detail::write_owned_surface(here / detail::kOwnedSurfaceFile,
                                detail::owned_surface(model, scene, spec->core));
  };
  const BuildResult built = build(options, diagnostics);
  if (!std::filesystem::exists(here / detail::kHoldsFile)) detail::write_holds(here / detail::kHoldsFile, {});

  detail::TileRecord record;
  record.key = key;
  record.x = x;
  record.y = y;
  record.window_ways = counts.ways;
  record.window_nodes = counts.nodes;
  record.window_chain_ways = counts.chain_ways;
  record.window_neighbour_ways = counts.neighbour_ways;
  record.holds_from = deps.built_names;
  record.holds_missing = deps.missing_names;
  record.held_variables = built.report.fit ? built.report.fit->held_variables : 0;
  record.holds_mismatched = mismatched;
  // A gate that fails at a place outside the core is the halo's: the window ends there, cutting
  // the network short, and the tile that owns the place checks it with its whole context.
  for (const Gate& g : failed_gates(built.report.gates)) {
    const std::optional<Vec2> place = gate_place(g.where);
    const bool halo = place && !(place->x() >= spec->core.min.x() && place->x() < spec->core.max.x() &&
                                 place->y() >= spec->core.min.y() && place->y() < spec->core.max.y());
    (halo ? record.halo_gates : record.failed_gates).push_back(g.name);
    if (halo) {
      diagnostics.report(Severity::info, codes::kTilesHaloGate,
                         g.name + " failed in tile " + std::to_string(x) + "," + std::to_string(y) +
                             "'s halo only: " + g.where);
    }
  }
  record.status = record.failed_gates.empty() ? "built" : "gates_failed";
  record.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  rusage usage{};
  if (getrusage(RUSAGE_SELF, &usage) == 0) record.peak_rss_mb = static_cast<double>(usage.ru_maxrss) / 1024.0;
  detail::write_tile_record(here, record, built.report);
  result.status = record.status;
  result.seconds = record.seconds;
  result.failed_gates = record.failed_gates;
  result.halo_gates = record.halo_gates;
  return result;
}

}  // namespace relief
