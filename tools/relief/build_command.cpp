// `relief build`: parse, call relief::build, print the summary.
#include <iostream>
#include <memory>
#include <sstream>

#include "commands.h"
#include "console.h"
#include "options.h"
#include "relief/pipeline/build.h"

namespace relief::cli {
namespace {

struct BuildArgs {
  InputArgs input;
  std::string out_dir;
  std::string name;
  std::vector<std::string> reference_dems;
  std::string reference_dem_unit;
  std::string nodata_fill = "interpolate";
  bool allow_partial = false;
  std::string grade_limits;
  std::string outputs = "all";
  bool quiet = false;
};

void print_summary(const BuildResult& result) {
  const RunReport& r = result.report;
  const NetworkStats& n = r.network;
  std::ostringstream out;
  out << "relief build: " << r.name << "\n"
      << "  network    " << n.roads << " roads, " << n.junctions << " junctions (" << n.intersections
      << " intersections, " << n.attribute_changes << " attribute changes), " << n.dead_ends
      << " dead ends, " << n.roundabouts << " roundabouts, " << n.traffic_signals << " signals, "
      << fixed(n.length_km, 2) << " km\n"
      << "  structures " << n.bridges << " bridges (" << fixed(n.bridge_km, 2) << " km), " << n.tunnels
      << " tunnels (" << fixed(n.tunnel_km, 2) << " km)\n"
      << "  elevation  " << r.samples << " samples every " << fixed(r.spacing_m, 2) << " m, "
      << to_string(r.interpolation) << "; " << r.void_samples << " in DEM voids, " << r.uncovered_samples
      << " uncovered\n"
      << "  vs DEM     MAE " << fixed(r.heights.vs_dem.mae_m, 3) << " m, RMSE " << fixed(r.heights.vs_dem.rmse_m, 3)
      << " m, max " << fixed(r.heights.vs_dem.max_m, 3) << " m (n = " << r.heights.vs_dem.n << ")\n";
  if (r.heights.vs_reference) {
    const ErrorStats& e = *r.heights.vs_reference;
    out << "  vs ref DEM MAE " << fixed(e.mae_m, 3) << " m, RMSE " << fixed(e.rmse_m, 3) << " m, max "
        << fixed(e.max_m, 3) << " m, bias " << fixed(e.bias_m, 3) << " m (n = " << e.n << ")\n";
  }
  out << "  gradient   max " << fixed(r.gradient.max_percent, 1) << " %, p99 " << fixed(r.gradient.p99_percent, 1)
      << " %, compliance with class limits " << fixed(r.gradient.compliance_percent, 1) << " %\n"
      << "  junctions  max elevation gap " << fixed(r.junctions.max_gap_m, 3) << " m (" << r.junctions.over_bound
      << " over " << fixed(r.junctions.bound_m, 2) << " m)\n";
  double total = 0.0;
  for (const auto& [stage, s] : r.timings_s) total += s;
  out << "  time       " << fixed(total, 3) << " s\n";
  for (const auto& path : result.written) out << "  wrote      " << path.string() << "\n";
  std::cout << out.str();
}

}  // namespace

Runner add_build_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("build", "Build the 3D road network from OSM and DEM(s) and write its outputs");
  auto args = std::make_shared<BuildArgs>();
  args->input.add_to(*cmd);
  cmd->add_option("--out", args->out_dir, "output directory (created if missing)")->required();
  cmd->add_option("--name", args->name, "base name of the outputs (default: the OSM file's stem)");
  cmd->add_option("--reference-dem", args->reference_dems,
                  "independent DEM(s) to validate the road heights against (e.g. a finer one)");
  cmd->add_option("--reference-dem-unit", args->reference_dem_unit, "vertical unit of the reference DEM(s): m, ft, us-ft");
  cmd->add_option("--nodata-fill", args->nodata_fill,
                  "DEM voids under roads: interpolate (along the road, reported) or error")
      ->capture_default_str();
  cmd->add_flag("--allow-partial", args->allow_partial, "accept roads partly outside the DEM(s) (filled, reported)");
  cmd->add_option("--grade-limits", args->grade_limits,
                  "override grade limits, e.g. highway=8,arterial=12,local=15,residential=18 (percent)");
  cmd->add_option("--outputs", args->outputs, "comma-separated outputs to write: geojson, report, or all")
      ->capture_default_str();
  cmd->add_flag("-q,--quiet", args->quiet, "print only errors and the summary");

  return [args] {
    return run_reporting_errors([&] {
      BuildOptions options;
      args->input.apply_to(options);
      options.out_dir = args->out_dir;
      options.name = args->name;
      options.reference_dem_paths = args->reference_dems;
      if (!args->reference_dem_unit.empty()) {
        options.reference_dem.unit = parse_vertical_unit(args->reference_dem_unit);
        if (!options.reference_dem.unit) {
          throw CLI::ValidationError("--reference-dem-unit", "'" + args->reference_dem_unit + "' is not one of m, ft, us-ft");
        }
      }
      const auto fill = parse_nodata_fill(args->nodata_fill);
      if (!fill) throw CLI::ValidationError("--nodata-fill", "'" + args->nodata_fill + "' is not interpolate or error");
      options.sampling.nodata_fill = *fill;
      options.sampling.allow_partial = args->allow_partial;
      if (!args->grade_limits.empty()) options.grade_limits.apply_overrides(args->grade_limits);
      if (args->outputs != "all") {
        options.outputs.clear();
        std::stringstream in(args->outputs);
        std::string item;
        while (std::getline(in, item, ',')) {
          const auto output = parse_output(item);
          if (!output) throw CLI::ValidationError("--outputs", "'" + item + "' is not one of geojson, report, all");
          options.outputs.insert(*output);
        }
      }
      Diagnostics diagnostics;
      print_diagnostics_live(diagnostics, args->quiet);
      const BuildResult result = build(options, diagnostics, stderr_progress(args->quiet));
      if (!args->quiet) print_diagnostics_summary(diagnostics);
      print_summary(result);
      return static_cast<int>(kOk);
    });
  };
}

}  // namespace relief::cli
