#pragma once
// Real demand on a relief build's SUMO net (issue 16): the traffic counts of count stations
// (traffic_counts.h) reproduced by SUMO's routeSampler.py from candidate routes that
// duarouter made on the grades (grade_routing.h); trips between zones of an OD matrix
// (zones.h) by od2trips, routed on the grades; optionally heavy trucks, routed on their own
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

struct TrafficDemandOptions {
  double begin_s = 0.0;
  double end_s = 3600.0;  ///< the counts are over [begin, end)
  unsigned seed = 42;
  int trucks = 0;             ///< heavy trucks added (random trips, truck-weighted routes)
  double step_s = 0.05;       ///< the configuration's step
  bool grade_routing = true;  ///< duarouter on grade travel times (else on the limits)
};

/// What the demand is made of: traffic counts, turn counts, an OD matrix with its zones, or any of them.
struct TrafficDemandInputs {
  std::filesystem::path counts_csv;     ///< traffic_counts.h
  std::filesystem::path od_csv, zones;  ///< zones.h: both or neither
  std::filesystem::path turns_csv;      ///< turn_counts.h
};

struct TrafficDemand {
  std::size_t count_rows = 0, counted_edges = 0;
  std::size_t turn_rows = 0, counted_turns = 0;  ///< turn counts: rows, and edge pairs they went onto
  std::size_t od_rows = 0, zones = 0, od_trips = 0;
  std::size_t od_truck_trips = 0;      ///< of od_trips, the trucks' (rows of class truck)
  std::vector<std::string> unmatched;  ///< rows no edge took, with why
  std::size_t vehicles = 0, trucks = 0;
  double geh_ok_share = 0.0;  ///< counted edges and turns whose routed count has GEH < 5
  double worst_geh = 0.0;
  std::filesystem::path routes, config;
};

/// Writes in `out_dir` (created): NAME.vtypes.xml, NAME.grade_CLASS.weights.xml; for counts
/// NAME.counts.xml (edge counts) and/or NAME.turns.xml (turn counts) and NAME.counted.rou.xml
/// (routeSampler.py on both at once); for an OD matrix NAME.taz.xml, NAME.od.xml and
/// NAME.od.rou.xml (its truck rows: NAME.od_truck.xml and NAME.od_truck.rou.xml, routed on the
/// trucks' weights); for trucks NAME.trucks.rou.xml; NAME.demand.sumocfg (the net by path) and
/// demand.json. Throws IoError for a missing tool or file, InvalidInput for counts (edge and
/// turn counts together) that fit no edge, a matrix naming a zone the zones do not have or that has no edge.
TrafficDemand make_traffic_demand(const std::filesystem::path& net_path, const TrafficDemandInputs& inputs,
                                  const std::filesystem::path& out_path, const TrafficDemandOptions& options,
                                  Diagnostics& diagnostics);

}  // namespace relief
