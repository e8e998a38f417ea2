#pragma once
// Private to the roads module: the OpenDRIVE junction of an intersection (or of intersections
// joined into one). Every allowed movement from an arriving road end to a departing one gets a
// connecting road per lane pair (`turn:lanes` where tagged, else through lanes paired from the
// outside in and one lane per turn): its reference line runs along the lane's centre as the
// roundest arc the corner allows, its elevation is the cubic with the arriving lane's height and
// slope at its start and the departing lane's at its end, its roll lays it on the junction's plane.

#include <vector>

#include "relief/core/diagnostics.h"
#include "relief/geometry/types.h"
#include "relief/roads/road_model.h"
#include "relief/roads/road_model_builder.h"
#include "relief/roads/road_network.h"
#include "roads/junction_clusters.h"

namespace relief::detail {

/// A road end at a junction, as the model sees it.
struct EndRef {
  int network_road = -1;
  bool at_start = true;
};

/// The network junction a road end touches (a joined junction holds several).
[[nodiscard]] int junction_of(const RoadNetwork& network, const EndRef& e);

/// Adds the junction of intersection `j` (a cluster's representative in `clusters`) to
/// out.model: links its road ends (`ends`, those with a model road) to it and adds a connecting
/// road for every movement and lane pair.
/// Where no movement is possible (every road leads away, or the turn lanes allow none) the roads
/// end there instead (codes::kOpendriveJunctionWithoutMovements) and no junction is added.
void add_junction(const RoadNetwork& network, const JunctionClusters& clusters, const Junction& j,
                  const std::vector<EndRef>& ends, const RoadModelOptions& options, RoadModelBuild& out,
                  Diagnostics& diagnostics);

}  // namespace relief::detail
