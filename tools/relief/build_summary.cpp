#include "build_summary.h"

#include <algorithm>
#include <filesystem>
#include <iomanip>
#include <map>
#include <sstream>

#include "console.h"

namespace relief::cli {
namespace {

// The quality gates, failed ones first and loud; the rest on one line.
void print_gates(std::ostream& out, const RunReport& r) {
  const std::vector<Gate> failed = failed_gates(r.gates);
  for (const Gate& g : failed) {
    out << "  GATE FAILED " << g.name << ": " << g.value << " (threshold " << g.threshold << ")"
        << (g.where.empty() ? "" : ", " + g.where) << "\n";
  }
  if (!r.gates.empty()) {
    out << "  gates      " << (r.gates.size() - failed.size()) << " of " << r.gates.size() << " passed"
        << (failed.empty() ? "" : " (see above; exit code 4)") << "\n";
  }
}

}  // namespace

std::string format_build_summary(const BuildResult& result) {
  const RunReport& r = result.report;
  const NetworkStats& n = r.network;
  std::ostringstream out;
  out << "relief build: " << r.name << "\n";
  print_gates(out, r);
  out << "  network    " << n.roads << " roads, " << n.junctions << " junctions (" << n.intersections
      << " intersections, " << n.attribute_changes << " attribute changes), " << n.dead_ends << " dead ends, "
      << n.roundabouts << " roundabouts, " << n.traffic_signals << " signals, " << fixed(n.length_km, 2)
      << " km\n"
      << "  structures " << n.bridges << " bridges (" << fixed(n.bridge_km, 2) << " km), " << n.tunnels
      << " tunnels (" << fixed(n.tunnel_km, 2) << " km)\n"
      << "  elevation  " << r.samples << " samples every " << fixed(r.spacing_m, 2) << " m, "
      << to_string(r.interpolation) << "; " << r.void_samples << " in DEM voids, " << r.uncovered_samples
      << " uncovered\n"
      << "  vs DEM     MAE " << fixed(r.heights.vs_dem.mae_m, 3) << " m, RMSE "
      << fixed(r.heights.vs_dem.rmse_m, 3) << " m, max " << fixed(r.heights.vs_dem.max_m, 3)
      << " m (n = " << r.heights.vs_dem.n << ")\n";
  if (r.heights.vs_reference) {
    const ErrorStats& e = *r.heights.vs_reference;
    out << "  vs ref DEM MAE " << fixed(e.mae_m, 3) << " m, RMSE " << fixed(e.rmse_m, 3) << " m, max "
        << fixed(e.max_m, 3) << " m, bias " << fixed(e.bias_m, 3) << " m (n = " << e.n << ")\n";
  }
  for (const MethodReport& m : r.methods) {
    out << "  " << (m.method == r.profile_method ? "* " : "  ") << std::left << std::setw(8) << m.method
        << " ground vs DEM RMSE " << fixed(m.ground.vs_dem.rmse_m, 3) << " m, max grade "
        << fixed(m.gradient.max_percent, 1) << " %, p99 " << fixed(m.gradient.p99_percent, 1)
        << " %, compliance " << fixed(m.gradient.compliance_percent, 1) << " %, clearance ok at "
        << (m.separations - m.below_clearance) << "/" << m.separations << " grade separations ("
        << m.separations_alongside << " alongside)\n";
  }
  if (r.fit) {
    out << "  fit        " << r.fit->policy << " policy, " << r.fit->variables << " heights, "
        << r.fit->constraints << " limits, " << r.fit->iterations << " iterations, " << r.fit->solver << "; "
        << r.fit->violations.size() << " limit(s) left violated, largest " << fixed(r.fit->max_violation_m, 3)
        << " m\n";
  }
  if (r.paper) {
    out << "  paper      " << r.paper->roads_not_converged << " roads still over their limit after "
        << r.paper->max_iterations << " iterations\n";
  }
  if (r.opendrive) {
    const OpenDriveSummary& o = *r.opendrive;
    out << "  opendrive  " << o.file << " (" << o.version << "): " << o.roads << " roads, " << o.junctions
        << " junctions";
    if (o.junctions_without_movements)
      out << " (+" << o.junctions_without_movements << " with no possible movement)";
    if (o.junctions_joined)
      out << " (" << o.junctions_joined << " more intersections joined into them over " << o.roads_absorbed
          << " short roads)";
    out << ", " << o.connecting_roads << " connecting roads, " << o.transition_roads
        << " transition roads; largest lane-border gap at links " << fixed(o.max_link_gap_m, 4)
        << " m horizontal, " << fixed(o.max_link_step_m, 4) << " m vertical; read back within "
        << fixed(std::max(o.round_trip_max_xy_m, o.round_trip_max_z_m), 6) << " m\n";
  }
  if (r.sumo) {
    const SumoSummary& o = *r.sumo;
    out << "  sumo       " << o.file << ": " << o.edges << " edges, " << o.junctions << " junctions, "
        << o.traffic_lights << " traffic lights, " << o.internal_lanes
        << " internal lanes; lanes vs OpenDRIVE "
        << "surface: z p99 " << fixed(o.z_p99_m, 3) << " m, max " << fixed(o.z_max_m, 3) << " m"
        << (o.z_max_lane.empty() ? "" : " (lane " + o.z_max_lane + ")") << "; lane/internal step max "
        << fixed(o.max_handover_step_m, 3) << " m, gap max " << fixed(o.max_handover_gap_m, 3) << " m\n";
    out << "  sumo       kept off by grade:";
    for (const auto& [vclass, edges] : o.restricted_edges) {
      out << " " << vclass << " " << edges << " edges (> " << fixed(o.max_grade_percent.at(vclass), 0)
          << " %)";
    }
    if (o.restricted_edges.empty()) out << " none";
    if (o.routes) out << "; " << o.routes << " routes, step " << fixed(o.step_length_s, 2) << " s";
    out << "\n";
  }
  if (r.mesh) {
    const MeshSummary& m = *r.mesh;
    out << "  mesh       ";
    for (const std::string& f : m.files) out << f << " ";
    out << "\n";
    if (!m.tile_files.empty()) {
      out << "  mesh       " << m.tile_files.size() << " tile files of " << fixed(m.tile_size_m, 0)
          << " m tiles, " << r.name << "_Tile_X_Y.*\n";
    }
    if (m.road) {
      out << "  mesh       Road_Road " << m.road->triangles << " triangles, " << m.junctions_meshed
          << " junctions (" << m.junctions_failed << " left open), " << m.road->non_manifold_edges
          << " non-manifold edges, " << m.road->self_intersecting_pairs << " self-intersections; within "
          << fixed(m.xodr_surface_max_distance_m, 3) << " m of the OpenDRIVE surface\n";
    }
    if (m.terrain) {
      out << "  mesh       Terrain " << m.terrain->triangles << " triangles, within "
          << fixed(m.terrain_max_vertical_error_m, 2) << " m of the DEM; ground (roads + terrain) "
          << m.ground_holes << " holes, " << m.ground_portals << " tunnel mouths open ("
          << m.ground_triangles_under_roads
          << " road triangles under other roads left to the terrain); seam road/terrain "
          << fixed(m.seam_road_terrain_m.value_or(0.0), 4) << " m\n";
    }
  }
  out << "  gradient   max " << fixed(r.gradient.max_percent, 1) << " %, p99 "
      << fixed(r.gradient.p99_percent, 1) << " %, compliance with class limits "
      << fixed(r.gradient.compliance_percent, 1) << " %\n"
      << "  junctions  max elevation gap " << fixed(r.junctions.max_gap_m, 3) << " m ("
      << r.junctions.over_bound << " over " << fixed(r.junctions.bound_m, 2) << " m)\n";
  double total = 0.0;
  for (const auto& [stage, s] : r.timings_s) total += s;
  out << "  time       " << fixed(r.wall_s > 0.0 ? r.wall_s : total, 3) << " s\n";
  // Files of a folder of their own (the 3D view's view/: a city has a hundred tiles) as one line.
  std::map<std::filesystem::path, std::size_t> in_folder;
  for (const auto& path : result.written)
    if (path.parent_path().filename() == "view") ++in_folder[path.parent_path()];
  for (const auto& path : result.written) {
    const auto folder = in_folder.find(path.parent_path());
    if (folder == in_folder.end()) {
      out << "  wrote      " << path.string() << "\n";
    } else if (folder->second > 0) {
      out << "  wrote      " << folder->first.string() << "/ (" << folder->second
          << " files: the 3D view's index and tiles)\n";
      folder->second = 0;
    }
  }
  return out.str();
}

}  // namespace relief::cli
