#pragma once
// Private to the roads module: an order of a junction's road ends around it that makes its
// outline a simple polygon, for junctions where the order by angle around their centre does not
// (ends reaching past one another in a joined junction, a road end lying across a neighbour's).

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

}  // namespace relief::detail
