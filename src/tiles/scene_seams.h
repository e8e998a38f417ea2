#pragma once
// The seams between a region's scene tiles. Each tile is built over its own window, so a vertex
// on the line between two tiles is computed twice: its plan position comes out with the same
// bits in both builds (the reference lines and the DEM do not depend on the window) and its
// height within the fits' agreement (well under a millimetre where the windows see enough). The
// weld gives every such vertex the height of the first tile that has it, so neighbouring tiles
// share their border vertices bit for bit; where the two fits disagree by more than the weld's
// tolerance the vertex is left apart and counted (a step the merge reports).

#include <bit>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "relief/geometry/triangle_mesh.h"

namespace relief::detail {

/// A vertex's plan position by its exact bits: the same point in two tiles' files.
struct PlanKey {
  std::uint64_t x, y;
  bool operator==(const PlanKey&) const = default;
};
struct PlanKeyHash {
  std::size_t operator()(const PlanKey& k) const {
    return std::hash<std::uint64_t>()(k.x * 0x9E3779B97F4A7C15ull ^ k.y);
  }
};
inline PlanKey plan_key(const Vec3& v) {
  return {std::bit_cast<std::uint64_t>(v.x()), std::bit_cast<std::uint64_t>(v.y())};
}

/// Shared vertices of one mesh left apart by the weld: how many, the largest height difference
/// and where (the later tile's vertex).
struct SeamApart {
  std::size_t vertices = 0;
  double max_m = 0.0;
  Vec3 at = Vec3::Zero();
};

struct SeamWeld {
  std::size_t shared_vertices = 0;  ///< vertices of a later tile at the plan position of an earlier one's
  std::size_t welded = 0;           ///< of them, moved to the earlier tile's height
  double max_dz_m = 0.0;            ///< largest height difference welded
  /// Of the shared vertices, those left apart (their heights differ by more than the weld's
  /// max_dz_m: the two tiles' fits disagree there), by mesh name.
  std::map<std::string, SeamApart> left_apart;
};

/// Welds the tiles' meshes of the same name, in the order given: a vertex whose plan position
/// (exact bits) is a vertex of an earlier tile's mesh and whose height is within `max_dz_m` of
/// it takes that height; one farther is left apart and counted. Linear (a hash of plan
/// positions).
SeamWeld weld_seams(std::vector<MeshScene>& tiles, double max_dz_m = 0.01);

/// Every tile's mesh `name` in one mesh, vertices at the same position (exact bits) merged: the
/// region's surface as a whole build would have it, for its checks.
[[nodiscard]] TriangleMesh joined_mesh(const std::vector<MeshScene>& tiles, const std::string& name);

}  // namespace relief::detail
