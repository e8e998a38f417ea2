#pragma once
// Which road triangles form the ground the terrain meets: not bridge decks nor tunnels, except
// the structure triangles the terrain would cut through (a deck lying on the DEM, a tunnel
// without cover), unless they lie over another road.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "relief/geometry/plan_overlap.h"
#include "relief/roads/road_model.h"
#include "relief/roads/road_network.h"
#include "relief/scene/road_mesh.h"
#include "relief/terrain/dem_sampler.h"

namespace relief {

/// Per triangle of the road mesh: 1 when it lies on the ground, 1 when in a tunnel.
struct GroundSupport {
  std::vector<std::uint8_t> ground, tunnel;
  std::vector<std::uint8_t> counted_as_ground;        ///< 1: a deck, 2: a tunnel triangle
  std::size_t decks_on_ground = 0, tunnels_open = 0;  ///< structure triangles counted as ground
};

/// From the OSM attributes of each triangle's road: junction patches and roads that are
/// neither bridge nor tunnel are ground.
[[nodiscard]] GroundSupport triangle_support(const RoadMeshes& roads, const RoadModel& model,
                                             const RoadNetwork& network);

/// Counts as ground a deck triangle within 1 m above the DEM (or below it) at one of its corners,
/// and a tunnel triangle with less than `mouth_height_m` of DEM over one of its corners.
void structures_on_the_ground(const TriangleMesh& road, const DemSampler& dem, double mouth_height_m,
                              GroundSupport& s);

/// Returns to structures those counted as ground that are the upper triangle of an overlap in
/// plan (a deck's end over the street beneath it); whether any was.
bool keep_covering_structures(const PlanOverlaps& overlaps, GroundSupport& s);

}  // namespace relief
