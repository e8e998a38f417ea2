#include "relief/scene/scene.h"

#include <algorithm>
#include <string>

#include "relief/core/diagnostic_codes.h"
#include "relief/core/number_format.h"
#include "relief/geometry/plan_overlap.h"
#include "scene/ground_openings.h"
#include "scene/ground_support.h"

namespace relief {
namespace {

constexpr double kSeamReachM = 0.1;  // a gap wider than this is a hole, counted as such

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
    } else {
      text += osm_way_note(road);
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

const TriangleMesh* mesh_named(const MeshScene& scene, std::string_view name) {
  for (const TriangleMesh& m : scene.meshes) {
    if (m.name == name) return &m;
  }
  return nullptr;
}

// Runs `f` between progress(stage, 0) and progress(stage, 1).
template <typename F>
auto staged(const ProgressFn& progress, std::string_view stage, F&& f) {
  if (progress) progress(stage, 0.0);
  auto value = f();
  if (progress) progress(stage, 1.0);
  return value;
}

}  // namespace

Scene build_scene(const RoadModel& model, const RoadNetwork& network, const DemSampler& dem,
                  const SceneOptions& options, Diagnostics& diagnostics, const ProgressFn& progress) {
  Scene scene;
  scene.roads = staged(progress, "mesh roads",
                       [&] { return build_road_meshes(model, options.road_mesh, diagnostics); });
  const RoadMeshes& roads = scene.roads;
  scene.stats.junctions_meshed = roads.junctions_meshed;
  scene.stats.junctions_failed = roads.junctions_failed;
  scene.stats.first_failed_junction = roads.first_failed_junction;
  scene.stats.xodr_surface_max_distance_m = roads.max_surface_deviation_m;

  // Junction patches share the road-end vertices: the seam gap measures that they do.
  std::vector<std::uint8_t> junction(roads.road.triangles.size()), lanes(roads.road.triangles.size());
  for (std::size_t i = 0; i < junction.size(); ++i) {
    junction[i] = roads.road_triangle_owner[i] < 0;
    lanes[i] = !junction[i];
  }
  scene.stats.seam_road_junction_m =
      seam_gap(submesh(roads.road, lanes), submesh(roads.road, junction), kSeamReachM).max_gap_m;

  // Roads on the ground, less the triangles that lie under another road seen from above (a
  // tunnel's approach running on under the street over its portal, a street in a cutting under
  // a bridge's abutment, OSM ways closer than their widths): a 2.5-D ground holds one surface
  // per point. The terrain closes the step between the lower road's edge and the upper road: as
  // a ramp where the step is small, over an opening where a vehicle passes below
  // (ground_openings.h).
  GroundSupport support = triangle_support(roads, model, network);
  structures_on_the_ground(roads.road, dem, options.tunnel_portal_height_m, support);
  std::vector<std::uint8_t>& ground = support.ground;
  PlanOverlaps overlaps = plan_overlaps(roads.road, ground);
  if (keep_covering_structures(overlaps, support)) overlaps = plan_overlaps(roads.road, ground);
  scene.stats.deck_triangles_on_ground = support.decks_on_ground;
  scene.stats.tunnel_triangles_open = support.tunnels_open;
  // Decks off the ground (before the pieces under other roads leave it): the terrain keeps under them.
  std::vector<std::uint8_t> is_deck(ground.size());
  for (std::size_t i = 0; i < ground.size(); ++i) is_deck[i] = !ground[i] && !support.tunnel[i];
  const TriangleMesh decks = submesh(roads.road, is_deck);
  for (std::size_t i = 0; i < ground.size(); ++i) {
    if (overlaps.under[i]) {
      ground[i] = 0;
      ++scene.stats.ground_triangles_under_roads;
    }
  }
  if (overlaps.pairs > 0)
    report_plan_overlaps(overlaps, scene.stats.ground_triangles_under_roads, diagnostics);
  scene.ground_road = submesh(roads.road, ground);
  GroundOpeningOptions opening_options;
  opening_options.mouth_height_m = options.tunnel_portal_height_m;
  scene.opening_tops = opening_tops(roads.road, ground, support.tunnel, overlaps, opening_options);

  if (options.terrain) {
    scene.terrain = staged(progress, "mesh terrain", [&] {
      std::vector<Polyline3> outline;
      for (const auto& loop : boundary_loops(scene.ground_road)) {
        Polyline3 points;
        for (const std::uint32_t v : loop) {
          // The terrain takes an opening's top edge, not the road's edge under it.
          const Vec3& p = scene.ground_road.vertices[v];
          points.push_back(opening_top(scene.opening_tops, p));
        }
        if (points.size() >= 3) outline.push_back(std::move(points));
      }
      Aabb2 area;
      for (const Vec3& p : roads.road.vertices) area.extend(Vec2(p.x(), p.y()));
      return build_terrain(dem, area, outline, options.terrain_options, decks);
    });
  }
  scene.ground = std::move(support.ground);
  scene.tunnel = std::move(support.tunnel);

  // The meshes, in CARLA's naming: Road_Road, Road_Marking, Road_Sidewalk, Terrain.
  scene.meshes.frame = model.frame;
  const auto add_mesh = [&](TriangleMesh mesh, const char* mesh_name, SurfaceKind kind) {
    if (mesh.empty()) return;
    mesh.name = mesh_name;
    mesh.kind = kind;
    if (mesh.normals.size() != mesh.vertices.size()) mesh.normals = vertex_normals(mesh);
    scene.meshes.meshes.push_back(std::move(mesh));
  };
  // Moved, not copied: a city's meshes are hundreds of MB (scene.h).
  add_mesh(std::move(scene.roads.road), "Road_Road", SurfaceKind::road);
  add_mesh(std::move(scene.roads.marking), "Road_Marking", SurfaceKind::marking);
  add_mesh(std::move(scene.roads.sidewalk), "Road_Sidewalk", SurfaceKind::sidewalk);
  if (scene.terrain) add_mesh(std::move(scene.terrain->terrain), "Terrain", SurfaceKind::terrain);

  if (options.checks) {
    scene.checks = check_scene(scene);
    report_scene_checks(scene, *scene.checks, model, diagnostics);
  }
  return scene;
}

SceneChecks check_scene(const Scene& scene) {
  SceneChecks c;
  std::vector<MeshQuality>& q = c.quality;
  for (const TriangleMesh& m : scene.meshes.meshes) q.push_back(analyse_mesh(m));
  const TriangleMesh* road = mesh_named(scene.meshes, "Road_Road");
  const TriangleMesh* terrain_mesh = mesh_named(scene.meshes, "Terrain");
  if (!scene.terrain || terrain_mesh == nullptr) return c;
  const TriangleMesh& terrain = *terrain_mesh;
  // Roads on the ground and terrain as one surface: the terrain took the outline's exact
  // positions over, so welding identical positions joins them.
  TriangleMesh ground_all = scene.ground_road;
  ground_all.append(terrain);
  ground_all = weld_identical_vertices(ground_all);
  ground_all.name = "Ground (Road_Road on the ground + Terrain, welded)";
  // Road and terrain pairs among themselves are the Road_Road and Terrain figures: only
  // pairs across the two are tested (a third of the whole test's time on NE).
  MeshQualityOptions across;
  across.intersections_across.assign(ground_all.triangles.size(), 0);
  std::fill_n(across.intersections_across.begin(), scene.ground_road.triangles.size(), 1);
  q.push_back(analyse_mesh(ground_all, across));
  // An opening is one by design (a road goes on below the ground there).
  c.ground_portals = loops_through_tops(ground_all, scene.opening_tops);
  c.ground_holes = q.back().holes - std::min(q.back().holes, c.ground_portals);
  c.ground_components = q.back().components;
  c.seam_road_terrain_m = seam_gap(scene.ground_road, terrain, kSeamReachM).max_gap_m;
  // Road triangles off the ground (decks, tunnels, pieces under other roads) against the
  // terrain, welded where they share positions, only pairs across the two tested.
  std::vector<std::uint8_t> off(scene.ground.size());
  for (std::size_t i = 0; i < off.size(); ++i) off[i] = !scene.ground[i];
  TriangleMesh structures = road != nullptr ? submesh(*road, off) : TriangleMesh{};
  const std::size_t n_structures = structures.triangles.size();
  if (n_structures > 0) {
    structures.append(terrain);
    structures = weld_identical_vertices(structures);
    MeshQualityOptions o;
    o.intersections_across.assign(structures.triangles.size(), 0);
    std::fill_n(o.intersections_across.begin(), n_structures, 1);
    MeshQuality crossing = analyse_mesh(structures, o);
    c.structure_terrain_pairs = crossing.self_intersecting_pairs;
    c.structure_terrain_sites = std::move(crossing.self_intersection_sites);
  }
  return c;
}

void report_scene_checks(const Scene& scene, const SceneChecks& checks, const RoadModel& model,
                         Diagnostics& diagnostics) {
  if (scene.terrain && checks.structure_terrain_pairs > 0) {
    diagnostics.report(
        Severity::warning, codes::kMeshStructureTerrainIntersections,
        std::to_string(checks.structure_terrain_pairs) +
            " triangle pair(s) of a deck, tunnel or road piece under another road intersect the terrain" +
            first_sites(checks.structure_terrain_sites) +
            ": the terrain closing the step over a road piece under another road, or a deck whose edge "
            "crosses a road edge (the terrain is kept under decks only inside edges clear of the roads)");
  }
  for (const MeshQuality& q : checks.quality) {
    if (q.name == "Road_Road" && q.self_intersecting_pairs > 0)
      report_self_intersections(q, scene.roads.road_triangle_owner, model, diagnostics);
  }
}

}  // namespace relief
