#include "pipeline/mesh_stage.h"

#include "relief/export/mesh_report.h"
#include "relief/export/mesh_writer.h"
#include "relief/geometry/mesh_tiles.h"
#include "relief/scene/scene.h"

namespace relief {

Scene build_scene_stage(const MeshStageInput& in, StageTimer& timer) {
  SceneOptions scene_options = in.options.scene;
  scene_options.checks = false;  // run by write_mesh_outputs, beside the file writers
  return build_scene(in.model, in.network, in.dem, scene_options, in.diagnostics, timer.stage_progress());
}

MeshSummary write_mesh_outputs(const MeshStageInput& in, const Scene& built, OutputSet& files,
                               StageTimer& timer, std::vector<std::filesystem::path>& written,
                               std::vector<std::string>& names) {
  const BuildOptions& options = in.options;
  const MeshScene& scene = built.meshes;
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
    summary.terrain_max_vertical_error_m = built.terrain->max_vertical_error_m;
    summary.terrain_max_cut_m = built.terrain->max_cut_m;
    summary.terrain_max_fill_m = built.terrain->max_fill_m;
  }

  // Files: every format asked for (then the tiles, then the report).
  const auto write_scene = [&](const MeshScene& s, MeshFormat format, const std::string& base,
                               std::vector<std::string>& listed) {
    write_mesh_scene(s, format, base,
                     [&](const std::string& filename, const std::function<void(std::ostream&)>& write) {
                       files.add(options.out_dir / filename, write);
                       written.push_back(options.out_dir / filename);
                       names.push_back(filename);
                       listed.push_back(filename);
                     });
  };
  for (const MeshFormat format : options.mesh_formats) {
    timer.run("write " + std::string(to_string(format)), [&] {
      write_scene(scene, format, in.name, summary.files);
      return 0;
    });
  }
  if (options.mesh_tile_size_m > 0.0) {
    summary.tile_size_m = options.mesh_tile_size_m;
    timer.run("write tiles", [&] {
      for (const SceneTile& tile : split_into_tiles(scene, options.mesh_tile_size_m)) {
        const std::string base = in.name + "_Tile_" + std::to_string(tile.x) + "_" + std::to_string(tile.y);
        for (const MeshFormat format : options.mesh_formats)
          write_scene(tile.scene, format, base, summary.tile_files);
      }
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

}  // namespace relief
