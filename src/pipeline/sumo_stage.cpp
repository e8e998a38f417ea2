#include "pipeline/sumo_stage.h"

#include <chrono>
#include <cmath>
#include <fstream>
#include <sstream>

#include "relief/core/diagnostic_codes.h"
#include "relief/core/errors.h"
#include "relief/export/sumo_checks.h"
#include "relief/export/sumo_drape.h"
#include "relief/export/sumo_mapping.h"
#include "relief/export/sumo_plain_xml.h"
#include "relief/geometry/polyline.h"

namespace relief {
namespace {}  // namespace

std::set<int> signalled_junctions(const LoadedNetwork& loaded, const RoadModel& model, double snap_m,
                                  std::size_t& mid_road) {
  const RoadNetwork& network = loaded.network;
  std::vector<int> odr_junction(network.junctions.size(), -1);
  for (const JunctionModel& j : model.junctions) {
    for (const int source : j.source_junctions) {
      if (source >= 0 && static_cast<std::size_t>(source) < odr_junction.size())
        odr_junction[static_cast<std::size_t>(source)] = j.id;
    }
  }
  std::set<int> out;
  for (std::size_t i = 0; i < network.junctions.size(); ++i) {
    if (network.junctions[i].traffic_signal && odr_junction[i] >= 0) out.insert(odr_junction[i]);
  }
  mid_road = 0;
  for (const Road& road : network.roads) {
    if (road.points.size() < 3) continue;
    const std::vector<double> along = cumulative_length(road.points);
    for (std::size_t k = 1; k + 1 < road.points.size(); ++k) {
      if (!loaded.osm.traffic_signals.contains(road.osm_node_ids[k])) continue;
      const double to_start = along[k], to_end = along.back() - along[k];
      const int junction = to_start <= to_end ? road.start_junction : road.end_junction;
      const int odr = junction >= 0 ? odr_junction[static_cast<std::size_t>(junction)] : -1;
      if (std::min(to_start, to_end) <= snap_m && odr >= 0) {
        out.insert(odr);
      } else {
        ++mid_road;
      }
    }
  }
  return out;
}

SumoJob start_sumo(const SumoStageInput& in) {
  SumoJob job;
  job.summary.file = in.name + ".net.xml";
  job.summary.max_grade_percent = in.options.sumo.max_grade_percent;
  // The plain network, netconvert (another process) and the check of its net run on their own
  // thread, beside the meshes; diagnostics are kept there and reported in finish_sumo.
  job.scratch = std::make_unique<ScratchDir>(in.options.out_dir);
  // Each road's grade cap, for the check's height steps (a footway's 100 % is no street's).
  SumoOptions sumo = in.options.sumo;
  sumo.grade_caps = in.grade_caps;
  job.netconvert = std::async(std::launch::async, [sumo = std::move(sumo), &model = in.model,
                                                   dir = job.scratch->path(), name = in.name] {
    NetconvertResult r;
    r.net = build_sumo_net(model, sumo, dir, name, r.diagnostics);
    return r;
  });
  return job;
}

SumoSummary finish_sumo(const SumoStageInput& in, SumoJob& job, OutputSet& files, StageTimer& timer,
                        std::vector<std::filesystem::path>& written, std::vector<std::string>& names) {
  const BuildOptions& options = in.options;
  SumoSummary& summary = job.summary;
  const ScratchDir& scratch = *job.scratch;
  const auto t_wait = std::chrono::steady_clock::now();
  const NetconvertResult result = job.netconvert.get();
  for (const Diagnostic& d : result.diagnostics.kept()) in.diagnostics.report(d);
  const SumoPlainNetwork& plain = result.net.plain;
  summary.signals_mid_road = in.signals_mid_road;
  summary.nodes = plain.stats.nodes;
  summary.edges = plain.stats.edges;
  summary.connections = plain.stats.connections;
  summary.restricted_edges = plain.stats.restricted_edges;
  summary.internal_lanes_by_netconvert = plain.stats.internal_lanes_by_netconvert;
  summary.max_profile_grade_percent = plain.stats.max_edge_grade_percent;
  const NetconvertRun& nc = result.net.run;
  timer.add("build SUMO network (beside the meshes)", result.net.build_seconds);
  timer.add("netconvert (beside the meshes)", result.net.netconvert_seconds);
  timer.add("drape and check SUMO network (after netconvert, beside the meshes)", result.net.check_seconds);
  timer.add("wait for netconvert",
            std::chrono::duration<double>(std::chrono::steady_clock::now() - t_wait).count());
  summary.netconvert_warnings = nc.warnings;

  const auto add = [&](const std::string& file, const std::string& text) {
    files.add(options.out_dir / file, [&](std::ostream& out) { out << text; });
    written.push_back(options.out_dir / file);
    names.push_back(file);
  };
  const auto add_with = [&](const std::string& file, auto&& write) {
    std::ostringstream text;
    write(text, plain);
    add(file, text.str());
  };
  add(in.name + ".net.xml", nc.net_xml);
  add_with(in.name + ".nod.xml", write_sumo_nodes);
  add_with(in.name + ".edg.xml", write_sumo_edges);
  add_with(in.name + ".con.xml", write_sumo_connections);
  add_with(in.name + ".sumo_mapping.json", write_sumo_mapping);

  {
    const SumoNetCheck& check = result.net.check;
    summary.junctions = check.junctions;
    summary.traffic_lights = check.traffic_lights;
    summary.lanes = check.lanes;
    summary.internal_lanes = check.internal_lanes;
    summary.points_checked = check.points;
    summary.z_max_m = check.z_max_m;
    summary.z_p99_m = check.z_p99_m;
    summary.z_max_lane = check.z_max_lane;
    summary.netconvert_lanes_z_max_m = check.netconvert_shape_z_max_m;
    summary.draped_points_moved = result.net.drape.points_moved;
    summary.drape_max_move_m = result.net.drape.max_move_m;
    summary.drape_max_move_lane = result.net.drape.max_move_lane;
    summary.draped_points_added = result.net.drape.points_added;
    summary.handover_ends_extended = result.net.drape.ends_extended;
    summary.handover_max_extension_m = result.net.drape.max_extension_m;
    summary.handover_max_extension_lane = result.net.drape.max_extension_lane;
    summary.handover_ends_snapped = result.net.drape.ends_snapped;
    summary.handover_max_snap_m = result.net.drape.max_snap_m;
    summary.handover_max_snap_lane = result.net.drape.max_snap_lane;
    summary.xy_max_m = check.xy_max_m;
    summary.xy_max_lane = check.xy_max_lane;
    summary.max_handover_step_m = check.max_handover_step_m;
    summary.max_handover_gap_m = check.max_handover_gap_m;
    summary.handover_gap_lanes = check.handover_gap_lanes;
    summary.handover_gap_point = check.handover_gap_point;
    summary.lanes_without_z = check.lanes_without_z;
    summary.height_steps = check.height_steps;
    summary.first_step_lane = check.first_step_lane;
    summary.first_step_point = check.first_step_point;
    summary.max_lane_grade_percent = check.max_lane_grade_percent;
    summary.max_internal_lane_grade_percent = check.max_internal_lane_grade_percent;
    if (check.points_unmapped > 0) {
      in.diagnostics.report(
          Severity::warning, codes::kSumoUnmappedLanePoints,
          std::to_string(check.points_unmapped) + " SUMO lane points have no OpenDRIVE road");
    }
  }

  if (options.demand.trips > 0) {
    const DemandRun demand =
        timer.run("SUMO demand", [&] { return make_demand(scratch.path(), in.name, options.demand); });
    add(in.name + ".rou.xml", demand.routes_xml);
    add(in.name + ".sumocfg", demand.sumocfg);
    summary.routes = demand.routes;
    summary.step_length_s = options.demand.step_length_s;
  }
  return summary;
}

}  // namespace relief
