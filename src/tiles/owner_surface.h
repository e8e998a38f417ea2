#pragma once
// Private to the tiles module: every piece of the region's paved surface takes its owner's
// heights. The scene is cut into tiles by triangle centroid (the rule CARLA's large-map tiles
// and --mesh-tile-size follow), so a road crossing a tile edge has its triangles in two tiles'
// files, each from that tile's own fit; where the two fits differ (a mountain climb that
// neither window sees whole) the road steps at the tile edge. The merged OpenDRIVE takes every
// road and junction from its owner (xodr_merge.h), so the owner's fit is the region's: each tile
// writes the paved vertices of the roads and junctions it owns, over its whole window (a road
// it owns runs on beyond its core), and the merge gives every paved vertex of every tile's file
// the height of the owner's vertex at its place (the lofted vertices of a road are placed by its
// reference line alone, the same bits in every window), moving the terrain's vertices on a road
// edge with it. What no owner has (a road its owner's window cut short) is left as built and
// counted; where two owners' vertices meet at one place (a road's end and the junction or road
// it joins) the first tile's is taken and their difference reported.

#include <cstddef>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "relief/geometry/triangle_mesh.h"
#include "relief/geometry/types.h"
#include "relief/roads/road_model.h"
#include "relief/scene/scene.h"

namespace relief::detail {

inline constexpr char kOwnedSurfaceFile[] = "owned_surface.bin";

/// The vertices of the paved triangles a tile owns, by mesh name (Road_Road, Road_Sidewalk,
/// Road_Marking), in the frame (not quantised as the tile's files are).
struct OwnedSurface {
  std::map<std::string, std::vector<Vec3>> vertices;
};

/// The vertices of `scene`'s paved triangles whose road (road_anchor in `core`) or junction
/// (junction_anchor in `core`, with its connecting roads) the tile of `core` owns: the rule
/// merge_models keeps elements by.
[[nodiscard]] OwnedSurface owned_surface(const RoadModel& model, const Scene& scene, const Aabb2& core);

void write_owned_surface(const std::filesystem::path& path, const OwnedSurface& surface);
/// Throws InvalidInput for a file that is not one write_owned_surface wrote.
[[nodiscard]] OwnedSurface read_owned_surface(const std::filesystem::path& path);

struct OwnerHeights {
  std::size_t vertices = 0;          ///< paved vertices of the tiles' files
  std::size_t moved = 0;             ///< of them, given their owner's different height
  std::size_t unmatched = 0;         ///< with no owner's vertex within the tolerance: left as built
  Vec3 unmatched_at = Vec3::Zero();  ///< the first of them
  /// Of them, moved by their mesh neighbours' changes (inverse-distance weighted): a station the
  /// owner's loft did not make between two it did.
  std::size_t interpolated = 0;
  double max_dz_m = 0.0;          ///< largest height change
  Vec3 at = Vec3::Zero();         ///< where (the vertex as its tile built it)
  std::size_t terrain_moved = 0;  ///< terrain vertices on a moved road vertex, moved with it
  /// Terrain vertices on a tile's border whose copies in two or more tiles' files stood apart
  /// beside a road (each tile's batter followed its own fit of the road), now all at the copy of
  /// the tile whose nearest paved vertex moved least: how many places, the largest change, where.
  std::size_t terrain_seams = 0;
  double terrain_seams_max_dz_m = 0.0;
  Vec3 terrain_seams_at = Vec3::Zero();
  /// Places where two owners' vertices meet (a road's end and the junction or road it joins, of
  /// two tiles) at heights more than 1 mm apart: how many, the largest difference and where.
  std::size_t owners_apart = 0;
  double owners_apart_max_m = 0.0;
  Vec3 owners_apart_at = Vec3::Zero();
};

/// The terrain's batter reaches this far from a road edge (TerrainOptions::max_slope_width_m's
/// default): a terrain vertex farther from every paved vertex does not follow a road's fit.
inline constexpr double kBatterReachM = 30.0;

/// Gives every vertex of the tiles' paved meshes the height of the nearest vertex of the same
/// mesh in `owned` within `tolerance_m` in plan (of `owned` in order: at a place two owners
/// share, the first's), a vertex no owner has its mesh neighbours' change; then every Terrain
/// vertex at the plan position (exact bits) of a Road_Road vertex of any tile's file, and within
/// 1 m of its height (not an opening's top), that vertex's height. Then the Terrain vertices on
/// the border of a tile's `cores` entry (one per tile, the order of `tiles`) that two tiles'
/// files hold at different heights: every copy takes the one of the tile whose paved vertex
/// nearest it (within kBatterReachM) moved least, the road's owner where it is one of them (a
/// place no copy's tile has a paved vertex near is left to the weld). Linear (hash grids).
OwnerHeights take_owner_heights(std::vector<MeshScene>& tiles, const std::vector<Aabb2>& cores,
                                const std::vector<OwnedSurface>& owned, double tolerance_m = 1e-3);

}  // namespace relief::detail
