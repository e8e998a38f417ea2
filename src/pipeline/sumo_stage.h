#pragma once
// The SUMO part of `build`: plain network from the road model, netconvert, checks against the
// OpenDRIVE surface, optional demand.

#include <filesystem>
#include <string>
#include <vector>

#include "pipeline/stages.h"
#include "relief/core/atomic_file.h"
#include "relief/export/report_writer.h"
#include "relief/roads/road_model.h"

namespace relief {

struct SumoStageInput {
  const BuildOptions& options;
  const LoadedNetwork& loaded;
  const RoadModel& model;
  const std::string& name;
  Diagnostics& diagnostics;
};

/// Writes NAME.net.xml, NAME.{nod,edg,con}.xml, NAME.sumo_mapping.json (and NAME.rou.xml,
/// NAME.sumocfg when options.demand.trips > 0) into `files`; appends their paths / names.
[[nodiscard]] SumoSummary write_sumo_outputs(const SumoStageInput& in, OutputSet& files, StageTimer& timer,
                                             std::vector<std::filesystem::path>& written,
                                             std::vector<std::string>& names);

/// OpenDRIVE junction ids of `model` that get a traffic light: intersections tagged with a
/// signal, and those within `snap_m` along a road of a signal node inside that road (OSM maps
/// many signals on the stop line rather than the junction node). `mid_road` counts the others.
[[nodiscard]] std::set<int> signalled_junctions(const LoadedNetwork& loaded, const RoadModel& model,
                                                double snap_m, std::size_t& mid_road);

}  // namespace relief
