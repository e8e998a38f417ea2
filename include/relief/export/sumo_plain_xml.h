#pragma once
// SUMO's plain XML files of a SumoPlainNetwork (export/sumo_network.h), the input of netconvert
// (--node-files / --edge-files / --connection-files). Shapes are written at millimetres, the
// files indented by four and ' escaped as &#39;, as SUMO writes its own.

#include <ostream>

#include "relief/export/sumo_network.h"

namespace relief {

/// The node file, with the <location> (netOffset = -origin, convBoundary in the local frame,
/// origBoundary in lon/lat, projParameter = the frame's CRS). Throws ProjectionError when the
/// frame's CRS has no transformation to WGS84.
void write_sumo_nodes(std::ostream& out, const SumoPlainNetwork& net);
/// The edge file: every edge with its lanes (custom shapes, widths, disallowed classes) and the
/// params odr.road, odr.lane and max_grade_percent.
void write_sumo_edges(std::ostream& out, const SumoPlainNetwork& net);
/// The connection file: lane to lane, with the internal lane's shape and its OpenDRIVE
/// connecting road and lane as params where it has one.
void write_sumo_connections(std::ostream& out, const SumoPlainNetwork& net);

}  // namespace relief
