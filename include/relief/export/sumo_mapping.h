#pragma once
// sumo_mapping.json: every SUMO lane of a SumoPlainNetwork (edge lanes "EDGE_INDEX", internal
// lanes by their from and to lanes) with its OpenDRIVE road and lane and the OSM ways its road was
// built from, and the frame, so that a co-simulation can translate vehicles between SUMO and the
// OpenDRIVE file and traffic counts given per OSM way find their edges (demand/traffic_counts.h).

#include <ostream>

#include "relief/export/sumo_network.h"

namespace relief {

/// Writes the mapping of `net` as JSON.
void write_sumo_mapping(std::ostream& out, const SumoPlainNetwork& net);

}  // namespace relief
