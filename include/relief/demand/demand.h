#pragma once
// Real demand on a relief build's SUMO net (issue 16): the traffic counts of count stations
// (traffic_counts.h) reproduced by SUMO's routeSampler.py from candidate routes that
// duarouter made on the grades (grade_routing.h); optionally heavy trucks, routed on their own
// grade-aware travel times; and a SUMO configuration with the emission device on every vehicle
// and slope-aware models (PHEMlight for the cars, whose fuel and CO2 follow the grade; SUMO's
// default HBEFA class for the trucks, which has no slope), so that fuel feels the hills.

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "relief/core/diagnostics.h"

namespace relief {

inline constexpr const char* kDemandReportFile = "demand.json";

struct CountDemandOptions {
  double begin_s = 0.0;
  double end_s = 3600.0;  ///< the counts are over [begin, end)
  unsigned seed = 42;
  int trucks = 0;             ///< heavy trucks added (random trips, truck-weighted routes)
  double step_s = 0.05;       ///< the configuration's step
  bool grade_routing = true;  ///< duarouter on grade travel times (else on the limits)
};

struct CountDemand {
  std::size_t count_rows = 0, counted_edges = 0;
  std::vector<std::string> unmatched;  ///< rows no edge took, with why
  std::size_t vehicles = 0, trucks = 0;
  double geh_ok_share = 0.0;  ///< counted edges whose routed count has GEH < 5
  double worst_geh = 0.0;
  std::filesystem::path routes, config;
};

/// Writes in `out_dir` (created): NAME.counts.xml, NAME.grade_CLASS.weights.xml,
/// NAME.demand.rou.xml (types and routes), NAME.demand.sumocfg (the net by path) and demand.json.
/// Throws IoError for a missing tool or file, InvalidInput for counts that fit no edge.
CountDemand make_count_demand(const std::filesystem::path& net_path, const std::filesystem::path& counts_csv,
                              const std::filesystem::path& out_path, const CountDemandOptions& options,
                              Diagnostics& diagnostics);

}  // namespace relief
