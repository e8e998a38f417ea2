// `relief tiles plan|build|merge`: region-scale conversion in tiles (relief/tiles/tiles.h).
#include <algorithm>
#include <atomic>
#include <iostream>
#include <memory>
#include <mutex>
#include <set>
#include <thread>

#include "build_args.h"
#include "commands.h"
#include "console.h"
#include "options.h"
#include "relief/core/errors.h"
#include "relief/core/file_hash.h"
#include "relief/core/subprocess.h"
#include "relief/tiles/tiles.h"

namespace relief::cli {
namespace {

// Options of `tiles plan` that the plan itself takes; every other one is a build option the
// tiles are built with.
const std::set<std::string> kPlanOnly = {
    "--osm",  "--out", "--tile-size", "--halo", "--hold-neighbours", "--no-hold-neighbours",
    "--name", "--crs", "--origin"};

// The build options given on the command line, as arguments again (for the manifest).
std::vector<std::string> given_build_args(const CLI::App& cmd) {
  std::vector<std::string> args;
  for (const CLI::Option* opt : cmd.get_options()) {
    if (opt->count() == 0 || opt->get_lnames().empty()) continue;
    const std::string name = "--" + opt->get_lnames().front();
    if (kPlanOnly.contains(name) || name == "--help") continue;
    if (opt->get_expected_max() == 0) {  // a flag
      args.push_back(name);
      continue;
    }
    // The tiles are built wherever their builder runs: input files by absolute paths.
    const bool input = name == "--dem" || name == "--reference-dem";
    for (const std::string& value : opt->results()) {
      args.push_back(name);
      args.push_back(input ? absolute_input_path(value) : value);
    }
  }
  return args;
}

// The build options of a manifest, parsed by `relief build`'s own parser.
BuildCommandArgs parse_build_args(const std::vector<std::string>& build_args) {
  BuildCommandArgs parsed;
  CLI::App app;
  add_build_options(&app, &parsed);
  std::vector<std::string> argv = {"--osm", "manifest"};
  argv.insert(argv.end(), build_args.begin(), build_args.end());
  std::reverse(argv.begin(), argv.end());  // CLI11 takes them last first
  try {
    app.parse(argv);
  } catch (const CLI::ParseError& e) {
    throw InvalidInput(std::string("the manifest's build options do not parse: ") + e.what());
  }
  return parsed;
}

std::pair<int, int> parse_tile(const std::string& text) {
  const std::size_t comma = text.find(',');
  try {
    if (comma != std::string::npos)
      return {std::stoi(text.substr(0, comma)), std::stoi(text.substr(comma + 1))};
  } catch (const std::exception&) {
  }
  throw OptionError("--tile '" + text + "' is not X,Y");
}

struct TilesArgs {
  BuildCommandArgs build;
  TilePlanOptions plan;
  std::string dir;
  std::vector<std::string> tiles;
  bool all = false;
  bool force = false;
  int jobs = 1;
  int retries = 1;
  std::string compare;      ///< merge: a whole build's .xodr
  double lod_cell_m = 0.0;  ///< merge: the coarse level's cell (0: tile size / 32)
  bool no_sumo = false;     ///< merge: no SUMO network
};

int run_plan(const TilesArgs& a, const CLI::App& cmd) {
  TilePlanOptions plan = a.plan;
  plan.osm_path = a.build.options.osm_path;
  plan.dem_paths = a.build.options.dem_paths;
  plan.name = a.build.options.name;
  plan.crs = a.build.options.crs;
  plan.frame_centre = a.build.options.frame_centre;
  plan.osm = a.build.options.osm;
  plan.build_args = given_build_args(cmd);
  if (std::find(plan.build_args.begin(), plan.build_args.end(), "--outputs") == plan.build_args.end()) {
    for (const char* arg : {"--outputs", "xodr,mesh,report", "--mesh-formats", "glb,fbx"})
      plan.build_args.emplace_back(arg);
  }
  const TileManifest manifest = plan_tiles(plan);
  write_manifest(a.dir, manifest);
  std::size_t nodes = 0;
  for (const TileSpec& t : manifest.tiles) nodes += t.road_nodes;
  std::cout << "planned " << manifest.tiles.size() << " tiles of " << manifest.tile_size_m << " m (halo "
            << manifest.halo_m << " m) over " << nodes << " road nodes in " << manifest.frame.crs() << "\n"
            << "  wrote " << (std::filesystem::path(a.dir) / "manifest.json").string() << "\n";
  return kOk;
}

// One tile in this process.
int run_one(const std::filesystem::path& dir, const TileManifest& manifest, int x, int y, bool force) {
  const BuildCommandArgs parsed = parse_build_args(manifest.build_args);
  Diagnostics diagnostics;
  print_diagnostics_live(diagnostics, /*quiet=*/true);
  const TileBuildResult r = build_tile(dir, manifest, x, y, parsed.options, diagnostics, force);
  std::cout << "tile " << x << "," << y << ": " << r.status;
  if (r.status != "skipped") std::cout << " in " << r.seconds << " s";
  if (!r.failed_gates.empty()) {
    std::cout << " (failed gates:";
    for (const std::string& g : r.failed_gates) std::cout << " " << g;
    std::cout << ")";
  }
  if (!r.halo_gates.empty()) std::cout << " (" << r.halo_gates.size() << " gate(s) failed in the halo only)";
  std::cout << "\n";
  return r.failed_gates.empty() ? kOk : kGateFailed;
}

// Every tile, phase after phase (tile_phase: a tile holds what its neighbours of earlier phases
// fitted), `jobs` at a time within a phase, each in its own process (its memory is its
// window's); a tile that fails is tried again `retries` times, the others go on.
int run_all(const TilesArgs& a, const TileManifest& manifest) {
  // This very program, also when its file was replaced (rebuilt) while the tiles run: the
  // kernel's link to the running image, not the path it was started from.
  const std::string self = "/proc/self/exe";
  const std::vector<const TileSpec*> order = build_order(manifest);
  std::atomic<std::size_t> next{0};
  std::size_t phase_end = 0;
  std::mutex mutex;
  std::size_t done = 0, gates_failed = 0;
  std::vector<std::string> failed;
  const auto worker = [&] {
    for (std::size_t i = next++; i < phase_end; i = next++) {
      const TileSpec& t = *order[i];
      const std::string tile = std::to_string(t.x) + "," + std::to_string(t.y);
      std::vector<std::string> argv = {self, "tiles", "build", a.dir, "--tile", tile};
      if (a.force) argv.emplace_back("--force");
      ProcessResult r;
      for (int attempt = 0; attempt <= a.retries; ++attempt) {
        try {
          r = run_process(argv);
        } catch (const std::exception& e) {  // the process could not be started: a failed try
          r = {kInternalError, std::string(e.what()) + "\n"};
        }
        if (r.exit_code == kOk || r.exit_code == kGateFailed) break;
        std::lock_guard lock(mutex);
        std::cerr << "tiles: tile " << tile << " failed (exit " << r.exit_code << ")"
                  << (attempt < a.retries ? ", trying again" : "") << ":\n"
                  << r.output;
      }
      std::lock_guard lock(mutex);
      ++done;
      if (r.exit_code == kGateFailed) ++gates_failed;
      if (r.exit_code != kOk && r.exit_code != kGateFailed) failed.push_back(tile);
      // The tile's own summary line ("tile X,Y: ..."); its diagnostics come before it.
      const std::size_t at = r.output.rfind("tile " + tile + ":");
      std::string line = at == std::string::npos ? "tile " + tile + ": done"
                                                 : r.output.substr(at, r.output.find('\n', at) - at);
      if (r.exit_code != kOk && r.exit_code != kGateFailed) line = "tile " + tile + ": FAILED";
      std::cerr << "tiles: [" << done << "/" << manifest.tiles.size() << "] " << line << "\n";
    }
  };
  for (std::size_t begin = 0; begin < order.size(); begin = phase_end) {
    phase_end = begin;
    while (phase_end < order.size() && tile_phase(*order[phase_end]) == tile_phase(*order[begin]))
      ++phase_end;
    next = begin;
    std::vector<std::thread> threads;
    for (int j = 0; j < std::max(1, a.jobs); ++j) threads.emplace_back(worker);
    for (std::thread& t : threads) t.join();
  }
  std::cout << manifest.tiles.size() - failed.size() << " of " << manifest.tiles.size() << " tiles built";
  if (gates_failed > 0) std::cout << ", " << gates_failed << " with failed gates";
  std::cout << "\n";
  if (!failed.empty()) {
    std::cerr << "relief: error: " << failed.size() << " tile(s) failed:";
    for (const std::string& f : failed) std::cerr << " " << f;
    std::cerr << "\n";
    return kInternalError;
  }
  return gates_failed > 0 ? kGateFailed : kOk;
}

int run_build(const TilesArgs& a) {
  const TileManifest manifest = read_manifest(a.dir);
  if (a.all) return run_all(a, manifest);
  if (a.tiles.empty()) throw OptionError("give --tile X,Y (repeatable) or --all");
  int code = kOk;
  for (const std::string& text : a.tiles) {
    const auto [x, y] = parse_tile(text);
    code = std::max(code, run_one(a.dir, manifest, x, y, a.force));
  }
  return code;
}

int run_merge(const TilesArgs& a) {
  Diagnostics diagnostics;
  TileMergeOptions options;
  if (!a.compare.empty()) options.whole_xodr = a.compare;
  options.lod_cell_m = a.lod_cell_m;
  {
    const BuildCommandArgs parsed = parse_build_args(read_manifest(a.dir).build_args);
    options.sumo = parsed.options.sumo;
    options.gates = parsed.options.gates;
    options.fit = parsed.options.fit;
  }
  options.sumo_net = !a.no_sumo;
  print_diagnostics_live(diagnostics, /*quiet=*/true);
  const TileMergeResult r = merge_tiles(a.dir, options, diagnostics);
  std::cout << "merged " << r.tiles << " tiles: " << r.roads << " roads, " << r.junctions << " junctions, "
            << r.scene_tiles << " scene tiles\n";
  if (r.scene_tiles > 0) {
    std::cout << "paved surface at its owners' heights: " << r.paved_moved << " of " << r.paved_vertices
              << " vertices moved (up to " << r.paved_max_dz_m << " m), " << r.paved_unmatched
              << " without an owner's vertex (" << r.paved_interpolated << " follow their neighbours); "
              << r.terrain_seams << " terrain vertices on tile lines beside roads joined (up to "
              << r.terrain_seams_max_dz_m << " m)\n";
    std::cout << "coarse level (lod1): " << r.lod_coarse_triangles << " of " << r.lod_full_triangles
              << " triangles, geometric error up to " << r.lod_max_error_m << " m\n";
  }
  if (options.whole_xodr) {
    std::cout << "against the whole build: " << r.whole_roads - r.whole_unmatched << " of " << r.whole_roads
              << " roads matched; surface within " << r.whole_max_xy_m << " m in plan, " << r.whole_max_z_m
              << " m in height (" << r.whole_roads_over_1mm << " roads over 1 mm)\n";
  }
  for (const std::filesystem::path& p : r.written) std::cout << "  wrote " << p.string() << "\n";
  if (!r.failed_gates.empty()) {
    std::cout << "FAILED (" << r.failed_gates.size() << "):\n";
    for (const std::string& g : r.failed_gates) std::cout << "  " << g << "\n";
    return kGateFailed;
  }
  return kOk;
}

}  // namespace

Runner add_tiles_command(CLI::App& app) {
  auto* tiles = app.add_subcommand("tiles", "Region-scale conversion in tiles: plan, build, merge");
  tiles->require_subcommand(1);
  auto args = std::make_shared<TilesArgs>();

  auto* plan =
      tiles->add_subcommand("plan", "Plan a region's tiles: DIR/manifest.json (takes every build option)");
  add_build_options(plan, &args->build);
  plan->add_option("--out", args->dir, "tiles folder")->required();
  plan->add_option("--tile-size", args->plan.tile_size_m, "tile size, m")
      ->capture_default_str()
      ->check(finite_positive());
  plan->add_option("--halo", args->plan.halo_m, "context read around each tile, m")->capture_default_str();
  plan->add_flag("--hold-neighbours,!--no-hold-neighbours", args->plan.hold_neighbours,
                 "each tile holds what its neighbours of earlier phases fitted where they meet, so that "
                 "links between neighbours meet exactly (default: on; off, each tile fits its window alone)");

  auto* build = tiles->add_subcommand(
      "build", "Build tiles of a plan into DIR/tiles/X_Y (unchanged tiles are skipped)");
  build->add_option("dir", args->dir, "tiles folder (relief tiles plan --out)")->required();
  build->add_option("--tile", args->tiles, "tile X,Y (repeatable)");
  build->add_flag("--all", args->all, "every tile of the plan, each in its own process");
  build->add_option("--jobs", args->jobs, "tiles built at once with --all")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  build->add_option("--retries", args->retries, "times a failed tile is tried again with --all")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  build->add_flag("--force", args->force, "build even tiles that are up to date");

  auto* merge = tiles->add_subcommand("merge", "Merge the built tiles into DIR/merged/");
  merge->add_option("dir", args->dir, "tiles folder")->required();
  merge->add_option("--compare", args->compare,
                    "a whole build's .xodr (relief build --origin at the plan's centre): measure the merge "
                    "against it");
  merge
      ->add_option("--lod-cell", args->lod_cell_m,
                   "the coarse level's clustering cell, m (default: the tile size / 32)")
      ->check(finite_positive());
  merge->add_flag("--no-sumo", args->no_sumo,
                  "no SUMO network (it needs netconvert; the region's in one run)");

  return [args, plan, build, merge] {
    return run_reporting_errors([&] {
      if (plan->parsed()) return run_plan(*args, *plan);
      if (build->parsed()) return run_build(*args);
      if (merge->parsed()) return run_merge(*args);
      return static_cast<int>(kUsage);
    });
  };
}

}  // namespace relief::cli
