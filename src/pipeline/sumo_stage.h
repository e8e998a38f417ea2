#pragma once
// The SUMO part of `build`: plain network from the road model, netconvert, checks against the
// OpenDRIVE surface, optional demand.

#include <filesystem>
#include <future>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "pipeline/stages.h"
#include "relief/core/atomic_file.h"
#include "relief/core/scratch_dir.h"
#include "relief/export/report_writer.h"
#include "relief/export/sumo_net_build.h"
#include "relief/roads/road_model.h"

namespace relief {

struct SumoStageInput {
  const BuildOptions& options;
  const LoadedNetwork& loaded;
  const RoadModel& model;
  const std::string& name;
  Diagnostics& diagnostics;
  std::size_t signals_mid_road = 0;  ///< OSM signals controlling no junction (signalled_junctions)
  /// Per model road, its grade cap (SumoOptions::grade_caps): the net's height steps are judged
  /// against it.
  std::vector<double> grade_caps;
};

/// What the SUMO thread makes (export/sumo_net_build.h), with its diagnostics (every one) kept
/// for the caller.
struct NetconvertResult {
  SumoNetBuild net;
  Diagnostics diagnostics{std::numeric_limits<std::size_t>::max()};
};

/// The SUMO stage under way.
struct SumoJob {
  SumoSummary summary;
  std::unique_ptr<ScratchDir> scratch;
  std::future<NetconvertResult> netconvert;
};

/// Starts the SUMO thread: the plain network from `in.model`, netconvert on it and the check of
/// the .net.xml it writes (`in`'s options, network and model must outlive the job).
[[nodiscard]] SumoJob start_sumo(const SumoStageInput& in);

/// Waits for netconvert, then writes NAME.net.xml, NAME.{nod,edg,con}.xml,
/// NAME.sumo_mapping.json (and NAME.rou.xml, NAME.sumocfg when options.demand.trips > 0) into
/// `files`, checks the net and returns the summary; appends the paths / names written.
/// Rethrows what netconvert's run threw.
[[nodiscard]] SumoSummary finish_sumo(const SumoStageInput& in, SumoJob& job, OutputSet& files,
                                      StageTimer& timer, std::vector<std::filesystem::path>& written,
                                      std::vector<std::string>& names);

/// OpenDRIVE junction ids of `model` that get a traffic light: intersections tagged with a
/// signal, and those within `snap_m` along a road of a signal node inside that road (OSM maps
/// many signals on the stop line rather than the junction node). `mid_road` counts the others.
[[nodiscard]] std::set<int> signalled_junctions(const LoadedNetwork& loaded, const RoadModel& model,
                                                double snap_m, std::size_t& mid_road);

}  // namespace relief
