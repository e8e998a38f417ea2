#pragma once
// OGC 3D Tiles 1.1 tileset.json over a region's scene tiles (glb content): one root whose
// transform puts the local frame on the WGS84 ellipsoid (east-north-up at the frame's origin),
// one child per tile with the bounding box of its glb, refined by adding.

#include <filesystem>
#include <string>
#include <vector>

#include "relief/geometry/geo_frame.h"
#include "relief/geometry/types.h"

namespace relief::detail {

struct TilesetTile {
  std::string uri;                              ///< relative to tileset.json
  Vec3 min = Vec3::Zero(), max = Vec3::Zero();  ///< local frame, z up
};

/// tileset.json text. `geometric_error_m`: the root's (what is lost when only it is drawn).
[[nodiscard]] std::string tileset_json(const GeoFrame& frame, const std::vector<TilesetTile>& tiles,
                                       double geometric_error_m);

}  // namespace relief::detail
