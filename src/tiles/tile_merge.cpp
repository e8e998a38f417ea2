#include <algorithm>
#include <array>
#include <cstdint>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "relief/core/atomic_file.h"
#include "relief/core/diagnostic_codes.h"
#include "relief/core/errors.h"
#include "relief/export/mesh_writer.h"
#include "relief/export/opendrive_writer.h"
#include "relief/export/report_writer.h"
#include "relief/geometry/mesh_quality.h"
#include "relief/roads/opendrive_reader.h"
#include "relief/roads/road_model_checks.h"
#include "relief/tiles/tiles.h"
#include "tiles/carla_merge.h"
#include "tiles/model_alignment.h"
#include "tiles/owner_surface.h"
#include "tiles/scene_lod.h"
#include "tiles/scene_seams.h"
#include "tiles/sumo_merge.h"
#include "tiles/tile_record.h"
#include "tiles/tileset_writer.h"
#include "tiles/xodr_merge.h"

namespace relief {
namespace {

std::string tile_name(const TileSpec& t) {
  return std::to_string(t.x) + "_" + std::to_string(t.y);
}

nlohmann::json read_json(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw IoError("cannot read " + path.string());
  return nlohmann::json::parse(in);
}

// Whether a glb relief wrote holds any mesh: a tile whose core has no triangle (roads that only
// pass its corner) writes a glb without meshes, which assimp refuses to read.
bool glb_holds_meshes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::array<std::uint32_t, 5> head{};  // magic, version, length, JSON chunk length, chunk type
  if (!in.read(reinterpret_cast<char*>(head.data()), sizeof head)) return false;
  std::string json(head[3], '\0');
  if (!in.read(json.data(), static_cast<std::streamsize>(json.size()))) return false;
  return json.find("\"meshes\"") != std::string::npos && json.find("\"meshes\":[]") == std::string::npos;
}

}  // namespace

TileMergeResult merge_tiles(const std::filesystem::path& dir, const TileMergeOptions& options,
                            Diagnostics& diagnostics) {
  const TileManifest manifest = read_manifest(dir);
  const std::filesystem::path merged = dir / "merged";
  TileMergeResult result;
  nlohmann::json tiles_json = nlohmann::json::array();
  std::vector<detail::TileModel> models;
  std::vector<detail::TilesetTile> tileset;
  std::vector<MeshScene> scenes;
  std::vector<detail::OwnedSurface> owned;  // per tile that wrote one, in the plan's order
  std::vector<std::string> scene_names;
  std::vector<Aabb2> scene_cores;
  std::vector<std::pair<int, int>> scene_tiles;
  std::vector<std::vector<MeshFormat>> scene_formats;
  OutputSet files;
  double seconds = 0.0, peak_rss_mb = 0.0;
  std::string peak_tile;
  for (const TileSpec& spec : manifest.tiles) {
    const std::filesystem::path here = tile_dir(dir, spec.x, spec.y);
    const std::optional<detail::TileRecord> record = detail::read_tile_record(here);
    if (!record || record->key != detail::dependency_state(dir, manifest, spec).key) {
      throw InvalidInput("tile " + std::to_string(spec.x) + "," + std::to_string(spec.y) + " is " +
                         (record ? "out of date" : "not built") + ": run relief tiles build " + dir.string() +
                         " --tile " + std::to_string(spec.x) + "," + std::to_string(spec.y) + " (or --all)");
    }
    ++result.tiles;
    seconds += record->seconds;
    if (record->peak_rss_mb > peak_rss_mb) {
      peak_rss_mb = record->peak_rss_mb;
      peak_tile = tile_name(spec);
    }
    for (const std::string& g : record->failed_gates)
      result.failed_gates.push_back(tile_name(spec) + ": " + g);
    nlohmann::json t = read_json(here / detail::kTileRecordFile);
    t.erase("key");
    tiles_json.push_back(t);

    const std::filesystem::path out = here / "out";
    if (const std::filesystem::path xodr = out / (manifest.name + ".xodr"); std::filesystem::exists(xodr)) {
      models.push_back({spec.x, spec.y, spec.core, read_opendrive(xodr)});
    }
    if (const std::filesystem::path o = here / detail::kOwnedSurfaceFile; std::filesystem::exists(o))
      owned.push_back(detail::read_owned_surface(o));
    if (const std::filesystem::path glb = out / (manifest.name + ".glb");
        std::filesystem::exists(glb) && glb_holds_meshes(glb)) {
      scenes.push_back(read_mesh_file(glb));
      scene_names.push_back(manifest.name + "_Tile_" + tile_name(spec));
      scene_cores.push_back(spec.core);
      scene_tiles.emplace_back(spec.x, spec.y);
      scene_formats.push_back({MeshFormat::glb});
      if (std::filesystem::exists(out / (manifest.name + ".fbx")))
        scene_formats.back().push_back(MeshFormat::fbx);
    }
  }

  std::filesystem::create_directories(merged);  // every tile is built: the merge can be written
  // The scene tiles: every paved vertex at its owner's height, their seams welded, then their
  // checks as one surface.
  const detail::OwnerHeights heights = detail::take_owner_heights(scenes, scene_cores, owned);
  owned.clear();
  owned.shrink_to_fit();
  result.paved_vertices = heights.vertices;
  result.paved_moved = heights.moved;
  result.paved_unmatched = heights.unmatched;
  result.paved_interpolated = heights.interpolated;
  result.paved_max_dz_m = heights.max_dz_m;
  result.terrain_seams = heights.terrain_seams;
  result.terrain_seams_max_dz_m = heights.terrain_seams_max_dz_m;
  const detail::SeamWeld weld = detail::weld_seams(scenes);
  const double lod_cell_m = options.lod_cell_m > 0.0 ? options.lod_cell_m : manifest.tile_size_m / 32.0;
  nlohmann::json lod_json = nlohmann::json::array();
  // CARLA's large map takes the FBX tiles as they are written.
  std::size_t fbx_tiles = 0;
  for (const std::vector<MeshFormat>& formats : scene_formats)
    fbx_tiles += std::count(formats.begin(), formats.end(), MeshFormat::fbx);
  const std::string carla_refusal = detail::carla_large_map_refusal(manifest, fbx_tiles);
  std::vector<EncodedFile> carla_fbx;
  std::vector<std::pair<int, int>> carla_tiles;
  double lowest_z = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < scenes.size(); ++i) {
    for (const MeshFormat format : scene_formats[i]) {
      for (EncodedFile& f : encode_mesh_scene(scenes[i], format, scene_names[i])) {
        const std::filesystem::path to = merged / f.filename;
        files.add(to, [&f](std::ostream& o) { o << f.bytes; });
        result.written.push_back(to);
        if (format == MeshFormat::fbx && carla_refusal.empty()) {
          carla_fbx.push_back(std::move(f));
          carla_tiles.push_back(scene_tiles[i]);
        }
      }
    }
    for (const TriangleMesh& m : scenes[i].meshes)
      for (const Vec3& v : m.vertices) lowest_z = std::min(lowest_z, v.z());
    ++result.scene_tiles;
    detail::TilesetTile tile;
    tile.uri = scene_names[i] + ".glb";
    detail::scene_bounds(scenes[i], tile.min, tile.max);
    // The coarse level: a glb of its own, measured against the full tile.
    detail::SceneLod lod = detail::coarsen_scene(scenes[i], lod_cell_m, scene_cores[i]);
    lod.scene.file_origin = scenes[i].file_origin;
    tile.coarse_uri = scene_names[i] + "_lod1.glb";
    detail::scene_bounds(lod.scene, tile.coarse_min, tile.coarse_max);
    tile.coarse_error_m = lod.error_m();
    for (EncodedFile& f : encode_mesh_scene(lod.scene, MeshFormat::glb, scene_names[i] + "_lod1")) {
      const std::filesystem::path to = merged / f.filename;
      files.add(to, [bytes = std::move(f.bytes)](std::ostream& o) { o << bytes; });
      result.written.push_back(to);
    }
    result.lod_full_triangles += lod.full_triangles;
    result.lod_coarse_triangles += lod.coarse_triangles;
    result.lod_max_error_m = std::max(result.lod_max_error_m, tile.coarse_error_m);
    lod_json.push_back({{"tile", scene_names[i]},
                        {"full_triangles", lod.full_triangles},
                        {"coarse_triangles", lod.coarse_triangles},
                        {"max_vertex_shift_m", lod.max_vertex_shift_m},
                        {"coarse_to_full_m", lod.coarse_to_full_m},
                        {"max_full_to_coarse_m", lod.max_full_to_coarse_m},
                        {"geometric_error_m", tile.coarse_error_m}});
    if (tile.min.allFinite()) tileset.push_back(tile);
  }

  nlohmann::json report;
  report["name"] = manifest.name;
  report["relief_version"] = relief_version();
  report["tile_size_m"] = manifest.tile_size_m;
  report["halo_m"] = manifest.halo_m;
  report["tiles"] = tiles_json;
  report["tile_builds"] = {
      {"seconds", seconds}, {"largest_peak_rss_mb", peak_rss_mb}, {"largest_tile", peak_tile}};
  if (!models.empty()) {
    detail::ModelMergeResult m = detail::merge_models(models);
    result.roads = m.model.roads.size();
    result.junctions = m.model.junctions.size();
    report["opendrive"] = {{"roads", result.roads},
                           {"junctions", result.junctions},
                           {"links_unresolved", m.links_unresolved},
                           {"first_unresolved", m.first_unresolved}};
    if (m.links_unresolved > 0) result.failed_gates.push_back("merge: " + m.first_unresolved);
    for (const std::string& where : m.unresolved) {
      diagnostics.report(Severity::error, codes::kTilesLinkUnresolved, where);
    }
    // Links across tiles join two owners' copies: their lane borders must meet as in one build
    // (the build's link_height_step_m gate, 1 cm), or the region has a step where tiles disagree.
    const LinkContinuity links = check_link_continuity(m.model);
    report["opendrive"]["max_link_gap_m"] = links.max_horizontal_m;
    report["opendrive"]["max_link_step_m"] = links.max_vertical_m;
    report["opendrive"]["links_over_1cm"] = links.over_tolerance;
    if (links.worst_road >= 0) {
      // Where the largest step is, and which tiles the two roads came from.
      const auto tile_of = [&](int road) {
        const auto it = m.road_tile.find(road);
        return it == m.road_tile.end()
                   ? std::string("?")
                   : std::to_string(it->second.first) + "_" + std::to_string(it->second.second);
      };
      const Vec3& at = links.worst_at;
      report["opendrive"]["worst_link"] = {
          {"roads", {links.worst_road, links.worst_other_road}},
          {"tiles", {tile_of(links.worst_road), tile_of(links.worst_other_road)}},
          {"at", {at.x(), at.y(), at.z()}}};
      if (links.over_tolerance > 0) {
        std::ostringstream where;
        where << "merge: " << links.over_tolerance << " lane borders apart at road links (largest "
              << links.max_horizontal_m << " m in plan, " << links.max_vertical_m << " m in height, road "
              << links.worst_road << " of tile " << tile_of(links.worst_road) << " to road "
              << links.worst_other_road << " of tile " << tile_of(links.worst_other_road) << " at (" << at.x()
              << ", " << at.y() << ")): tiles disagree there";
        result.failed_gates.push_back(where.str());
      }
    }
    if (options.whole_xodr) {
      const detail::WholeBuildComparison c =
          detail::compare_with_whole(read_opendrive(*options.whole_xodr), m.model);
      result.whole_roads = c.roads;
      result.whole_unmatched = c.unmatched;
      result.whole_max_xy_m = c.deviation.max_xy_m;
      result.whole_max_z_m = c.deviation.max_z_m;
      result.whole_roads_over_1mm = c.roads_over_1mm;
      report["whole_build"] = {{"xodr", options.whole_xodr->string()},
                               {"roads", c.roads},
                               {"unmatched", c.unmatched},
                               {"points", c.deviation.points},
                               {"max_xy_m", c.deviation.max_xy_m},
                               {"max_z_m", c.deviation.max_z_m},
                               {"roads_over_1mm", c.roads_over_1mm},
                               {"roads_over_1cm", c.roads_over_1cm},
                               {"worst_road", c.deviation.worst_road}};
    }
    if (options.sumo_net) {
      SumoOptions sumo = options.sumo;
      sumo.grade_caps = detail::model_grade_caps(m.model, options.fit);
      report["sumo"] = detail::merge_sumo_net(m.model, sumo, options.gates, merged, manifest.name, files,
                                              result.written, result.failed_gates, diagnostics);
    }
    const std::filesystem::path xodr = merged / (manifest.name + ".xodr");
    std::ostringstream xodr_text;
    write_opendrive(xodr_text, m.model);
    files.add(xodr, [&xodr_text](std::ostream& o) { o << xodr_text.view(); });
    result.written.push_back(xodr);
    if (carla_refusal.empty()) {
      report["carla"] = detail::write_carla_large_map(
          manifest, std::move(xodr_text).str(), std::move(carla_fbx), carla_tiles, lowest_z, scenes.front(),
          merged, files, result.written, diagnostics);
    } else {
      report["carla"] = {{"package", nullptr}, {"why_not", carla_refusal}};
    }
  }
  if (!tileset.empty()) {
    const std::string text = detail::tileset_json(manifest.frame, tileset);
    files.add(merged / "tileset.json", [&text](std::ostream& o) { o << text; });
    result.written.push_back(merged / "tileset.json");
  }
  report["scene_tiles"] = result.scene_tiles;
  report["lod1"] = {{"cell_m", lod_cell_m},
                    {"full_triangles", result.lod_full_triangles},
                    {"coarse_triangles", result.lod_coarse_triangles},
                    {"max_geometric_error_m", result.lod_max_error_m},
                    {"tiles", lod_json}};
  report["seams"] = {
      {"shared_vertices", weld.shared_vertices}, {"welded", weld.welded}, {"max_dz_m", weld.max_dz_m}};
  report["seams"]["left_apart"] = nlohmann::json::object();
  for (const auto& [mesh, apart] : weld.left_apart) {
    report["seams"]["left_apart"][mesh] = {{"vertices", apart.vertices},
                                           {"max_m", apart.max_m},
                                           {"at", {apart.at.x(), apart.at.y(), apart.at.z()}}};
  }
  const auto point = [](const Vec3& p) { return nlohmann::json{p.x(), p.y(), p.z()}; };
  report["seams"]["owner_heights"] = {{"vertices", heights.vertices},
                                      {"moved", heights.moved},
                                      {"max_dz_m", heights.max_dz_m},
                                      {"at", point(heights.at)},
                                      {"unmatched", heights.unmatched},
                                      {"unmatched_at", point(heights.unmatched_at)},
                                      {"interpolated", heights.interpolated},
                                      {"terrain_moved", heights.terrain_moved},
                                      {"terrain_seams", heights.terrain_seams},
                                      {"terrain_seams_max_dz_m", heights.terrain_seams_max_dz_m},
                                      {"terrain_seams_at", point(heights.terrain_seams_at)},
                                      {"owners_apart", heights.owners_apart},
                                      {"owners_apart_max_m", heights.owners_apart_max_m},
                                      {"owners_apart_at", point(heights.owners_apart_at)}};
  // Two owners whose surfaces meet at different heights (a road's end and the junction it joins,
  // from two tiles' fits): the merged surface takes the first's, a step in the other's element.
  if (heights.owners_apart_max_m > 0.01) {
    std::ostringstream where;
    const Vec3& p = heights.owners_apart_at;
    where << "merge: " << heights.owners_apart
          << " places where the paved surfaces of two tiles' elements meet "
          << "more than 1 mm apart, the largest " << heights.owners_apart_max_m << " m at (" << p.x() << ", "
          << p.y() << ", " << p.z() << ") (over 1 cm): the tiles' fits disagree where their roads join";
    result.failed_gates.push_back(where.str());
  }
  // A road vertex the two tiles put at different heights is a step in the region's road surface
  // (the terrain is simplified per window, so its seams are not held to this).
  if (const auto road = weld.left_apart.find("Road_Road"); road != weld.left_apart.end()) {
    std::ostringstream where;
    const Vec3& p = road->second.at;
    where << "merge: " << road->second.vertices
          << " Road_Road vertices of two tiles more than 1 cm apart in height (largest " << road->second.max_m
          << " m at (" << p.x() << ", " << p.y() << ", " << p.z() << ")): the tiles' fits disagree there";
    result.failed_gates.push_back(where.str());
  }
  if (!scenes.empty()) {
    const MeshQuality road = analyse_mesh(detail::joined_mesh(scenes, "Road_Road"));
    const MeshQuality terrain = analyse_mesh(detail::joined_mesh(scenes, "Terrain"));
    result.road_self_intersections = road.self_intersecting_pairs;
    for (const MeshQuality* q : {&road, &terrain}) {
      report["joined"][q == &road ? "Road_Road" : "Terrain"] = {
          {"triangles", q->triangles},
          {"self_intersecting_pairs", q->self_intersecting_pairs},
          {"boundary_loops", q->boundary_loops},
          {"holes", q->holes},
          {"non_manifold_edges", q->non_manifold_edges}};
      // Where to look: the first self-intersecting pairs' places.
      nlohmann::json sites = nlohmann::json::array();
      for (std::size_t i = 0; i < q->self_intersection_sites.size() && i < 5; ++i) {
        const Vec3& p = q->self_intersection_sites[i];
        sites.push_back({p.x(), p.y(), p.z()});
      }
      report["joined"][q == &road ? "Road_Road" : "Terrain"]["first_self_intersections"] = sites;
    }
    if (road.self_intersecting_pairs > 0) {
      std::ostringstream where;
      const Vec3& p = road.self_intersection_sites.front();
      where << "merge: " << road.self_intersecting_pairs
            << " self-intersecting Road_Road pairs, the first at (" << p.x() << ", " << p.y() << ", " << p.z()
            << ")";
      result.failed_gates.push_back(where.str());
    }
  }
  // Last, with every failed gate: the tiles' and the merge's own.
  report["failed_gates"] = result.failed_gates;
  files.add(merged / "report.json", [&report](std::ostream& o) { o << report.dump(1) << "\n"; });
  result.written.push_back(merged / "report.json");
  files.commit();
  return result;
}

}  // namespace relief
