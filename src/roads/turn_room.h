#pragma once
// Private to the roads module: how tight a turn between two road ends at a junction is. A
// connecting road runs from a lane centre of one end to a lane centre of the other as the
// roundest arc between the two lanes' lines (corner_connector): its radius is the shorter of the
// two tangent lengths over tan(turn / 2). Junctions trim their road ends back until every turn
// is at least min_turn_radius_m round (end_trims.h), the roads' lengths allowing, so that a car's
// body, which SUMO draws as a chord behind its front bumper, stays on the lane it turns along.

#include <numbers>

#include "relief/geometry/types.h"
#include "relief/roads/road_network.h"
#include "roads/junction_ends.h"

namespace relief::detail {

/// A turn under this angle goes through (30 degrees); one over kUTurnAngle_rad is a U-turn (150
/// degrees), which connecting roads leave out unless asked. Shared by the movements
/// (connecting_roads.cpp) and the room their turns need.
inline constexpr double kThroughAngle_rad = std::numbers::pi / 6.0;
inline constexpr double kUTurnAngle_rad = 5.0 * std::numbers::pi / 6.0;

/// The lanes of a road end, across its travel direction into the junction: `arriving` lanes
/// drive into it, `departing` lanes out of it (right-hand traffic: each on the right of its
/// direction of travel), all `lane_width` wide, on a carriageway `width` wide centred on the end.
struct EndLanes {
  int arriving = 0, departing = 0;
  double lane_width = 0.0, width = 0.0;
};

/// The lanes of `road`'s end at its start or its end.
[[nodiscard]] EndLanes end_lanes(const Road& road, bool at_start);

/// The tightest turn from end `a` into end `b`: right turns from the outermost arriving lane into
/// the outermost departing lane, left turns between the innermost ones, as connecting roads pair
/// them without turn lanes.
struct TurnRoom {
  double radius = 0.0;  ///< m, of the lane centre's arc; infinity where no turn needs room
  /// Which end must be trimmed back for a rounder turn: the one with the shorter tangent (0 = a).
  int shorter = 0;
};

/// The room of the turn from `a` into `b`. No turn needs room (radius infinity) where no lane
/// arrives at `a` or departs from `b`, or where the turn is under 30 degrees (a through movement)
/// or over 150 (a U-turn, which connecting roads leave out). A turn whose lanes' lines cross
/// behind an end has radius 0 and that end is the shorter.
[[nodiscard]] TurnRoom turn_room(const EndShape& a, const EndLanes& la, const EndShape& b,
                                 const EndLanes& lb);

}  // namespace relief::detail
