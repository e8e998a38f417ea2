#pragma once
// Private to relief: an order of a junction's road ends around it that makes its outline a simple
// polygon, for the junction surface of the scene and the node outlines given to netconvert.

#include <cstddef>
#include <optional>
#include <vector>

#include "relief/geometry/types.h"

namespace relief::detail {

/// The cyclic order of the chains (each a road end's cross-section from its right corner to its
/// left) that, joined by straight gaps from each chain's last point to the next one's first,
/// makes a simple counter-clockwise polygon, with the least total gap length among the orders
/// tried; chain 0 comes first. A depth-first search that drops a partial order as soon as one
/// of its edges touches an earlier one (or its gaps are already longer than the best) and stops
/// after `budget` partial orders. Nothing when no order is found.
[[nodiscard]] std::optional<std::vector<std::size_t>> simple_outline_order(
    const std::vector<Polyline2>& chains, std::size_t budget = 100000);

/// Whether the chains in `order` (a cyclic order of some of them), joined by straight gaps, make a
/// simple counter-clockwise polygon.
[[nodiscard]] bool is_simple_outline(const std::vector<Polyline2>& chains,
                                     const std::vector<std::size_t>& order);

/// A road end at a junction, in plan: the corners of its cross-section, right then left looking
/// out of the junction along the road, and that direction (a unit vector).
struct PlanEnd {
  Vec2 right, left, out;
};

/// The counter-clockwise order of a junction's road ends: by the angle, around the centroid of
/// their midpoints, of a point ahead of each end along its road as far as the farthest midpoint
/// lies from the centroid. An end lying at the centre then sorts by its road's direction (its
/// midpoint's own angle is noise there) and ends far apart by where they are. When the outline
/// of that order (each end's corners right to left, straight gaps) is not simple, the order of
/// simple_outline_order if it finds one; else the sorted order.
[[nodiscard]] std::vector<std::size_t> junction_end_order(const std::vector<PlanEnd>& ends);

}  // namespace relief::detail
