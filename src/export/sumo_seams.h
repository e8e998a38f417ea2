#pragma once
// Private to the export module: closing the hand-overs netconvert leaves open. netconvert cuts
// a lane where it enters the junction outline; where the outline reaches over a road's first
// metres (a road drawn closer to a joined junction's other roads than its width, measured: 56 m
// on Liechtenstein, 51 m in Portland) the lane ends there while the internal lane that relief
// gave it starts at the road's end. The internal lane is extended along the OpenDRIVE lane over
// the part netconvert cut, so that every vehicle path is continuous and on the surface.

#include <pugixml.hpp>

#include <cstddef>
#include <string>

#include "export/sumo_lane_locator.h"

namespace relief::detail {

struct SumoSeams {
  std::size_t extended = 0;      ///< internal lane ends extended along a lane netconvert cut short
  double max_extension_m = 0.0;  ///< longest extension (plan length)
  std::string max_extension_lane;
  std::size_t snapped = 0;  ///< internal lane ends moved onto a lane end beside or behind them
  double max_snap_m = 0.0;  ///< farthest such move (plan)
  std::string max_snap_lane;
};

/// For every hand-over between a lane and an internal lane (either way) whose ends lie more than
/// `tolerance_m` apart in plan: where the lane stops short of the internal lane on its OpenDRIVE
/// lane, the internal lane is extended along that lane's centre (points every metre, simplified
/// within 1 cm) up to the lane's end point; otherwise (side by side, netconvert offsetting lanes
/// by a few centimetres, or the lane reaching past) the internal lane is cut at its point nearest
/// the lane's end and ends there. Its `length` changes by its shape's change in plan length.
/// Heights of new points come from the surface; the drape sets them again afterwards. The 5 cm
/// default leaves netconvert's own centimetres alone (it offsets lanes from the edge's shape and
/// rounds to 1 cm: 1.5 cm off the OpenDRIVE lane centre on Potrero).
SumoSeams close_handover_gaps(pugi::xml_node net, LaneLocator& locator, double tolerance_m = 0.05);

}  // namespace relief::detail
