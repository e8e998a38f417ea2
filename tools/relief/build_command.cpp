// `relief build`: parse, call relief::build, print the summary.
#include <cmath>
#include <iomanip>
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
  std::string profiles = "relief";
  std::string grade_policy = "fidelity";
  double max_grade_percent = 35.0;
  double highway_max_grade_percent = 10.0;
  double clearance_m = 5.0;
  double wavelength_m = 40.0;
  double max_curvature = 0.05;
  bool no_compare = false;
  int opendrive_minor = 7;
  std::vector<std::string> vclass_max_grade;
  int routes = 0;
  double route_end_s = 0.0;
  unsigned seed = 42;
  double step_length_s = 0.05;
  std::string mesh_formats = "glb,obj,fbx";
  bool no_terrain = false;
  double mesh_tolerance_m = 0.02;
  double terrain_tolerance_m = 0.25;
  double mesh_tile_size_m = 0.0;
  double max_ground_departure_m = 15.0;
  bool no_design_curves = false;
  std::vector<std::string> gates;
  std::string gate_mode = "enforce";
};

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

void print_summary(const BuildResult& result) {
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
        << fixed(o.max_handover_step_m, 3) << " m\n";
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
  for (const auto& path : result.written) out << "  wrote      " << path.string() << "\n";
  std::cout << out.str();
}

}  // namespace

Runner add_build_command(CLI::App& app) {
  auto* cmd =
      app.add_subcommand("build", "Build the 3D road network from OSM and DEM(s) and write its outputs");
  auto args = std::make_shared<BuildArgs>();
  args->input.add_to(*cmd);
  cmd->add_option("--out", args->out_dir, "output directory (created if missing)")->required();
  cmd->add_option("--name", args->name, "base name of the outputs (default: the OSM file's stem)");
  cmd->add_option("--reference-dem", args->reference_dems,
                  "independent DEM(s) to validate the road heights against (e.g. a finer one)");
  cmd->add_option("--reference-dem-unit", args->reference_dem_unit,
                  "vertical unit of the reference DEM(s): m, ft, us-ft");
  cmd->add_option("--nodata-fill", args->nodata_fill,
                  "DEM voids under roads: interpolate (along the road, reported) or error")
      ->capture_default_str();
  cmd->add_flag("--allow-partial", args->allow_partial,
                "accept roads partly outside the DEM(s) (filled, reported)");
  cmd->add_option("--grade-limits", args->grade_limits,
                  "override grade limits, e.g. highway=8,arterial=12,local=15,residential=18 (percent)");
  cmd->add_option(
         "--outputs", args->outputs,
         "comma-separated outputs to write: xodr, sumo (NAME.net.xml and its plain XML, via netconvert), "
         "mesh (3D scene NAME.glb/.obj/.fbx + mesh_report.json), geojson, report (report.json), html "
         "(report.html), or all")
      ->capture_default_str();
  cmd->add_flag("-q,--quiet", args->quiet, "print only errors and the summary");
  cmd->add_option("--profiles", args->profiles,
                  "road profiles the outputs carry: relief (network-wide constrained fit), paper (the seed "
                  "paper's 3-point moving average), raw (DEM drape)")
      ->capture_default_str();
  cmd->add_option(
         "--grade-policy", args->grade_policy,
         "fit policy: fidelity (keep real grades, cap at --max-grade) or design (enforce the class limits)")
      ->capture_default_str();
  cmd->add_option("--max-grade", args->max_grade_percent, "fidelity: grade cap for streets, percent")
      ->capture_default_str()
      ->check(finite_positive());
  cmd->add_option("--highway-max-grade", args->highway_max_grade_percent,
                  "fidelity: grade cap for motorways, trunks and their links, percent")
      ->capture_default_str()
      ->check(finite_positive());
  cmd->add_option("--clearance", args->clearance_m,
                  "minimum vertical clearance where roads on different layers cross, m")
      ->capture_default_str()
      ->check(finite_non_negative());
  cmd->add_option("--smoothing-wavelength", args->wavelength_m,
                  "height variations shorter than this are DEM noise to the fit, m")
      ->capture_default_str()
      ->check(finite_positive());
  cmd->add_option("--max-curvature", args->max_curvature, "bound on vertical curvature |z''|, 1/m (0: none)")
      ->capture_default_str()
      ->check(finite_non_negative());
  cmd->add_option("--opendrive-version", args->opendrive_minor, "OpenDRIVE 1.N to write: 4, 7 (default) or 8")
      ->capture_default_str()
      ->check(CLI::IsMember({4, 7, 8}));
  cmd->add_option("--vclass-max-grade", args->vclass_max_grade,
                  "SUMO: keep a vehicle class off lanes steeper than a grade, CLASS=PERCENT (repeatable; "
                  "defaults truck=15 trailer=10 bus=20 coach=15; CLASS=none drops a default)");
  cmd->add_option("--routes", args->routes,
                  "SUMO: write NAME.rou.xml with this many random trips (randomTrips.py + duarouter) and "
                  "NAME.sumocfg")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--route-end", args->route_end_s, "SUMO: last departure, s (default: one per second)")
      ->check(finite_non_negative());
  cmd->add_option("--seed", args->seed, "SUMO: random seed of the trips")->capture_default_str();
  cmd->add_option("--step-length", args->step_length_s, "SUMO: simulation step in NAME.sumocfg, s")
      ->capture_default_str()
      ->check(finite_positive());
  cmd->add_option("--mesh-formats", args->mesh_formats, "3D scene formats: comma-separated glb, obj, fbx")
      ->capture_default_str();
  cmd->add_flag("--no-terrain", args->no_terrain, "3D scene: roads only, no Terrain mesh");
  cmd->add_option("--mesh-tolerance", args->mesh_tolerance_m,
                  "3D scene: largest distance of the road mesh from the OpenDRIVE surface, m")
      ->capture_default_str()
      ->check(finite_positive());
  cmd->add_option("--terrain-tolerance", args->terrain_tolerance_m,
                  "3D scene: largest vertical error of the simplified terrain vs the DEM, m")
      ->capture_default_str()
      ->check(finite_positive());
  cmd->add_option("--mesh-tile-size", args->mesh_tile_size_m,
                  "3D scene: also write it cut into square tiles of this size, m, as NAME_Tile_X_Y "
                  "(CARLA large maps)")
      ->check(finite_positive());
  cmd->add_flag("--no-compare", args->no_compare,
                "run only the chosen profile method (no comparison in the report)");
  cmd->add_option("--max-ground-departure", args->max_ground_departure_m,
                  "fit: a road on the ground stays within this of the DEM, m (0: no bound)")
      ->capture_default_str()
      ->check(finite_non_negative());
  cmd->add_flag("--no-design-curves", args->no_design_curves,
                "fit: no design-speed vertical curves on motorways..primary roads (physical bound only)");
  cmd->add_option(
      "--gate", args->gates, "quality gate threshold, NAME=VALUE (repeatable); names: " + [] {
        std::string names;
        for (const std::string& n : GateThresholds::names()) names += (names.empty() ? "" : ", ") + n;
        return names;
      }());
  cmd->add_option("--gates", args->gate_mode,
                  "enforce: exit with 4 when an output fails a quality gate (outputs are written); report: "
                  "report failed gates but exit with 0")
      ->capture_default_str()
      ->check(CLI::IsMember({"enforce", "report"}));

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
          throw CLI::ValidationError("--reference-dem-unit",
                                     "'" + args->reference_dem_unit + "' is not one of m, ft, us-ft");
        }
      }
      const auto fill = parse_nodata_fill(args->nodata_fill);
      if (!fill)
        throw CLI::ValidationError("--nodata-fill",
                                   "'" + args->nodata_fill + "' is not interpolate or error");
      options.sampling.nodata_fill = *fill;
      options.sampling.allow_partial = args->allow_partial;
      const auto method = parse_profile_method(args->profiles);
      if (!method)
        throw CLI::ValidationError("--profiles", "'" + args->profiles + "' is not one of relief, paper, raw");
      options.profile_method = *method;
      const auto policy = parse_grade_policy(args->grade_policy);
      if (!policy)
        throw CLI::ValidationError("--grade-policy",
                                   "'" + args->grade_policy + "' is not fidelity or design");
      options.fit.policy = *policy;
      options.fit.fidelity_max_grade_percent = args->max_grade_percent;
      options.fit.fidelity_highway_max_grade_percent = args->highway_max_grade_percent;
      options.fit.clearance_m = args->clearance_m;
      options.fit.cutoff_wavelength_m = args->wavelength_m;
      options.fit.max_curvature_per_m = args->max_curvature;
      options.fit.max_ground_departure_m = args->max_ground_departure_m;
      options.fit.design_curves = !args->no_design_curves;
      for (const std::string& item : args->gates) {
        const std::size_t eq = item.find('=');
        double value = 0.0;
        try {
          std::size_t used = 0;
          value = std::stod(item.substr(eq == std::string::npos ? item.size() : eq + 1), &used);
          if (eq == std::string::npos || used != item.size() - eq - 1 || !std::isfinite(value))
            throw std::invalid_argument(item);
        } catch (const std::exception&) {
          throw CLI::ValidationError("--gate", "'" + item + "' is not NAME=VALUE with a finite VALUE");
        }
        if (!options.gates.set(item.substr(0, eq), value)) {
          throw CLI::ValidationError("--gate", "'" + item.substr(0, eq) + "' is not a quality gate");
        }
      }
      options.compare_methods = !args->no_compare;
      options.opendrive_rev_minor = args->opendrive_minor;
      for (const std::string& item : args->vclass_max_grade) {
        const std::size_t eq = item.find('=');
        const std::string vclass = item.substr(0, eq);
        if (eq == std::string::npos || vclass.empty()) {
          throw CLI::ValidationError("--vclass-max-grade", "'" + item + "' is not CLASS=PERCENT");
        }
        const std::string value = item.substr(eq + 1);
        if (value == "none") {
          options.sumo.max_grade_percent.erase(vclass);
          continue;
        }
        try {
          std::size_t used = 0;
          const double percent = std::stod(value, &used);
          if (used != value.size() || !(percent > 0.0)) throw std::invalid_argument(value);
          options.sumo.max_grade_percent[vclass] = percent;
        } catch (const std::exception&) {
          throw CLI::ValidationError("--vclass-max-grade", "'" + item + "': the grade must be a percent > 0");
        }
      }
      options.mesh_formats.clear();
      {
        std::stringstream in(args->mesh_formats);
        std::string item;
        while (std::getline(in, item, ',')) {
          const auto format = parse_mesh_format(item);
          if (!format)
            throw CLI::ValidationError("--mesh-formats", "'" + item + "' is not one of glb, obj, fbx");
          options.mesh_formats.insert(*format);
        }
      }
      options.terrain = !args->no_terrain;
      options.road_mesh.tolerance_m = args->mesh_tolerance_m;
      options.terrain_options.vertical_tolerance_m = args->terrain_tolerance_m;
      options.mesh_tile_size_m = args->mesh_tile_size_m;
      options.demand.trips = args->routes;
      options.demand.end_s = args->route_end_s;
      options.demand.seed = args->seed;
      options.demand.step_length_s = args->step_length_s;
      if (!args->grade_limits.empty()) options.grade_limits.apply_overrides(args->grade_limits);
      if (args->outputs != "all") {
        options.outputs.clear();
        std::stringstream in(args->outputs);
        std::string item;
        while (std::getline(in, item, ',')) {
          const auto output = parse_output(item);
          if (!output)
            throw CLI::ValidationError(
                "--outputs", "'" + item + "' is not one of xodr, sumo, mesh, geojson, report, html, all");
          options.outputs.insert(*output);
        }
      }
      Diagnostics diagnostics;
      print_diagnostics_live(diagnostics, args->quiet);
      const BuildResult result = build(options, diagnostics, stderr_progress(args->quiet));
      if (!args->quiet) print_diagnostics_summary(diagnostics);
      print_summary(result);
      const bool failed = !failed_gates(result.report.gates).empty();
      return static_cast<int>(failed && args->gate_mode == "enforce" ? kGateFailed : kOk);
    });
  };
}

}  // namespace relief::cli
