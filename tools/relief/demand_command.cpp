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
  std::string net, counts, out;
  CountDemandOptions options;
  bool flat_routing = false;
};

}  // namespace

Runner add_demand_command(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "demand",
      "Traffic counts per OSM way on a relief build's SUMO net (routeSampler), routed on the grades");
  auto args = std::make_shared<DemandArgs>();
  cmd->add_option("--net", args->net, "A relief build's NAME.net.xml (NAME.sumo_mapping.json beside it)")
      ->required();
  cmd->add_option("--counts", args->counts,
                  "CSV with the header osm_way,direction,count (direction NB, SB, EB, "
                  "WB, a bearing in degrees, or both)")
      ->required();
  cmd->add_option("--out", args->out,
                  "Output directory (NAME.demand.sumocfg, NAME.counted.rou.xml, demand.json)")
      ->required();
  cmd->add_option("--begin", args->options.begin_s, "Start of the counts' interval, s")
      ->check(finite_non_negative())
      ->capture_default_str();
  cmd->add_option("--end", args->options.end_s, "End of the counts' interval, s")
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
      const CountDemand d = make_count_demand(args->net, args->counts, args->out, args->options, diagnostics);
      std::cout << "demand     " << d.count_rows << " count rows on " << d.counted_edges << " edges ("
                << d.unmatched.size() << " unmatched); " << d.vehicles << " vehicles (" << d.trucks
                << " trucks); GEH < 5 on " << fixed(100.0 * d.geh_ok_share, 1)
                << " % of the counted edges (worst " << fixed(d.worst_geh, 2) << ")\n"
                << "wrote      " << d.config.string() << "\n";
      print_diagnostics_summary(diagnostics);
      return static_cast<int>(kOk);
    });
  };
}

}  // namespace relief::cli
