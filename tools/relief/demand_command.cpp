// `relief demand`: traffic counts per OSM way reproduced on a relief build's SUMO net, routed on
// the grades, with slope-aware emissions switched on.
#include <iostream>
#include <memory>

#include "commands.h"
#include "console.h"
#include "options.h"
#include "relief/demand/demand.h"

namespace relief::cli {
namespace {

struct DemandArgs {
  std::string net, counts, turns, od, zones, out;
  TrafficDemandOptions options;
  bool flat_routing = false;
};

}  // namespace

Runner add_demand_command(CLI::App& app) {
  auto* cmd =
      app.add_subcommand("demand",
                         "Traffic and turn counts per OSM way (routeSampler) and OD matrices (od2trips) on a "
                         "relief build's SUMO net, routed on "
                         "the grades");
  auto args = std::make_shared<DemandArgs>();
  cmd->add_option("--net", args->net, "A relief build's NAME.net.xml (NAME.sumo_mapping.json beside it)")
      ->required();
  cmd->add_option(
      "--counts", args->counts,
      "CSV with the header osm_way,direction,count (direction NB, SB, EB, WB, a bearing in degrees, "
      "or both)");
  cmd->add_option("--turn-counts", args->turns,
                  "CSV with the header from_way,from_direction,to_way,to_direction,count (directions as for "
                  "--counts; both: any)");
  auto* od = cmd->add_option(
      "--od", args->od,
      "OD matrix: CSV with the header origin,destination,count[,class] (zone ids; class car or truck)");
  auto* zones = cmd->add_option("--zones", args->zones,
                                "GeoJSON polygons of the OD matrix's zones (WGS84; property id or name)");
  od->needs(zones);
  zones->needs(od);
  cmd->add_option("--out", args->out,
                  "Output directory (NAME.demand.sumocfg, NAME.counted.rou.xml, demand.json)")
      ->required();
  cmd->add_option("--begin", args->options.begin_s, "Start of the counts' and the matrix's interval, s")
      ->check(finite_non_negative())
      ->capture_default_str();
  cmd->add_option("--end", args->options.end_s, "End of the counts' and the matrix's interval, s")
      ->check(finite_positive())
      ->capture_default_str();
  cmd->add_option("--trucks", args->options.trucks,
                  "Heavy trucks added, routed on their own grade travel times")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd->add_option("--seed", args->options.seed, "Random seed of the candidate routes and the sampling")
      ->capture_default_str();
  cmd->add_flag("--flat-routing", args->flat_routing, "Route on the speed limits, not on the grades");
  return [args] {
    return run_reporting_errors([&] {
      args->options.grade_routing = !args->flat_routing;
      Diagnostics diagnostics;
      print_diagnostics_live(diagnostics, false);
      const TrafficDemandInputs inputs{args->counts, args->od, args->zones, args->turns};
      const TrafficDemand d = make_traffic_demand(args->net, inputs, args->out, args->options, diagnostics);
      if (d.count_rows + d.turn_rows > 0)
        std::cout << "counts     " << d.count_rows << " rows on " << d.counted_edges << " edges, "
                  << d.turn_rows << " turn rows on " << d.counted_turns << " turns (" << d.unmatched.size()
                  << " unmatched); GEH < 5 on " << fixed(100.0 * d.geh_ok_share, 1) << " % of them (worst "
                  << fixed(d.worst_geh, 2) << ")\n";
      if (d.od_rows > 0)
        std::cout << "od         " << d.od_rows << " relations between " << d.zones << " zones, "
                  << d.od_trips << " trips routed\n";
      std::cout << "demand     " << d.vehicles << " vehicles (" << d.trucks << " trucks)\n"
                << "wrote      " << d.config.string() << "\n";
      print_diagnostics_summary(diagnostics);
      return static_cast<int>(kOk);
    });
  };
}

}  // namespace relief::cli
