#pragma once
// The 3D scene of a RoadModel over a DEM, in one call: the paved surface (lofted lanes and
// junction patches, road_mesh.h), the ground the terrain meets (roads on the ground, less
// structures and the pieces under another road in plan), the openings where a road goes on
// below the ground (tunnel mouths, underpasses), the terrain conformed to all that, and the
// quality checks of the whole. Writers (export/) and the co-simulation read the result; nothing
// here writes a file.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "relief/core/diagnostics.h"
#include "relief/geometry/mesh_quality.h"
#include "relief/geometry/triangle_mesh.h"
#include "relief/roads/road_model.h"
#include "relief/roads/road_network.h"
#include "relief/scene/road_mesh.h"
#include "relief/terrain/dem_sampler.h"
#include "relief/terrain/terrain_tin.h"

namespace relief {

struct SceneOptions {
  RoadMeshOptions road_mesh;
  bool terrain = true;  ///< build the Terrain mesh (false: the paved surface only)
  TerrainOptions terrain_options;
  /// Top edge of a tunnel's mouth above the road: a tunnel triangle under less DEM than this is
  /// meshed as a road on the ground (a cutting), and the terrain meets a mouth this high.
  double tunnel_portal_height_m = 5.0;
  /// Run check_scene() inside build_scene() and report its findings. A caller that wants the
  /// checks beside other work (the pipeline runs them beside the file writers) sets false and
  /// calls check_scene() and report_scene_checks() itself.
  bool checks = true;
};

/// Quality of a scene: every mesh, and the ground (roads on the ground + terrain) as a whole.
struct SceneChecks {
  /// analyse_mesh() of each of Scene::meshes.meshes in order, then (with a terrain) of the
  /// ground welded, named "Ground (Road_Road on the ground + Terrain, welded)".
  std::vector<MeshQuality> quality;
  std::size_t ground_holes = 0;       ///< boundary loops of the ground less its openings
  std::size_t ground_components = 0;  ///< connected pieces of the ground
  std::size_t ground_portals = 0;     ///< openings: boundary loops through an opening's top edge
  /// Road triangles off the ground (decks, tunnels, under other roads) x Terrain, intersecting
  /// pairs, and the first of their sites.
  std::size_t structure_terrain_pairs = 0;
  std::vector<Vec3> structure_terrain_sites;
  std::optional<double> seam_road_terrain_m;  ///< widest gap between ground roads and terrain
};

/// Figures of the build itself (the checks are in SceneChecks).
struct SceneStats {
  std::size_t junctions_meshed = 0, junctions_failed = 0;
  std::string first_failed_junction;         ///< "junction J at (x, y, z)"; empty if none failed
  double xodr_surface_max_distance_m = 0.0;  ///< road mesh vs the OpenDRIVE surface S(road, s, t)
  double seam_road_junction_m = 0.0;         ///< widest gap between lofted lanes and junction patches
  /// Structure triangles meshed as roads on the ground: decks within 1 m above the DEM (or
  /// below it), tunnel triangles under less than the mouth's height of DEM.
  std::size_t deck_triangles_on_ground = 0, tunnel_triangles_open = 0;
  /// Road triangles on the ground left out of the ground because another road lies over them
  /// in plan (plan_overlaps); the terrain closes the step between the two.
  std::size_t ground_triangles_under_roads = 0;
};

struct Scene {
  /// The meshes in CARLA's naming, each with vertex normals, in the model's frame:
  /// Road_Road, Road_Marking, Road_Sidewalk (when any), Terrain (when built); empty ones left out.
  MeshScene meshes;
  /// The paved surface as built, with the owner of each Road_Road triangle. Its meshes (road,
  /// marking, sidewalk) are moved into `meshes` and empty here, as is terrain->terrain: a city's
  /// meshes are hundreds of MB, and one copy of each is kept.
  RoadMeshes roads;
  /// Per triangle of roads.road: 1 when it is part of the ground the terrain meets; 1 when in a tunnel.
  std::vector<std::uint8_t> ground, tunnel;
  TriangleMesh ground_road;  ///< the triangles of roads.road flagged `ground`
  /// Top edge of every opening as (road vertex, the terrain's position above it) (ground_openings.h).
  std::vector<std::pair<Vec3, Vec3>> opening_tops;
  std::optional<TerrainBuild> terrain;  ///< with SceneOptions::terrain
  SceneStats stats;
  std::optional<SceneChecks> checks;  ///< with SceneOptions::checks
};

/// Builds the scene. Data problems (a junction that cannot be triangulated, roads overlapping
/// in plan, and with SceneOptions::checks the findings of report_scene_checks) go to
/// `diagnostics`; throws InvalidInput for options out of range. `network` gives each road's
/// OSM attributes (bridge, tunnel). `progress`, when set, is called with ("mesh roads", 0) and
/// (…, 1) around the paved surface and ("mesh terrain", 0 / 1) around the terrain.
[[nodiscard]] Scene build_scene(const RoadModel& model, const RoadNetwork& network, const DemSampler& dem,
                                const SceneOptions& options, Diagnostics& diagnostics,
                                const ProgressFn& progress = {});

/// The quality checks of a built scene. Only reads `scene` (safe beside other readers).
[[nodiscard]] SceneChecks check_scene(const Scene& scene);

/// Reports the checks' findings: triangles of structures crossing the terrain
/// ("mesh.structure_terrain_intersections", with a terrain) and self-intersecting Road_Road
/// pairs named by their roads and junctions ("mesh.road_self_intersections").
void report_scene_checks(const Scene& scene, const SceneChecks& checks, const RoadModel& model,
                         Diagnostics& diagnostics);

}  // namespace relief
