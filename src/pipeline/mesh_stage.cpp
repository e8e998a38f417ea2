#include "pipeline/mesh_stage.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <set>
#include <sstream>
#include <utility>

#include "relief/core/diagnostic_codes.h"
#include "relief/export/carla_package.h"
#include "relief/export/mesh_report.h"
#include "relief/export/mesh_writer.h"
#include "relief/geometry/mesh_tiles.h"
#include "relief/scene/scene.h"

namespace relief {
namespace {

// CarlaFbx's placeholders for the tiles of the grid's rectangle (0, 0)..(max X, max Y) that
// `tiles` lacks, 50 m under the scene's lowest point. Tile (X, Y) spans origin + size * [X, X + 1]
// x [Y, Y + 1], the origin being the south-west corner of tile (0, 0) (mesh_tiles.h).
void add_placeholder_tiles(const MeshScene& scene, const std::vector<SceneTile>& tiles, double size_m,
                           const std::string& name, CarlaFbx& carla) {
  if (tiles.empty()) return;
  std::set<std::pair<int, int>> present;
  for (const SceneTile& t : tiles) present.emplace(t.x, t.y);
  const Vec2 origin = tiles.front().bounds.min - size_m * Vec2(tiles.front().x, tiles.front().y);
  double z = std::numeric_limits<double>::infinity();
  for (const TriangleMesh& m : scene.meshes)
    for (const Vec3& v : m.vertices) z = std::min(z, v.z());
  for (EncodedFile& f :
       carla_placeholder_tiles(present, origin, size_m, z - 50.0, scene, name, carla.placeholders))
    carla.files.push_back(std::move(f));
}

// A region tile's terrain: the triangles on the core's side of the lines cut into it (its
// centroid would give a triangle along a detour round a road edge to the wrong tile).
void core_terrain(const Scene& built, MeshScene& core) {
  if (!built.terrain) return;
  const TriangleMesh* terrain = nullptr;
  for (const TriangleMesh& m : built.meshes.meshes)
    if (m.name == "Terrain") terrain = &m;
  if (terrain == nullptr || built.terrain->in_core.size() != terrain->triangles.size()) return;
  std::erase_if(core.meshes, [](const TriangleMesh& m) { return m.name == "Terrain"; });
  TriangleMesh owned = submesh(*terrain, built.terrain->in_core);
  owned.name = terrain->name;
  owned.kind = terrain->kind;
  if (!owned.triangles.empty()) core.meshes.push_back(std::move(owned));
}

// A scene written in the frame's own coordinates (no file origin) that reaches where a float
// steps by more than 1 mm (beyond 16 384 m of the origin): its files hold the vertices only to
// that step, and narrow triangles collapse. Said once, with where and how coarse.
void warn_if_far_from_origin(const MeshScene& scene, Diagnostics& diagnostics) {
  if (scene.file_origin) return;
  double far = 0.0;
  Vec2 where = Vec2::Zero();
  for (const TriangleMesh& mesh : scene.meshes) {
    for (const Vec3& v : mesh.vertices) {
      const double d = v.head<2>().cwiseAbs().maxCoeff();
      if (d > far) {
        far = d;
        where = v.head<2>();
      }
    }
  }
  constexpr double kOneMillimetreStep = 16384.0;  // a float's step is 2^-9 m = 1.95 mm beyond
  if (!(far >= kOneMillimetreStep)) return;
  const double step_mm = 1000.0 * std::exp2(std::floor(std::log2(far)) - 23.0);
  std::ostringstream m;
  m.precision(3);
  m << "the scene reaches " << far / 1000.0 << " km from the frame's origin (at " << std::fixed
    << std::setprecision(0) << where.x() << ", " << where.y() << "), where a float steps by "
    << std::setprecision(1) << step_mm
    << " mm: its mesh files hold the vertices only to that, and narrow triangles collapse; build it as "
       "region tiles (relief tiles) or with --mesh-tile-size, whose files each have their own origin";
  diagnostics.report(Severity::warning, codes::kMeshFarFromOrigin, m.str());
}

}  // namespace

Scene build_scene_stage(const MeshStageInput& in, StageTimer& timer) {
  SceneOptions scene_options = in.options.scene;
  scene_options.checks = false;  // run by write_mesh_outputs, beside the file writers
  if (in.options.mesh_core_size_m > 0.0) {
    // A region tile: its terrain is cut along the core's edges (the same bits in every tile:
    // whole multiples of the size), so that neighbouring tiles' terrain meets vertex for vertex.
    const double size = in.options.mesh_core_size_m;
    const auto column = static_cast<double>(in.options.mesh_core_column);
    const auto row = static_cast<double>(in.options.mesh_core_row);
    Aabb2 core;
    core.extend(Vec2(column * size, row * size));
    core.extend(Vec2((column + 1.0) * size, (row + 1.0) * size));
    scene_options.terrain_options.core = core;
  }
  return build_scene(in.model, in.network, in.dem, scene_options, in.diagnostics, timer.stage_progress());
}

MeshSummary write_mesh_outputs(const MeshStageInput& in, const Scene& built, OutputSet& files,
                               StageTimer& timer, std::vector<std::filesystem::path>& written,
                               std::vector<std::string>& names, CarlaFbx* carla_fbx) {
  const BuildOptions& options = in.options;
  MeshScene core = options.mesh_core_size_m > 0.0
                       ? scene_in_cell(built.meshes, options.mesh_core_size_m, options.mesh_core_column,
                                       options.mesh_core_row)
                       : MeshScene{};
  if (options.mesh_core_size_m > 0.0) core_terrain(built, core);
  const MeshScene& scene = options.mesh_core_size_m > 0.0 ? core : built.meshes;
  if (!options.mesh_formats.empty()) warn_if_far_from_origin(scene, in.diagnostics);
  // The checks only read the scene, so they run beside the file writers.
  BackgroundStage<SceneChecks> check("check meshes (beside the files)", [&] { return check_scene(built); });

  MeshSummary summary;
  summary.junctions_meshed = built.stats.junctions_meshed;
  summary.junctions_failed = built.stats.junctions_failed;
  summary.first_failed_junction = built.stats.first_failed_junction;
  summary.xodr_surface_max_distance_m = built.stats.xodr_surface_max_distance_m;
  summary.seam_road_junction_m = built.stats.seam_road_junction_m;
  summary.deck_triangles_on_ground = built.stats.deck_triangles_on_ground;
  summary.tunnel_triangles_open = built.stats.tunnel_triangles_open;
  summary.ground_triangles_under_roads = built.stats.ground_triangles_under_roads;
  if (built.terrain) {
    summary.terrain_tin_vertices = built.terrain->tin_vertices;
    summary.core_lines = !built.terrain->in_core.empty();
    summary.core_line_vertices = built.terrain->core_line_vertices;
    summary.core_detours = built.terrain->core_detours;
    summary.core_blocked = built.terrain->core_blocked;
    summary.core_leaks = built.terrain->core_leaks;
    summary.terrain_max_vertical_error_m = built.terrain->max_vertical_error_m;
    summary.terrain_max_cut_m = built.terrain->max_cut_m;
    summary.terrain_max_fill_m = built.terrain->max_fill_m;
  }

  // Files: every format asked for (then the tiles, then the report). The FBX the CARLA package
  // takes is kept as written (the tiles when there are tiles).
  const bool tiles = options.mesh_tile_size_m > 0.0;
  const auto write_scene = [&](const MeshScene& s, MeshFormat format, const std::string& base,
                               std::vector<std::string>& listed, bool is_tile) {
    const bool keep = carla_fbx != nullptr && format == MeshFormat::fbx && is_tile == tiles;
    write_mesh_scene(s, format, base,
                     [&](const std::string& filename, const std::function<void(std::ostream&)>& write) {
                       if (keep) {
                         std::ostringstream bytes;
                         write(bytes);
                         carla_fbx->files.push_back(EncodedFile{filename, std::move(bytes).str()});
                         const std::string& kept = carla_fbx->files.back().bytes;
                         files.add(options.out_dir / filename, [&](std::ostream& out) { out << kept; });
                       } else {
                         files.add(options.out_dir / filename, write);
                       }
                       written.push_back(options.out_dir / filename);
                       names.push_back(filename);
                       listed.push_back(filename);
                     });
  };
  for (const MeshFormat format : options.mesh_formats) {
    timer.run("write " + std::string(to_string(format)), [&] {
      write_scene(scene, format, in.name, summary.files, false);
      return 0;
    });
  }
  if (options.mesh_tile_size_m > 0.0) {
    summary.tile_size_m = options.mesh_tile_size_m;
    timer.run("write tiles", [&] {
      const std::vector<SceneTile> cut = split_into_tiles(scene, options.mesh_tile_size_m);
      for (const SceneTile& tile : cut) {
        const std::string base = in.name + "_Tile_" + std::to_string(tile.x) + "_" + std::to_string(tile.y);
        for (const MeshFormat format : options.mesh_formats)
          write_scene(tile.scene, format, base, summary.tile_files, true);
      }
      if (carla_fbx != nullptr)
        add_placeholder_tiles(scene, cut, options.mesh_tile_size_m, in.name, *carla_fbx);
      return 0;
    });
  }
  const SceneChecks checked = check.take(timer);
  const std::vector<MeshQuality>& quality = checked.quality;
  if (built.terrain) {
    summary.ground_holes = checked.ground_holes;
    summary.ground_portals = checked.ground_portals;
    summary.structure_terrain_intersecting_pairs = checked.structure_terrain_pairs;
    summary.structure_terrain_sites = checked.structure_terrain_sites;
    if (checked.ground_holes > 0 && !quality.empty()) summary.ground_hole_sites = quality.back().hole_sites;
    summary.ground_components = checked.ground_components;
    summary.seam_road_terrain_m = checked.seam_road_terrain_m;
  }
  for (const MeshQuality& q : quality) {
    if (q.name == "Road_Road") summary.road = q;
    if (q.name == "Terrain") summary.terrain = q;
  }
  report_scene_checks(built, checked, in.model, in.diagnostics);
  MeshReportExtras extras;
  extras.file = in.name;
  extras.seam_road_junction_m = summary.seam_road_junction_m;
  if (summary.seam_road_terrain_m) extras.seam_road_terrain_m = *summary.seam_road_terrain_m;
  extras.xodr_surface_max_distance_m = summary.xodr_surface_max_distance_m;
  const std::string report = mesh_report_json(quality, extras);
  files.add(options.out_dir / "mesh_report.json", [&](std::ostream& out) { out << report; });
  written.push_back(options.out_dir / "mesh_report.json");
  names.emplace_back("mesh_report.json");
  return summary;
}

void write_carla_package_output(const MeshStageInput& in, std::string xodr, CarlaFbx fbx,
                                std::int64_t mtime_s, OutputSet& files, StageTimer& timer,
                                MeshSummary& summary, std::vector<std::filesystem::path>& written,
                                std::vector<std::string>& names) {
  CarlaPackageInput package;
  package.map_name = in.name;
  package.xodr = std::move(xodr);
  package.fbx_files = std::move(fbx.files);
  package.tile_size_m = static_cast<int>(in.options.mesh_tile_size_m);  // whole metres (build() checks)
  package.mtime_s = mtime_s;
  const std::string filename = in.name + ".carla.tar.gz";
  timer.run("write CARLA package", [&] {
    const std::string bytes = encode_carla_package(package);
    files.add(in.options.out_dir / filename, [&](std::ostream& out) { out << bytes; });
    return 0;
  });
  summary.carla_package = filename;
  summary.carla_package_entries = carla_package_entries(package);
  summary.carla_placeholder_tiles = std::move(fbx.placeholders);
  if (!summary.carla_placeholder_tiles.empty()) {
    in.diagnostics.report(Severity::warning, codes::kCarlaTileGridGap,
                          carla_placeholder_message(summary.carla_placeholder_tiles, package.tile_size_m));
  }
  written.push_back(in.options.out_dir / filename);
  names.push_back(filename);
}

}  // namespace relief
