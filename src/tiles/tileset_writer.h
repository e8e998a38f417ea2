#pragma once
// OGC 3D Tiles 1.1 tileset.json over a region's scene tiles (glb content): one root whose
// transform puts the local frame on the WGS84 ellipsoid (east-north-up at the frame's origin),
// without content, refined by adding its children: one node per tile. A tile with a coarse
// level of detail (scene_lod.h) is two nodes: the coarse glb with the coarse geometry's measured
// error as geometricError, refined by replacing it with its one child, the full glb (error 0);
// a tile without is the full glb alone. Every box holds its content's vertices and its
// children's boxes; the root's geometricError (and the tileset's) is the diagonal of its box
// (what is missing when nothing is drawn), never less than a tile's.

#include <filesystem>
#include <string>
#include <vector>

#include "relief/geometry/geo_frame.h"
#include "relief/geometry/types.h"

namespace relief::detail {

struct TilesetTile {
  std::string uri;                              ///< relative to tileset.json
  Vec3 min = Vec3::Zero(), max = Vec3::Zero();  ///< local frame, z up: the full content's box
  std::string coarse_uri;                       ///< empty: no coarse level
  Vec3 coarse_min = Vec3::Zero(), coarse_max = Vec3::Zero();
  double coarse_error_m = 0.0;  ///< what is lost when the coarse content is drawn instead (metres)
};

/// tileset.json text.
[[nodiscard]] std::string tileset_json(const GeoFrame& frame, const std::vector<TilesetTile>& tiles);

}  // namespace relief::detail
