#pragma once
// Private to the tiles module: the heights a tile fitted where its neighbours meet what it owns,
// which tiles built after it hold (ProfileFitOptions::holds), so that both build the same
// surface there whatever else their windows see.

#include <cstdint>
#include <filesystem>
#include <map>
#include <tuple>
#include <vector>

#include "relief/geometry/types.h"
#include "relief/roads/profile_fit.h"
#include "relief/roads/road_model.h"
#include "relief/roads/road_network.h"

namespace relief::detail {

/// A network road by its OSM nodes (first, second, second to last, last): the same in every
/// window that splits its ways alike (osm_window.h).
struct RoadKey {
  std::int64_t first = 0, second = 0, penultimate = 0, last = 0;
  [[nodiscard]] bool operator<(const RoadKey& o) const {
    return std::tie(first, second, penultimate, last) < std::tie(o.first, o.second, o.penultimate, o.last);
  }
};
[[nodiscard]] RoadKey road_key(const Road& road);

struct TileHolds {
  std::map<RoadKey, std::vector<double>> road_z;   ///< per sample, NaN where not held
  std::map<std::int64_t, Vec2> junction_gradient;  ///< by the network junction's OSM node
};

/// Samples of a road held on each side of a junction a tile owns: beyond its end trims and the
/// reach of the curvature rows, so that the connecting roads and the road's end come out alike.
constexpr double kJunctionHoldReachM = 150.0;

/// What a tile owning `core` fitted that its neighbours must build alike where their elements
/// meet its own: at every junction it owns (junction_anchor in the core, xodr_merge.h, or the
/// anchor of the transition road it keeps at an attribute change) or one of
/// the roads it owns (road_anchor in the core) ends at, the junction's plane and the stations
/// within kJunctionHoldReachM of it (and short of the road's middle) of each road there that it
/// owns, or of every road there when it owns the junction. Only there: the rest of a road is the
/// owner's copy in the merge, and holding it whole would pin a neighbour's fit to what a window
/// saw far from its core.
[[nodiscard]] TileHolds tile_holds(const RoadNetwork& network, const ProfileFitResult& fit,
                                   const RoadModel& model, const Aabb2& core);

/// Adds `from`'s values where `into` has none.
void add_holds(TileHolds& into, const TileHolds& from);

/// The holds by this network's roads and junctions; `mismatched` counts held roads whose sample
/// count differs here (left free).
[[nodiscard]] FitHolds index_holds(const RoadNetwork& network, const std::vector<RoadProfile>& raw,
                                   const TileHolds& holds, std::size_t& mismatched);

void write_holds(const std::filesystem::path& path, const TileHolds& holds);
/// Throws InvalidInput for a file that is not one write_holds wrote.
[[nodiscard]] TileHolds read_holds(const std::filesystem::path& path);

}  // namespace relief::detail
