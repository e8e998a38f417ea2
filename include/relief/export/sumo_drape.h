#pragma once
// The lanes of a .net.xml laid onto the OpenDRIVE surface they came from. netconvert cuts lanes
// at the junction outlines it computes and interpolates their heights linearly between the
// shape points it keeps (in a large joined junction, from a point metres inside it), so a lane
// end can lie decimetres off the road surface (0.88 m on Liechtenstein). Every point of every
// lane (internal lanes included) that maps to an OpenDRIVE road (sumo_checks.h: through the
// net's params, else the model's junction connections) takes the surface height at its (x, y)
// on that road; x and y are kept as netconvert wrote them. Before that, an internal lane whose
// end lies away from its lane's (netconvert cut the lane where its outline reaches over the
// road) is extended along the OpenDRIVE lane to meet it, and one whose end lies beside or behind
// its lane's end is cut there (sumo_seams.h). Where the chord between two points leaves the
// surface by more than 0.01 m (a crest or a sag between them), points go in between (on the
// OpenDRIVE lane centre; on netconvert's own curves, on the chord), so that a vehicle between
// them is on the surface too.

#include <cstddef>
#include <string>

#include "relief/roads/road_model.h"

namespace relief {

struct SumoDrape {
  std::size_t points = 0;           ///< lane shape points given the surface height
  std::size_t points_moved = 0;     ///< of those, points moved by more than 1 mm
  std::size_t points_unmapped = 0;  ///< points whose OpenDRIVE road is unknown (left as they are)
  /// Points put in between two where their chord leaves the surface by more than 0.01 m (SUMO
  /// interpolates heights linearly between shape points), by bisection down to 1 m apart.
  std::size_t points_added = 0;
  /// Points whose height changed when the final shape was located again point by point, each
  /// from the one before it (inserted points included), as the checks read it: a road lying over
  /// itself in plan, where the first pass, locating from the original point before, chose another
  /// part of it.
  std::size_t points_reheighted = 0;
  double max_move_m = 0.0;         ///< largest height change
  std::string max_move_lane;       ///< the lane of that change
  std::size_t ends_extended = 0;   ///< internal lane ends extended to a lane netconvert cut short
  double max_extension_m = 0.0;    ///< longest such extension (plan length)
  std::string max_extension_lane;  ///< the internal lane of that extension
  std::size_t ends_snapped = 0;    ///< internal lane ends moved onto a lane end beside or behind
  double max_snap_m = 0.0;         ///< farthest such move (plan)
  std::string max_snap_lane;       ///< the internal lane of that move
};

/// Rewrites the z of every mapped lane shape point of `net_xml` (a .net.xml, named `file` in
/// errors) with the surface of `model`, 3 decimals as SUMO writes them. Throws InvalidInput when
/// `net_xml` is not a SUMO network.
[[nodiscard]] SumoDrape drape_sumo_net(std::string& net_xml, const RoadModel& model, const std::string& file);

}  // namespace relief
