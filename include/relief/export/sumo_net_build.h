#pragma once
// The whole SUMO chain on a RoadModel: the plain network (export/sumo_network.h; edge types from
// the roads' OSM highway classes, traffic lights at the junctions OSM signals), netconvert on it
// (export/sumo_tools.h), netconvert's lanes laid onto the model's surface (export/sumo_drape.h)
// and the check of the result against that surface (export/sumo_checks.h). `relief build` runs it
// beside its other outputs; a region merged from tiles runs it on the merged model.

#include <filesystem>
#include <string>

#include "relief/core/diagnostics.h"
#include "relief/export/sumo_checks.h"
#include "relief/export/sumo_drape.h"
#include "relief/export/sumo_network.h"
#include "relief/export/sumo_tools.h"
#include "relief/roads/road_model.h"

namespace relief {

struct SumoNetBuild {
  SumoPlainNetwork plain;
  NetconvertRun run;  ///< run.net_xml: the draped .net.xml text
  SumoDrape drape;
  SumoNetCheck check;
  double build_seconds = 0.0;       ///< the plain network's
  double netconvert_seconds = 0.0;  ///< netconvert's wall time
  double check_seconds = 0.0;       ///< the drape and the check
};

/// Runs the chain on `model` in `work_dir` (which must exist) as `name`. Every junction with
/// traffic_signal set joins options.signalled_junctions. Throws IoError when netconvert is
/// missing or fails, InvalidInput for options out of range.
[[nodiscard]] SumoNetBuild build_sumo_net(const RoadModel& model, SumoOptions options,
                                          const std::filesystem::path& work_dir, const std::string& name,
                                          Diagnostics& diagnostics);

}  // namespace relief
