#pragma once
// The sight-distance part of `build` (output `sight`): every lane's sight distance on the
// built scene (relief/sight/sight_distance.h), NAME.sight.geojson and report.json's summary.

#include <filesystem>
#include <string>
#include <vector>

#include "pipeline/stages.h"
#include "relief/core/atomic_file.h"
#include "relief/export/sight_writer.h"
#include "relief/pipeline/build.h"

namespace relief {

struct SightStageInput {
  const BuildOptions& options;
  const RoadNetwork& network;
  const RoadModel& model;
  const MeshScene& scene;
  const std::string& name;
};

/// The sight distances (the roads' classes from the network: OSM highway values; connecting
/// roads "junction").
[[nodiscard]] SightResult compute_sight(const SightStageInput& in);

/// Writes NAME.sight.geojson into `files` and returns the summary for report.json; appends the
/// path written and its name.
[[nodiscard]] SightSummary write_sight_outputs(const SightStageInput& in, const SightResult& result,
                                               double seconds, OutputSet& files,
                                               std::vector<std::filesystem::path>& written,
                                               std::vector<std::string>& names);

}  // namespace relief
