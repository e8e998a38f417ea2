#pragma once
// Square plan tiles of a scene, for large areas that game engines import piece by piece
// (CARLA's large maps take one file per tile, named NAME_Tile_X_Y).

#include <vector>

#include "relief/geometry/triangle_mesh.h"

namespace relief {

/// One tile: grid column x (east) and row y (north), counted from 0 at the tile holding the
/// scene's south-west corner; its plan bounds in the local frame; the meshes of its triangles.
struct SceneTile {
  int x = 0, y = 0;
  Aabb2 bounds;
  MeshScene scene;
};

/// Splits `scene` into tiles of size_m x size_m on the grid whose lines lie at multiples of
/// size_m in the local frame. Every triangle goes whole to the tile holding its centroid, so
/// the tiles' triangle counts add up to the scene's and neighbouring tiles share the exact
/// vertex positions along their ragged common edge (no gap, no overlap). Each tile's meshes
/// keep their names and kinds (a mesh without triangles in a tile is left out of it), its scene
/// the cell's file origin, the frame and metadata plus "relief:tile" ("X Y") and
/// "relief:tile_bounds" ("xmin ymin xmax ymax", local metres). Tiles without triangles are left
/// out; tiles come in row-major order (y, then x). Linear in the number of triangles. Throws
/// InvalidInput unless size_m is positive and finite.
[[nodiscard]] std::vector<SceneTile> split_into_tiles(const MeshScene& scene, double size_m);

/// The FileOrigin (triangle_mesh.h) of grid cell (column, row) of size_m (cell (c, r) spans
/// size_m * [c, c + 1)): its centre in whole metres, the smallest power-of-two quantum at which
/// a float holds every value within 2 size_m of it. Throws InvalidInput unless size_m is
/// positive and finite.
[[nodiscard]] FileOrigin cell_file_origin(double size_m, long long column, long long row);

/// The triangles of `scene` that split_into_tiles puts in the grid cell (column, row), counted
/// from the frame's origin (cell (c, r) spans size_m * [c, c + 1) x [r, r + 1)): a region
/// tile's own piece of a scene built over its window. Same frame and metadata, the cell's file
/// origin; meshes without triangles there are left out.
[[nodiscard]] MeshScene scene_in_cell(const MeshScene& scene, double size_m, long long column, long long row);

}  // namespace relief
