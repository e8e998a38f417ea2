#include "scene/ground_support.h"

#include <algorithm>
#include <optional>
#include <unordered_map>

namespace relief {
namespace {

constexpr double kDeckOnGroundM = 1.0;  // a deck triangle this close above the DEM lies on it

}  // namespace

// Structure triangles the terrain would cut through count as ground (the terrain then meets
// them): a deck within kDeckOnGroundM above the DEM or below it at a corner (a deck cut off by
// the data's edge follows the DEM; nothing passes under it, or the fit would have lifted it), and a tunnel
// triangle with less than the mouth's height of DEM over it (the tunnel runs in a cutting there,
// and its mouth moves to where the cover is enough).
void structures_on_the_ground(const TriangleMesh& road, const DemSampler& dem, double mouth_height_m,
                              GroundSupport& s) {
  std::vector<std::uint32_t> used;
  for (std::size_t i = 0; i < road.triangles.size(); ++i) {
    if (!s.ground[i]) used.insert(used.end(), road.triangles[i].begin(), road.triangles[i].end());
  }
  std::sort(used.begin(), used.end());
  used.erase(std::unique(used.begin(), used.end()), used.end());
  std::vector<Vec2> xy;
  xy.reserve(used.size());
  for (const std::uint32_t v : used) xy.emplace_back(road.vertices[v].head<2>());
  std::vector<std::optional<double>> z_dem(used.size());
  dem.heights_at(xy, z_dem);
  const auto dem_at = [&](std::uint32_t v) {
    return z_dem[static_cast<std::size_t>(std::lower_bound(used.begin(), used.end(), v) - used.begin())];
  };
  for (std::size_t i = 0; i < road.triangles.size(); ++i) {
    if (s.ground[i]) continue;
    bool deck_on_dem = false, shallow = false;
    for (const std::uint32_t v : road.triangles[i]) {
      const std::optional<double> z = dem_at(v);
      deck_on_dem = deck_on_dem || (z && road.vertices[v].z() - *z <= kDeckOnGroundM);
      shallow = shallow || (z && *z - road.vertices[v].z() < mouth_height_m);
    }
    if (s.tunnel[i] ? shallow : deck_on_dem) {
      s.ground[i] = 1;
      s.counted_as_ground[i] = s.tunnel[i] ? 2 : 1;
      ++(s.tunnel[i] ? s.tunnels_open : s.decks_on_ground);
      s.tunnel[i] = 0;
    }
  }
}

// A structure triangle counted as ground that lies over another road in plan (a deck's end
// over the street in the cutting beneath it) stays a structure: as ground, the terrain would
// close the step under it across the lower road. Returns whether any did.
bool keep_covering_structures(const PlanOverlaps& overlaps, GroundSupport& s) {
  bool any = false;
  for (const auto& [lower, upper] : overlaps.lower_upper) {
    if (!s.counted_as_ground[upper]) continue;
    s.ground[upper] = 0;
    s.tunnel[upper] = s.counted_as_ground[upper] == 2;
    --(s.tunnel[upper] ? s.tunnels_open : s.decks_on_ground);
    s.counted_as_ground[upper] = 0;
    any = true;
  }
  return any;
}

GroundSupport triangle_support(const RoadMeshes& roads, const RoadModel& model, const RoadNetwork& network) {
  std::unordered_map<int, WayAttributes> attributes;  // OpenDRIVE road id -> its OSM way's
  for (const ModelRoad& road : model.roads) {
    if (road.source_road >= 0)
      attributes[road.id] = network.roads[static_cast<std::size_t>(road.source_road)].attributes;
  }
  GroundSupport s;
  s.ground.assign(roads.road.triangles.size(), 1);
  s.tunnel.assign(roads.road.triangles.size(), 0);
  s.counted_as_ground.assign(roads.road.triangles.size(), 0);
  for (std::size_t i = 0; i < s.ground.size(); ++i) {
    const auto it = attributes.find(roads.road_triangle_owner[i]);
    if (it == attributes.end()) continue;  // a junction patch
    s.ground[i] = !(it->second.bridge || it->second.tunnel);
    s.tunnel[i] = it->second.tunnel;
  }
  return s;
}

}  // namespace relief
