#pragma once
// One region's RoadModel from its tiles' models: each tile keeps what it owns (a road whose
// midpoint, a junction whose centre lies in its core, with the junction's connecting roads), ids
// renumbered, and every link re-pointed at the owner's copy of its target, found by position
// (a road by its end at the contact, a junction by its centre).

#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "relief/geometry/types.h"
#include "relief/roads/road_model.h"

namespace relief::detail {

struct TileModel {
  int x = 0, y = 0;
  Aabb2 core;
  RoadModel model;
};

struct ModelMergeResult {
  RoadModel model;
  std::size_t links_unresolved = 0;     ///< links whose target no tile owns (dropped)
  std::string first_unresolved;         ///< where, for the message
  std::vector<std::string> unresolved;  ///< every one, where
  /// The tile each merged road came from (its owner), by merged road id.
  std::unordered_map<int, std::pair<int, int>> road_tile;
};

/// Merges the tiles' models (moving their owned roads out). Linear in the roads (hash grids of
/// road ends and junction centres).
[[nodiscard]] ModelMergeResult merge_models(std::vector<TileModel>& tiles);

/// Whether a tile whose core is `core` owns what is decided by point `p` (half-open box).
[[nodiscard]] bool owns(const Aabb2& core, const Vec2& p);
/// The point a road's ownership is decided by: its reference line at half its length.
[[nodiscard]] Vec2 road_anchor(const ModelRoad& road);
/// The point a junction's ownership is decided by: the mean of its connecting roads' midpoints.
[[nodiscard]] Vec2 junction_anchor(const RoadModel& model, const JunctionModel& junction);

}  // namespace relief::detail
