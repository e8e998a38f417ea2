// `relief build`: parse, call relief::build, print the summary.
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <set>
#include <sstream>

#include "build_args.h"
#include "build_summary.h"
#include "commands.h"
#include "console.h"
#include "options.h"
#include "relief/core/errors.h"
#include "relief/pipeline/build.h"
#include "relief/pipeline/option_text.h"

namespace relief::cli {
namespace {

// "bus=20 coach=15 ..." for the --help text of --vclass-max-grade: the library's defaults.
std::string vclass_grades_text(const std::map<std::string, double>& grades) {
  std::ostringstream text;
  for (const auto& [vclass, percent] : grades)
    text << (text.tellp() > 0 ? " " : "") << vclass << "=" << percent;
  return text.str();
}

// "glb,obj,fbx" for the --help default of a set-valued option: the library's default.
template <class T>
std::string list_text(const std::set<T>& items) {
  std::string text;
  for (const T& item : items) text += (text.empty() ? "" : ",") + std::string(to_string(item));
  return text;
}

}  // namespace

void add_build_options(CLI::App* cmd, BuildCommandArgs* args) {
  BuildOptions& o = args->options;
  add_input_options(*cmd, o);
  cmd->add_option("--name", o.name, "base name of the outputs (default: the OSM file's stem)");
  cmd->add_option("--reference-dem", o.reference_dem_paths,
                  "independent DEM(s) to validate the road heights against (e.g. a finer one)");
  cmd->add_option_function<std::string>(
      "--reference-dem-unit",
      [&o](const std::string& text) {
        if (text.empty()) return;
        o.reference_dem.unit = parse_vertical_unit(text);
        if (!o.reference_dem.unit)
          throw CLI::ValidationError("--reference-dem-unit", "'" + text + "' is not one of m, ft, us-ft");
      },
      "vertical unit of the reference DEM(s): m, ft, us-ft");
  add_enum_option(*cmd, "--nodata-fill", o.sampling.nodata_fill, &parse_nodata_fill, "interpolate or error",
                  "DEM voids under roads: interpolate (along the road, reported) or error");
  cmd->add_flag("--allow-partial", o.sampling.allow_partial,
                "accept roads partly outside the DEM(s) (filled, reported)");
  cmd->add_option_function<std::string>(
      "--grade-limits",
      [&o](const std::string& text) {
        if (!text.empty()) parse_for("--grade-limits", [&] { o.fit.limits.apply_overrides(text); });
      },
      "override grade limits, e.g. highway=8,arterial=12,local=15,residential=18 (percent)");
  cmd->add_option_function<std::string>(
         "--outputs",
         [&o](const std::string& text) { parse_for("--outputs", [&] { o.outputs = parse_outputs(text); }); },
         "comma-separated outputs to write: xodr, sumo (NAME.net.xml and its plain XML, via netconvert), "
         "mesh (3D scene NAME.glb/.obj/.fbx + mesh_report.json), sight (every lane's sight distance against "
         "AASHTO's stopping sight distance: NAME.sight.geojson), view (the interactive 3D view: view.html "
         "and view/), geojson, report (report.json), html (report.html), or all")
      ->default_str(o.outputs == parse_outputs("all") ? "all" : list_text(o.outputs));
  cmd->add_flag("-q,--quiet", args->quiet, "print only errors and the summary");
  cmd->add_option("--fit-trace", args->fit_trace,
                  "write the profile fit solver's progress (its start, each iteration's residuals, step and "
                  "barrier) to this file, to see why a fit is slow or does not converge");
  add_enum_option(*cmd, "--profiles", o.profile_method, &parse_profile_method, "one of relief, paper, raw",
                  "road profiles the outputs carry: relief (network-wide constrained fit), paper (the seed "
                  "paper's 3-point moving average), raw (DEM drape)");
  add_enum_option(
      *cmd, "--grade-policy", o.fit.policy, &parse_grade_policy, "fidelity or design",
      "fit policy: fidelity (keep real grades, cap at --max-grade) or design (enforce the class limits)");
  cmd->add_option("--max-grade", o.fit.fidelity_max_grade_percent, "fidelity: grade cap for streets, percent")
      ->capture_default_str()
      ->check(finite_positive());
  cmd->add_option("--highway-max-grade", o.fit.fidelity_highway_max_grade_percent,
                  "fidelity: grade cap for motorways, trunks and their links, percent")
      ->capture_default_str()
      ->check(finite_positive());
  cmd->add_option("--foot-max-grade", o.fit.fidelity_foot_max_grade_percent,
                  "fidelity: grade cap for footways, paths, steps and bridleways (--include-paths), percent")
      ->capture_default_str()
      ->check(finite_positive());
  cmd->add_option("--max-cross-slope", o.fit.max_cross_slope_percent,
                  "fit: a road end lies across its junction's plane at most this steeply, percent (0: its "
                  "grade cap)")
      ->capture_default_str()
      ->check(finite_non_negative());
  cmd->add_option("--clearance", o.fit.clearance_m,
                  "minimum vertical clearance where roads on different layers cross, m")
      ->capture_default_str()
      ->check(finite_non_negative());
  cmd->add_option("--smoothing-wavelength", o.fit.cutoff_wavelength_m,
                  "height variations shorter than this are DEM noise to the fit, m")
      ->capture_default_str()
      ->check(finite_positive());
  cmd->add_option("--max-curvature", o.fit.max_curvature_per_m,
                  "bound on vertical curvature |z''|, 1/m (0: none)")
      ->capture_default_str()
      ->check(finite_non_negative());
  cmd->add_option("--opendrive-version", o.opendrive_rev_minor, "OpenDRIVE 1.N to write: 4, 7 or 8")
      ->capture_default_str()
      ->check(CLI::IsMember({4, 7, 8}));
  cmd->add_option_function<std::vector<std::string>>(
      "--vclass-max-grade",
      [&o](const std::vector<std::string>& items) {
        for (const std::string& item : items) {
          parse_for("--vclass-max-grade", [&] { apply_vclass_max_grade(o.sumo.max_grade_percent, item); });
        }
      },
      "SUMO: keep a vehicle class off lanes steeper than a grade, CLASS=PERCENT (repeatable; defaults " +
          vclass_grades_text(o.sumo.max_grade_percent) + "; CLASS=none drops a default)");
  cmd->add_option("--routes", o.demand.trips,
                  "SUMO: write NAME.rou.xml with this many random trips (randomTrips.py + duarouter) and "
                  "NAME.sumocfg (0: none)")
      ->capture_default_str()
      ->check(finite_non_negative());
  cmd->add_option("--route-end", o.demand.end_s, "SUMO: last departure, s (0: one per second)")
      ->capture_default_str()
      ->check(finite_non_negative());
  cmd->add_option("--seed", o.demand.seed, "SUMO: random seed of the trips")
      ->capture_default_str()
      ->check(finite_non_negative());
  cmd->add_option("--step-length", o.demand.step_length_s, "SUMO: simulation step in NAME.sumocfg, s")
      ->capture_default_str()
      ->check(finite_positive());
  cmd->add_option_function<std::string>(
         "--mesh-formats",
         [&o](const std::string& text) {
           parse_for("--mesh-formats", [&] { o.mesh_formats = parse_mesh_formats(text); });
         },
         "3D scene formats: comma-separated glb, obj, fbx")
      ->default_str(list_text(o.mesh_formats));
  cmd->add_flag_callback(
      "--no-terrain", [&o] { o.scene.terrain = false; }, "3D scene: roads only, no Terrain mesh");
  cmd->add_option("--mesh-tolerance", o.scene.road_mesh.tolerance_m,
                  "3D scene: largest distance of the road mesh from the OpenDRIVE surface, m")
      ->capture_default_str()
      ->check(finite_positive());
  cmd->add_option("--terrain-tolerance", o.scene.terrain_options.vertical_tolerance_m,
                  "3D scene: largest vertical error of the simplified terrain vs the DEM, m")
      ->capture_default_str()
      ->check(finite_positive());
  cmd->add_option("--mesh-tile-size", o.mesh_tile_size_m,
                  "3D scene: also write it cut into square tiles of this size, m, as NAME_Tile_X_Y "
                  "(CARLA large maps)")
      ->check(finite_positive());
  cmd->add_flag("--carla-package", o.carla_package,
                "also write NAME.carla.tar.gz, the folder and JSON CARLA's `make import` ingests (NAME.fbx + "
                "NAME.xodr; with --mesh-tile-size, the large map of NAME_Tile_X_Y.fbx tiles, whole metres "
                "up to 2000)");
  cmd->add_option("--sight-step", o.sight.step_m,
                  "sight: stations along every lane, and the object's steps ahead, every this many m")
      ->capture_default_str()
      ->check(finite_positive());
  cmd->add_option("--sight-eye-height", o.sight.eye_height_m, "sight: the driver's eye above the lane, m")
      ->capture_default_str()
      ->check(finite_positive());
  cmd->add_option("--sight-object-height", o.sight.object_height_m,
                  "sight: the object's height on the lane, m")
      ->capture_default_str()
      ->check(finite_positive());
  cmd->add_flag(
      "--sight-measure", o.sight.measure_beyond_required,
      "sight: measure every station's sight distance up to 300 m (default: only as far as it needs)");
  cmd->add_flag_callback(
      "--no-compare", [&o] { o.compare_methods = false; },
      "run only the chosen profile method (no comparison in the report)");
  cmd->add_option("--max-ground-departure", o.fit.max_ground_departure_m,
                  "fit: a road on the ground stays within this of the DEM, m (0: no bound)")
      ->capture_default_str()
      ->check(finite_non_negative());
  cmd->add_flag_callback(
      "--no-design-curves", [&o] { o.fit.design_curves = false; },
      "fit: no design-speed vertical curves on motorways..primary roads (physical bound only)");
  cmd->add_option_function<std::vector<std::string>>(
      "--gate",
      [&o](const std::vector<std::string>& items) {
        for (const std::string& item : items)
          parse_for("--gate", [&] { apply_gate_threshold(o.gates, item); });
      },
      "quality gate threshold, NAME=VALUE (repeatable); names: " +
          [] {
            std::string names;
            for (const std::string& n : GateThresholds::names()) names += (names.empty() ? "" : ", ") + n;
            return names;
          }());
  cmd->add_option("--gates", args->gate_mode,
                  "enforce: exit with 4 when an output fails a quality gate (outputs are written); report: "
                  "report failed gates but exit with 0")
      ->capture_default_str()
      ->check(CLI::IsMember({"enforce", "report"}));
}

Runner add_build_command(CLI::App& app) {
  auto* cmd =
      app.add_subcommand("build", "Build the 3D road network from OSM and DEM(s) and write its outputs");
  auto args = std::make_shared<BuildCommandArgs>();
  add_build_options(cmd, args.get());
  cmd->add_option_function<std::string>(
         "--out", [args](const std::string& dir) { args->options.out_dir = dir; },
         "output directory (created if missing)")
      ->required();
  return [args] {
    return run_reporting_errors([&] {
      Diagnostics diagnostics;
      print_diagnostics_live(diagnostics, args->quiet);
      std::shared_ptr<std::ofstream> trace;
      if (!args->fit_trace.empty()) {
        trace = std::make_shared<std::ofstream>(args->fit_trace);
        if (!*trace) throw OptionError("--fit-trace: cannot write '" + args->fit_trace + "'");
        args->options.fit.trace = [trace](const std::string& line) { *trace << line << '\n'; };
      }
      const BuildResult result = build(args->options, diagnostics, stderr_progress(args->quiet));
      if (!args->quiet) print_diagnostics_summary(diagnostics);
      std::cout << format_build_summary(result);
      const bool failed = !failed_gates(result.report.gates).empty();
      return static_cast<int>(failed && args->gate_mode == "enforce" ? kGateFailed : kOk);
    });
  };
}

}  // namespace relief::cli
