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
#include "relief/export/report_writer.h"
#include "relief/export/sumo_checks.h"
#include "relief/export/sumo_drape.h"
#include "relief/export/sumo_tools.h"
#include "relief/roads/road_model.h"

namespace relief {

struct SumoStageInput {
  const BuildOptions& options;
  const LoadedNetwork& loaded;
  const RoadModel& model;
  const std::string& name;
  Diagnostics& diagnostics;
};

/// A scratch directory beside the outputs (netconvert and randomTrips need files), removed
/// when it goes out of scope.
class ScratchDir {
 public:
  explicit ScratchDir(const std::filesystem::path& parent);
  ~ScratchDir();
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  [[nodiscard]] const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

/// What the SUMO thread makes: the plain network, netconvert's run on it, then the check of
/// its .net.xml; the diagnostics of the plain network are kept here (every one) for the caller.
struct NetconvertResult {
  std::shared_ptr<const SumoPlainNetwork> plain;
  Diagnostics diagnostics{std::numeric_limits<std::size_t>::max()};
  std::size_t signals_mid_road = 0;
  double build_seconds = 0.0;  ///< the plain network's
  NetconvertRun run;
  double seconds = 0.0;  ///< netconvert's wall time
  SumoDrape drape;  ///< netconvert's lanes laid onto the OpenDRIVE surface
  SumoNetCheck check;
  double check_seconds = 0.0;
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
