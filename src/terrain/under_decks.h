#pragma once
// Private to src/terrain: keeps the finished TIN under bridge decks. A fill or cut slope beside
// a deck, or the DEM between its 30 m samples, may otherwise rise through the deck.

#include <cstddef>
#include <vector>

#include "relief/geometry/triangle_mesh.h"
#include "terrain/terrain_cdt.h"

namespace relief::terrain_detail {

struct UnderDecks {
  std::size_t edges_constrained = 0;  ///< deck outline edges inserted as constraints
  std::size_t edges_skipped = 0;      ///< touching the road outline or the paved area: left out
  std::size_t vertices_lowered =
      0;  ///< terrain vertices put (or moved) below the terrain's height under a deck
};

/// Inserts the outline of the decks (road triangles off the ground) into the finished `tin` as
/// constraints, where an outline edge neither touches the road outline nor lies in the paved
/// area, its ends at the terrain's height or `clearance_m` under the deck, whichever is lower;
/// then lowers every terrain vertex under a deck (not a road-outline vertex) to `clearance_m`
/// under it. A terrain face inside a constrained deck outline then lies below the deck.
UnderDecks keep_under_decks(Tin& tin, const TriangleMesh& decks, const std::vector<Polyline3>& outline,
                            double clearance_m);

}  // namespace relief::terrain_detail
