#include "pipeline/mesh_stage.h"

#include <algorithm>
#include <optional>

#include "relief/core/diagnostic_codes.h"
#include "relief/core/number_format.h"
#include "relief/export/mesh_report.h"
#include "relief/export/mesh_writer.h"
#include "relief/geometry/mesh_quality.h"
#include "relief/geometry/mesh_tiles.h"
#include "relief/geometry/plan_overlap.h"
#include "relief/scene/road_mesh.h"
#include "relief/terrain/terrain_tin.h"
#include "scene/ground_openings.h"
#include "scene/ground_support.h"

namespace relief {
namespace {

// " at (x, y), (x, y)..." for the first five sites, in the local frame.
std::string first_sites(const std::vector<Vec3>& sites) {
  std::string text;
  for (std::size_t i = 0; i < sites.size() && i < 5; ++i) {
    text += i == 0 ? " at (" : ", (";
    append_fixed(text, sites[i].x(), 1);
    text += ", ";
    append_fixed(text, sites[i].y(), 1);
    text += ")";
  }
  return text;
}

// What a triangle of Road_Road belongs to: "road N (OSM way W)" or "junction J".
std::string triangle_owner(int owner, const RoadModel& model) {
  if (owner < 0) return "junction " + std::to_string(-1 - owner);
  std::string text = "road " + std::to_string(owner);
  const int index = model.road_index(owner);
  if (index >= 0) {
    const ModelRoad& road = model.roads[static_cast<std::size_t>(index)];
    if (road.junction != -1) {
      text += " (connecting, junction " + std::to_string(road.junction) + ")";
    } else if (!road.osm_way_ids.empty()) {
      text += " (OSM way " + std::to_string(road.osm_way_ids.front()) + ")";
    }
  }
  return text;
}

// One warning naming the owners of the first self-intersecting Road_Road pairs, one line per
// distinct pair of owners, so that a user finds them in the .xodr and in OSM.
void report_self_intersections(const MeshQuality& road, const std::vector<int>& owner, const RoadModel& model,
                               Diagnostics& diagnostics) {
  std::string text;
  std::vector<std::pair<int, int>> named;
  for (std::size_t i = 0; i < road.self_intersection_triangles.size(); ++i) {
    const auto [s, t] = road.self_intersection_triangles[i];
    if (s >= owner.size() || t >= owner.size()) continue;
    const std::pair<int, int> key{std::min(owner[s], owner[t]), std::max(owner[s], owner[t])};
    if (std::find(named.begin(), named.end(), key) != named.end()) continue;
    named.push_back(key);
    const Vec3& p = road.self_intersection_sites[i];
    text += "; " + triangle_owner(key.first, model) + " x " + triangle_owner(key.second, model) + " at (";
    append_fixed(text, p.x(), 1);
    text += ", ";
    append_fixed(text, p.y(), 1);
    text += ", ";
    append_fixed(text, p.z(), 2);
    text += ")";
  }
  diagnostics.report(Severity::warning, codes::kMeshRoadSelfIntersections,
                     std::to_string(road.self_intersecting_pairs) +
                         " Road_Road triangle pair(s) intersect; the first pairs' owners" + text);
}

void report_plan_overlaps(const PlanOverlaps& overlaps, std::size_t under, Diagnostics& diagnostics) {
  const std::string sites = first_sites(overlaps.sites);
  diagnostics.report(
      Severity::info, codes::kMeshRoadsOverlapInPlan,
      std::to_string(under) + " road triangle(s) on the ground lie under another road seen from above (" +
          std::to_string(overlaps.pairs) + " overlapping pairs" + sites +
          "): a tunnel approach under the street over its portal, a street under a bridge's abutment, or "
          "ways "
          "closer than their widths; the terrain closes the step to the upper road, over an opening where it "
          "clears a vehicle");
}

}  // namespace

MeshSummary write_mesh_outputs(const MeshStageInput& in, OutputSet& files, StageTimer& timer,
                               std::vector<std::filesystem::path>& written, std::vector<std::string>& names) {
  const BuildOptions& options = in.options;
  MeshSummary summary;

  RoadMeshes roads =
      timer.run("mesh roads", [&] { return build_road_meshes(in.model, options.road_mesh, in.diagnostics); });
  summary.junctions_meshed = roads.junctions_meshed;
  summary.junctions_failed = roads.junctions_failed;
  summary.xodr_surface_max_distance_m = roads.max_surface_deviation_m;

  constexpr double kSeamReachM = 0.1;  // a gap wider than this is a hole, counted as such
  // Junction patches share the road-end vertices: the seam gap measures that they do.
  std::vector<std::uint8_t> junction(roads.road.triangles.size()), lanes(roads.road.triangles.size());
  for (std::size_t i = 0; i < junction.size(); ++i) {
    junction[i] = roads.road_triangle_owner[i] < 0;
    lanes[i] = !junction[i];
  }
  summary.seam_road_junction_m =
      seam_gap(submesh(roads.road, lanes), submesh(roads.road, junction), kSeamReachM).max_gap_m;

  // Roads on the ground, less the triangles that lie under another road seen from above (a
  // tunnel's approach running on under the street over its portal, a street in a cutting under
  // a bridge's abutment, OSM ways closer than their widths): a 2.5-D ground holds one surface
  // per point. The terrain closes the step between the lower road's edge and the upper road: as
  // a ramp where the step is small, over an opening where a vehicle passes below
  // (ground_openings.h).
  GroundSupport support = triangle_support(roads, in.model, in.network);
  structures_on_the_ground(roads.road, in.dem, options.tunnel_portal_height_m, support);
  std::vector<std::uint8_t>& ground = support.ground;
  PlanOverlaps overlaps = plan_overlaps(roads.road, ground);
  if (keep_covering_structures(overlaps, support)) overlaps = plan_overlaps(roads.road, ground);
  summary.deck_triangles_on_ground = support.decks_on_ground;
  summary.tunnel_triangles_open = support.tunnels_open;
  // Decks off the ground (before the pieces under other roads leave it): the terrain keeps under them.
  std::vector<std::uint8_t> is_deck(ground.size());
  for (std::size_t i = 0; i < ground.size(); ++i) is_deck[i] = !ground[i] && !support.tunnel[i];
  const TriangleMesh decks = submesh(roads.road, is_deck);
  for (std::size_t i = 0; i < ground.size(); ++i) {
    if (overlaps.under[i]) {
      ground[i] = 0;
      ++summary.ground_triangles_under_roads;
    }
  }
  if (overlaps.pairs > 0)
    report_plan_overlaps(overlaps, summary.ground_triangles_under_roads, in.diagnostics);
  const TriangleMesh ground_road = submesh(roads.road, ground);
  GroundOpeningOptions opening_options;
  opening_options.mouth_height_m = options.tunnel_portal_height_m;
  const std::vector<std::pair<Vec3, Vec3>> tops =
      opening_tops(roads.road, ground, support.tunnel, overlaps, opening_options);

  std::optional<TerrainBuild> terrain;
  if (options.terrain) {
    terrain = timer.run("mesh terrain", [&] {
      std::vector<Polyline3> outline;
      for (const auto& loop : boundary_loops(ground_road)) {
        Polyline3 points;
        for (const std::uint32_t v : loop) {
          // The terrain takes an opening's top edge, not the road's edge under it.
          const Vec3& p = ground_road.vertices[v];
          points.push_back(opening_top(tops, p));
        }
        if (points.size() >= 3) outline.push_back(std::move(points));
      }
      Aabb2 area;
      for (const Vec3& p : roads.road.vertices) area.extend(Vec2(p.x(), p.y()));
      return build_terrain(in.dem, area, outline, options.terrain_options, decks);
    });
    summary.terrain_tin_vertices = terrain->tin_vertices;
    summary.terrain_max_vertical_error_m = terrain->max_vertical_error_m;
    summary.terrain_max_cut_m = terrain->max_cut_m;
    summary.terrain_max_fill_m = terrain->max_fill_m;
  }

  // The scene, in CARLA's naming: Road_Road, Road_Marking, Road_Sidewalk, Terrain.
  MeshScene scene;
  scene.frame = in.model.frame;
  const auto add_mesh = [&](TriangleMesh mesh, const char* mesh_name, SurfaceKind kind) {
    if (mesh.empty()) return;
    mesh.name = mesh_name;
    mesh.kind = kind;
    if (mesh.normals.size() != mesh.vertices.size()) mesh.normals = vertex_normals(mesh);
    scene.meshes.push_back(std::move(mesh));
  };
  add_mesh(roads.road, "Road_Road", SurfaceKind::road);
  add_mesh(roads.marking, "Road_Marking", SurfaceKind::marking);
  add_mesh(roads.sidewalk, "Road_Sidewalk", SurfaceKind::sidewalk);
  if (terrain) add_mesh(terrain->terrain, "Terrain", SurfaceKind::terrain);

  // Quality of every mesh, of the paved surface, and of the ground (roads + terrain) as a whole;
  // it only reads the scene, so it runs beside the file writers.
  struct Checked {
    std::vector<MeshQuality> quality;
    std::size_t ground_holes = 0, ground_components = 0, ground_portals = 0, structure_terrain_pairs = 0;
    std::vector<Vec3> structure_terrain_sites;
    std::optional<double> seam_road_terrain_m;
  };
  BackgroundStage<Checked> check("check meshes (beside the files)", [&] {
    Checked c;
    std::vector<MeshQuality>& q = c.quality;
    for (const TriangleMesh& m : scene.meshes) q.push_back(analyse_mesh(m));
    if (terrain) {
      // Roads on the ground and terrain as one surface: the terrain took the outline's exact
      // positions over, so welding identical positions joins them.
      TriangleMesh ground_all = ground_road;
      ground_all.append(terrain->terrain);
      ground_all = weld_identical_vertices(ground_all);
      ground_all.name = "Ground (Road_Road on the ground + Terrain, welded)";
      // Road and terrain pairs among themselves are the Road_Road and Terrain figures: only
      // pairs across the two are tested (a third of the whole test's time on NE).
      MeshQualityOptions across;
      across.intersections_across.assign(ground_all.triangles.size(), 0);
      std::fill_n(across.intersections_across.begin(), ground_road.triangles.size(), 1);
      q.push_back(analyse_mesh(ground_all, across));
      // An opening is one by design (a road goes on below the ground there).
      c.ground_portals = loops_through_tops(ground_all, tops);
      c.ground_holes = q.back().holes - std::min(q.back().holes, c.ground_portals);
      c.ground_components = q.back().components;
      c.seam_road_terrain_m = seam_gap(ground_road, terrain->terrain, kSeamReachM).max_gap_m;
      // Road triangles off the ground (decks, tunnels, pieces under other roads) against the
      // terrain, welded where they share positions, only pairs across the two tested.
      std::vector<std::uint8_t> off(ground.size());
      for (std::size_t i = 0; i < off.size(); ++i) off[i] = !ground[i];
      TriangleMesh structures = submesh(roads.road, off);
      const std::size_t n_structures = structures.triangles.size();
      if (n_structures > 0) {
        structures.append(terrain->terrain);
        structures = weld_identical_vertices(structures);
        MeshQualityOptions o;
        o.intersections_across.assign(structures.triangles.size(), 0);
        std::fill_n(o.intersections_across.begin(), n_structures, 1);
        MeshQuality crossing = analyse_mesh(structures, o);
        c.structure_terrain_pairs = crossing.self_intersecting_pairs;
        c.structure_terrain_sites = std::move(crossing.self_intersection_sites);
      }
    }
    return c;
  });

  // Files: every format asked for (then the tiles, then the report).
  const auto write_scene = [&](const MeshScene& s, MeshFormat format, const std::string& base,
                               std::vector<std::string>& listed) {
    for (EncodedFile& f : encode_mesh_scene(s, format, base)) {
      const std::string bytes = std::move(f.bytes);
      files.add(options.out_dir / f.filename, [&](std::ostream& out) { out << bytes; });
      written.push_back(options.out_dir / f.filename);
      names.push_back(f.filename);
      listed.push_back(f.filename);
    }
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
  Checked checked = check.take(timer);
  const std::vector<MeshQuality>& quality = checked.quality;
  if (terrain) {
    summary.ground_holes = checked.ground_holes;
    summary.ground_portals = checked.ground_portals;
    summary.structure_terrain_intersecting_pairs = checked.structure_terrain_pairs;
    if (checked.structure_terrain_pairs > 0) {
      in.diagnostics.report(
          Severity::warning, codes::kMeshStructureTerrainIntersections,
          std::to_string(checked.structure_terrain_pairs) +
              " triangle pair(s) of a deck, tunnel or road piece under another road intersect the terrain" +
              first_sites(checked.structure_terrain_sites) +
              ": the terrain closing the step over a road piece under another road, or a deck whose edge "
              "crosses a road edge (the terrain is kept under decks only inside edges clear of the roads)");
    }
    summary.ground_components = checked.ground_components;
    summary.seam_road_terrain_m = checked.seam_road_terrain_m;
  }
  for (const MeshQuality& q : quality) {
    if (q.name == "Road_Road") summary.road = q;
    if (q.name == "Terrain") summary.terrain = q;
  }
  if (summary.road && summary.road->self_intersecting_pairs > 0) {
    report_self_intersections(*summary.road, roads.road_triangle_owner, in.model, in.diagnostics);
  }
  MeshReportExtras extras;
  extras.file = in.name;
  extras.seam_road_junction_m = summary.seam_road_junction_m;
  if (summary.seam_road_terrain_m) extras.seam_road_terrain_m = *summary.seam_road_terrain_m;
  extras.xodr_surface_max_distance_m = summary.xodr_surface_max_distance_m;
  const std::string report = mesh_report_json(quality, extras);
  files.add(options.out_dir / "mesh_report.json", [&](std::ostream& out) { out << report; });
  written.push_back(options.out_dir / "mesh_report.json");
  names.push_back("mesh_report.json");
  return summary;
}

}  // namespace relief
