#pragma once
// A small synthetic world for the scene tests: on a level plane at 20 m, a street along x
// (-150, 0) -> (100, 0) ending in a T junction with a street along x = 100, crossed at the
// origin by a bridge along y whose deck rises 7 m over the street (a Gaussian bump, sigma 40 m;
// no shared node). Profiles are given, not fitted: the plane's drape, plus the bump on the
// bridge, so the street's surface lies exactly at 20 m.

#include <cmath>

#include "relief/core/diagnostics.h"
#include "relief/roads/road_model_builder.h"
#include "relief/terrain/dem_sampler.h"
#include "support/synthetic.h"

namespace relief::test {

inline constexpr double kWorldGroundM = 20.0;
inline constexpr double kWorldDeckRiseM = 7.0;

struct BridgeWorld {
  RoadNetwork network;
  RoadModelBuild built;
  DemSampler dem;
};

inline WayAttributes world_street(bool bridge = false) {
  WayAttributes a;
  a.highway = HighwayClass::residential;
  a.lanes_forward = 1;
  a.lanes_backward = 1;
  a.lane_width_m = 3.0;
  a.bridge = bridge;
  a.layer = bridge ? 1 : 0;
  return a;
}

inline BridgeWorld make_bridge_world(Diagnostics& diagnostics) {
  RoadNetwork network = make_network(
      {{{-150, 0}, {100, 0}}, {{100, 0}, {100, 100}}, {{100, 0}, {100, -100}}, {{0, -150}, {0, 150}}},
      {world_street(), world_street(), world_street(), world_street(true)});
  std::vector<RoadProfile> profiles = drape(network, [](const Vec2&) { return kWorldGroundM; });
  RoadProfile& bridge = profiles.back();
  for (std::size_t i = 0; i < bridge.size(); ++i) {
    const double d = bridge.xy[i].y();
    bridge.z[i] += kWorldDeckRiseM * std::exp(-d * d / (2.0 * 40.0 * 40.0));
  }
  RoadModelBuild built = build_road_model(network, profiles, {}, diagnostics);
  Aabb2 area;
  area.extend(Vec2(-250, -250));
  area.extend(Vec2(250, 250));
  DemSampler dem(
      {write_local_dem("scene_bridge_world", 300.0, 5.0, [](double, double) { return kWorldGroundM; })},
      network.frame, area);
  return BridgeWorld{std::move(network), std::move(built), std::move(dem)};
}

}  // namespace relief::test
