#include "relief/pipeline/build.h"

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <ctime>
#include <iomanip>
#include <sstream>

#include "pipeline/mesh_stage.h"
#include "pipeline/sight_stage.h"
#include "pipeline/stages.h"
#include "pipeline/sumo_stage.h"
#include "pipeline/view_stage.h"
#include "relief/core/atomic_file.h"
#include "relief/core/diagnostic_codes.h"
#include "relief/core/errors.h"
#include "relief/core/number_format.h"
#include "relief/export/carla_package.h"
#include "relief/export/geojson_writer.h"
#include "relief/export/opendrive_writer.h"
#include "relief/export/quality_gates.h"
#include "relief/export/report_html.h"
#include "relief/roads/opendrive_reader.h"
#include "relief/roads/road_model_checks.h"
#include "relief/viewer/overview_image.h"

namespace relief {
namespace {

// The build's time stamp: now, or SOURCE_DATE_EPOCH when set (reproducible-builds.org), so
// that two builds of the same inputs can be byte-identical.
std::time_t build_time() {
  std::time_t now = std::time(nullptr);
  if (const char* epoch = std::getenv("SOURCE_DATE_EPOCH"); epoch != nullptr && *epoch != '\0') {
    char* end = nullptr;
    const long long seconds = std::strtoll(epoch, &end, 10);
    if (*end != '\0' || seconds < 0) {
      throw InvalidInput("SOURCE_DATE_EPOCH='" + std::string(epoch) + "' is not a number of seconds >= 0");
    }
    now = static_cast<std::time_t>(seconds);
  }
  return now;
}

std::string utc_text(std::time_t now) {
  std::tm tm{};
  gmtime_r(&now, &tm);
  std::ostringstream out;
  out << std::put_time(&tm, "%Y-%m-%dT%H:%M:%SZ");
  return out.str();
}

// The CARLA package takes the .xodr and the FBX, a name Unreal accepts and CARLA's tile sizes:
// refused as bad usage before any work.
void check_carla_package_options(const BuildOptions& options, const std::string& name) {
  if (!options.carla_package) return;
  if (!options.outputs.contains(Output::xodr) || !options.outputs.contains(Output::mesh) ||
      !options.mesh_formats.contains(MeshFormat::fbx)) {
    throw OptionError("--carla-package needs the xodr and mesh outputs and the fbx mesh format (--outputs " +
                      std::string("...,xodr,mesh --mesh-formats ...,fbx)"));
  }
  if (!is_valid_carla_map_name(name)) {
    throw OptionError("--carla-package: the name '" + name +
                      "' is not a CARLA map name (letters, digits, '_' and '-', at most 64): set --name");
  }
  const double tile = options.mesh_tile_size_m;
  if (tile > 0.0 && (tile != std::floor(tile) || tile > kCarlaMaxTileSizeM)) {
    std::string size;
    append_shortest(size, tile);
    throw OptionError("--carla-package: --mesh-tile-size " + size +
                      " is not a whole number of metres up to " + std::to_string(kCarlaMaxTileSizeM) +
                      " (CARLA's largest tile)");
  }
}

// The figures of one method's profiles.
MethodReport evaluate(std::string method, const RoadNetwork& network,
                      const std::vector<RoadProfile>& profiles, const std::vector<RoadProfile>& raw,
                      const HeightValidator& validator, std::vector<GradeSeparation> separations,
                      const BuildOptions& options, double seconds) {
  MethodReport m;
  m.method = std::move(method);
  m.seconds = seconds;
  const std::vector<std::uint8_t> ground = ground_mask(network);
  const std::vector<std::uint8_t> structures = ground_mask(network, true);
  m.all = validator.validate(profiles);
  m.ground = validator.validate(profiles, ground);
  if (m.ground.max_road >= 0) {
    const Road& road = network.roads[static_cast<std::size_t>(m.ground.max_road)];
    if (!road.osm_way_ids.empty()) m.ground.max_osm_way = road.osm_way_ids.front();
  }
  m.structures = validator.validate(profiles, structures);
  m.gradient = grade_stats(network, profiles, options.fit.limits);
  m.junctions = junction_gaps(network, profiles);
  m.cut_fill = cut_fill(profiles, raw, ground);
  update_clearances(separations, profiles);
  for (const GradeSeparation& s : separations) {
    const double c = s.clearance_m;
    if (s.ordering_only) {
      ++m.overlaps_ordered;
      if (c < kOrderingGap_m - 1e-3) ++m.overlaps_out_of_order;
      continue;
    }
    m.min_clearance_m = m.separations == 0 ? c : std::min(m.min_clearance_m, c);
    ++m.separations;
    m.separations_alongside += s.alongside ? 1 : 0;
    if (c < options.fit.clearance_m - 1e-3) ++m.below_clearance;
  }
  return m;
}

}  // namespace

std::optional<ProfileMethod> parse_profile_method(std::string_view text) {
  if (text == "raw" || text == "none") return ProfileMethod::raw;
  if (text == "paper") return ProfileMethod::paper;
  if (text == "relief") return ProfileMethod::relief;
  return std::nullopt;
}

std::string_view to_string(ProfileMethod method) {
  switch (method) {
    case ProfileMethod::raw:
      return "raw";
    case ProfileMethod::paper:
      return "paper";
    case ProfileMethod::relief:
      return "relief";
  }
  return "unknown";
}

std::optional<Output> parse_output(std::string_view text) {
  if (text == "geojson") return Output::geojson;
  if (text == "report") return Output::report;
  if (text == "html") return Output::html;
  if (text == "xodr") return Output::xodr;
  if (text == "sumo") return Output::sumo;
  if (text == "mesh") return Output::mesh;
  if (text == "sight") return Output::sight;
  if (text == "view") return Output::view;
  return std::nullopt;
}

std::string_view to_string(Output output) {
  switch (output) {
    case Output::geojson:
      return "geojson";
    case Output::report:
      return "report";
    case Output::html:
      return "html";
    case Output::xodr:
      return "xodr";
    case Output::sumo:
      return "sumo";
    case Output::mesh:
      return "mesh";
    case Output::sight:
      return "sight";
    case Output::view:
      return "view";
  }
  return "unknown";
}

std::string default_name(const std::filesystem::path& osm_path) {
  std::string name = osm_path.filename().string();
  for (const char* ext : {".gz", ".bz2", ".pbf", ".osm", ".xml"}) {
    const std::string e(ext);
    if (name.size() > e.size() && name.compare(name.size() - e.size(), e.size(), e) == 0) {
      name.resize(name.size() - e.size());
    }
  }
  return name.empty() ? "relief" : name;
}

BuildResult build(const BuildOptions& options, Diagnostics& diagnostics, const ProgressFn& progress) {
  StageTimer timer(progress);
  BuildResult result;
  RunReport& report = result.report;
  report.name = options.name.empty() ? default_name(options.osm_path) : options.name;
  check_carla_package_options(options, report.name);
  const std::time_t started = build_time();
  report.created_utc = utc_text(started);
  report.osm_path = options.osm_path.string();
  report.interpolation = options.dem.interpolation;
  report.spacing_m = options.sampling.spacing_m;
  report.nodata_fill = std::string(to_string(options.sampling.nodata_fill));
  report.grade_limits = options.fit.limits;
  report.profile_method = std::string(to_string(options.profile_method));
  report.diagnostics = &diagnostics;

  const LoadedNetwork loaded = load_network(options, diagnostics, timer);
  const RoadNetwork& network = loaded.network;
  report.frame = network.frame;
  report.network = network_stats(network);
  // Options whose cost would exhaust the machine are refused before any DEM is read.
  check_sample_budget(network, options.sampling);

  const DemSampler dem = timer.run("open DEM", [&] {
    return DemSampler(options.dem_paths, network.frame, network_bounds(network), options.dem, &diagnostics);
  });
  report.dems = dem.sources();

  ElevationSamples samples = timer.run(
      "sample elevation", [&] { return sample_elevation(network, dem, options.sampling, diagnostics); });
  // Where the road as driven rounds a sharp OSM vertex it is shorter than the polyline: the fit
  // takes grades and curvatures along the driven road.
  timer.run("driven stations", [&] {
    for (const Road& road : network.roads) {
      RoadProfile& p = samples.profiles[road.id];
      if (p.size() >= 2) p.driven_s = driven_stations(road, p, options.road_model);
    }
    return 0;
  });
  report.samples = samples.samples;
  report.void_samples = samples.void_samples;
  report.uncovered_samples = samples.uncovered_samples;
  report.roads_without_height = samples.roads_without_height;
  const std::vector<RoadProfile>& raw = samples.profiles;

  // The profiles: the chosen method, and the others when comparing.
  const auto wanted = [&](ProfileMethod m) { return options.compare_methods || options.profile_method == m; };
  std::optional<PaperSmoothingResult> paper;
  double paper_seconds = 0.0, fit_seconds = 0.0;
  if (wanted(ProfileMethod::paper)) {
    paper = timer.run("paper smoothing", [&] {
      PaperSmoothingOptions o;
      o.limits = options.fit.limits;
      o.max_iterations = options.paper_max_iterations;
      return smooth_paper(network, raw, o);
    });
    paper_seconds = timer.timings().back().second;
    report.paper = PaperSummary{options.paper_max_iterations, paper->not_converged_roads.size(),
                                paper->max_shift_m, paper->not_converged_roads};
  }
  std::optional<ProfileFitResult> fit;
  if (wanted(ProfileMethod::relief)) {
    fit = timer.run("fit profiles", [&] {
      ProfileFitOptions fit_options = options.fit;
      if (options.hold_profiles) fit_options.holds = options.hold_profiles(network, raw);
      // Where the road model will cut the roads for their junctions (plan only), so that the
      // fit bounds the grades across each junction there.
      return fit_profiles(network, raw, fit_options, diagnostics,
                          junction_cuts(network, raw, options.road_model));
    });
    fit_seconds = timer.timings().back().second;
    FitSummary summary;
    summary.policy = std::string(to_string(options.fit.policy));
    summary.iterations = fit->iterations;
    summary.converged = fit->converged;
    summary.solver = fit->solver_status;
    summary.variables = fit->variables;
    summary.held_variables = fit->held_variables;
    summary.constraints = fit->constraints;
    summary.max_violation_m = fit->max_violation_m;
    summary.clearance_m = options.fit.clearance_m;
    summary.cutoff_wavelength_m = options.fit.cutoff_wavelength_m;
    summary.max_ground_departure_m = options.fit.max_ground_departure_m;
    summary.max_cross_slope_percent = options.fit.max_cross_slope_percent;
    summary.violations = fit->violations;
    report.fit = std::move(summary);
  }
  const std::vector<RoadProfile>& profiles = options.profile_method == ProfileMethod::paper ? paper->profiles
                                             : options.profile_method == ProfileMethod::relief ? fit->profiles
                                                                                               : raw;

  std::optional<DemSampler> reference;
  if (!options.reference_dem_paths.empty()) {
    reference = timer.run("open reference DEM", [&] {
      return DemSampler(options.reference_dem_paths, network.frame, network_bounds(network),
                        options.reference_dem, &diagnostics);
    });
    report.reference_dems = reference->sources();
  }
  // Validation only reads the profiles and the DEM: it runs beside the outputs.
  BackgroundStage<std::vector<MethodReport>> validation("validate (beside the outputs)", [&] {
    std::vector<MethodReport> methods;
    const HeightValidator validator(raw, dem, reference ? &*reference : nullptr);
    // The fit found the crossings of different layers on the same stations already.
    const std::vector<GradeSeparation> separations =
        fit ? fit->separations : find_grade_separations(network, raw);
    if (wanted(ProfileMethod::raw)) {
      methods.push_back(evaluate("raw", network, raw, raw, validator, separations, options, 0.0));
    }
    if (paper) {
      methods.push_back(
          evaluate("paper", network, paper->profiles, raw, validator, separations, options, paper_seconds));
    }
    if (fit) {
      methods.push_back(
          evaluate("relief", network, fit->profiles, raw, validator, separations, options, fit_seconds));
    }
    return methods;
  });
  const auto take_validation = [&] {
    report.methods = validation.take(timer);
    for (const MethodReport& m : report.methods) {
      if (m.method != report.profile_method) continue;
      report.heights = m.all;
      report.gradient = m.gradient;
      report.junctions = m.junctions;
    }
  };

  // Every output goes to a temporary first; all are renamed together at the end.
  std::error_code ec;
  std::filesystem::create_directories(options.out_dir, ec);
  if (ec) {
    throw IoError("cannot create the output directory '" + options.out_dir.string() + "': " + ec.message());
  }
  OutputSet files;
  const auto path_of = [&](const std::string& suffix) { return options.out_dir / (report.name + suffix); };
  std::optional<RoadModelBuild> built;
  std::size_t signals_mid_road = 0;
  const bool scene_needed = options.outputs.contains(Output::mesh) ||
                            options.outputs.contains(Output::sight) || options.outputs.contains(Output::view);
  // Each model road's grade cap (-1 for a connecting road: the larger of the roads it joins), for
  // the elevation records' check and the SUMO net's height steps.
  std::vector<double> model_caps;
  if (options.outputs.contains(Output::xodr) || options.outputs.contains(Output::sumo) || scene_needed) {
    built = timer.run("build road model", [&] {
      // The junction planes of relief's fit tilt the lanes at junctions onto them; the other
      // methods have none and keep every cross-section level.
      static const std::vector<Vec2> level;
      const std::vector<Vec2>& planes =
          options.profile_method == ProfileMethod::relief ? fit->junction_gradient : level;
      RoadModelOptions model_options = options.road_model;
      if (options.profile_method == ProfileMethod::relief) {
        model_options.grade_caps.resize(network.roads.size());
        for (std::size_t r = 0; r < network.roads.size(); ++r)
          model_options.grade_caps[r] = grade_limit(options.fit, network.roads[r].attributes);
      }
      return build_road_model(network, profiles, model_options, diagnostics, planes);
    });
    built->model.name = report.name;
    if (options.fitted && fit) options.fitted(network, *fit, built->model);
    // The junctions traffic lights control (OSM's signals, and those the options name): the
    // .xodr records them, SUMO gives them a light.
    const std::set<int> signalled =
        signalled_junctions(loaded, built->model, options.signal_snap_m, signals_mid_road);
    for (JunctionModel& j : built->model.junctions)
      j.traffic_signal = signalled.contains(j.id) || options.sumo.signalled_junctions.contains(j.id);
    // The elevation records' grades against the caps the fit applied (connecting roads: the
    // steeper road's they join).
    model_caps.assign(built->model.roads.size(), -1.0);
    for (std::size_t i = 0; i < built->model.roads.size(); ++i) {
      const int source = built->model.roads[i].source_road;
      if (source >= 0) model_caps[i] = grade_limit(options.fit, network.roads[source].attributes);
    }
    report.model_grades =
        timer.run("check road model grades", [&] { return check_grades(built->model, model_caps); });
  }
  // netconvert is the longest chain of the build (SUMO network, netconvert, its check): it
  // starts first and runs in the background while the other outputs are written.
  std::optional<SumoStageInput> sumo_in;
  std::optional<SumoJob> sumo;
  if (options.outputs.contains(Output::sumo)) {
    sumo_in.emplace(SumoStageInput{options, loaded, built->model, report.name, diagnostics, signals_mid_road,
                                   model_caps});
    if (signals_mid_road > 0) {
      diagnostics.report(Severity::info, codes::kSumoSignalMidRoad,
                         std::to_string(signals_mid_road) + " traffic signals are more than " +
                             std::to_string(options.signal_snap_m) +
                             " m from any intersection (pedestrian crossings); SUMO gets no light for them");
    }
    sumo = start_sumo(*sumo_in);
  }
  if (options.outputs.contains(Output::geojson)) {
    timer.run("write GeoJSON", [&] {
      files.add(path_of(".geojson"), [&](std::ostream& out) { write_geojson(out, network, profiles); });
      return 0;
    });
    report.outputs.push_back(report.name + ".geojson");
    result.written.push_back(path_of(".geojson"));
  }
  std::optional<BackgroundStage<OpenDriveSummary>> xodr_check;
  std::string carla_xodr;  // the .xodr text again, for the CARLA package
  if (options.outputs.contains(Output::xodr)) {
    const RoadModel& model = built->model;
    std::string xodr = timer.run("write OpenDRIVE", [&] {
      OpenDriveOptions odr;
      odr.rev_minor = options.opendrive_rev_minor;
      odr.date = report.created_utc;
      std::ostringstream text;
      write_opendrive(text, model, odr);
      std::string written = text.str();
      files.add(path_of(".xodr"), [&](std::ostream& out) { out << written; });
      return written;
    });
    if (options.carla_package) carla_xodr = xodr;
    // The file read back is the model written; lane borders meet at every link. Only reads the
    // model and the text, so it runs beside the outputs that follow.
    xodr_check.emplace("check OpenDRIVE (beside the outputs)", [&, xodr = std::move(xodr)] {
      const RoadModel back = parse_opendrive(xodr, report.name + ".xodr");
      const ModelDeviation dev = compare_models(model, back);
      const LinkContinuity links = check_link_continuity(model);
      const ConnectingRoadCrossings crossings = check_connecting_road_crossings(model);
      const ConnectingRoadsOverRoads over_roads = check_connecting_roads_over_roads(model);
      OpenDriveSummary o;
      o.file = report.name + ".xodr";
      o.version = "1." + std::to_string(options.opendrive_rev_minor);
      o.roads = built->stats.roads;
      o.connecting_roads = built->stats.connecting_roads;
      o.connecting_roads_off_surface = built->stats.connecting_roads_off_surface;
      o.connecting_road_departure_max_m = built->stats.connecting_road_departure_max_m;
      o.junctions = built->stats.junctions;
      o.junctions_without_movements = built->stats.junctions_without_movements;
      o.junctions_joined = built->stats.junctions_joined;
      o.roads_absorbed = built->stats.roads_absorbed;
      o.direct_links = built->stats.direct_links;
      o.transition_roads = built->stats.transition_roads;
      o.transitions_as_junctions = built->stats.transitions_as_junctions;
      o.roads_skipped = built->stats.roads_skipped;
      o.max_link_gap_m = links.max_horizontal_m;
      o.max_link_step_m = links.max_vertical_m;
      o.link_borders_checked = links.borders_checked;
      o.crossing_max_step_m = crossings.max_step_m;
      o.crossing_junctions_over = crossings.junctions_over;
      o.crossing_worst_junction = crossings.worst_junction;
      o.crossing_worst_xy = crossings.worst_xy;
      o.over_road_max_step_m = over_roads.max_step_m;
      o.over_road_junctions_over = over_roads.junctions_over;
      o.over_road_worst_junction = over_roads.worst_junction;
      o.over_road_worst_road = over_roads.worst_road;
      o.over_road_worst_xy = over_roads.worst_xy;
      o.round_trip_max_xy_m = dev.max_xy_m;
      o.round_trip_max_z_m = dev.max_z_m;
      o.round_trip_points = dev.points;
      o.elevation_max_deviation_m = built->stats.max_elevation_deviation_m;
      return o;
    });
    report.outputs.push_back(report.name + ".xodr");
    result.written.push_back(path_of(".xodr"));
  }
  std::optional<SightResult> sight_result;  // for report.html's map
  std::optional<Scene> scene;
  std::optional<SightStageInput> sight_in;
  std::optional<BackgroundStage<std::pair<SightResult, double>>> sight;
  std::optional<ViewStage> view;
  std::string overview_png;  // report.html's picture
  if (scene_needed) {
    const MeshStageInput in{options, network, built->model, dem, report.name, diagnostics};
    scene.emplace(build_scene_stage(in, timer));
    if (options.meshed) options.meshed(built->model, *scene);
    if (options.outputs.contains(Output::mesh)) {
      CarlaFbx carla_fbx;
      report.mesh = write_mesh_outputs(in, *scene, files, timer, result.written, report.outputs,
                                       options.carla_package ? &carla_fbx : nullptr);
      if (options.carla_package) {
        write_carla_package_output(in, std::move(carla_xodr), std::move(carla_fbx), started, files, timer,
                                   *report.mesh, result.written, report.outputs);
      }
    }
    if (options.outputs.contains(Output::view))
      view = write_view_tiles(in, *scene, files, timer, result.written);
    if (options.outputs.contains(Output::html))
      overview_png = timer.run("render the overview", [&] { return render_overview_png(scene->meshes); });
    // The sight distances only read the scene: after its files (their buffers freed: Portland's
    // peak stayed 200 MB lower than beside them), beside the end of the SUMO chain.
    if (options.outputs.contains(Output::sight)) {
      sight_in.emplace(SightStageInput{options, network, built->model, scene->meshes, report.name});
      sight.emplace("sight distances (beside the SUMO chain)", [&] {
        const auto start = std::chrono::steady_clock::now();
        SightResult r = compute_sight(*sight_in);
        return std::make_pair(
            std::move(r), std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
      });
    }
  }
  if (sumo) report.sumo = finish_sumo(*sumo_in, *sumo, files, timer, result.written, report.outputs);
  if (sight) {
    auto [computed, seconds] = sight->take(timer);
    report.sight = write_sight_outputs(*sight_in, computed, seconds, files, result.written, report.outputs);
    sight_result = std::move(computed);
  }
  scene.reset();
  if (xodr_check) report.opendrive = xodr_check->take(timer);
  take_validation();
  report.gates = evaluate_gates(report, options.gates);
  for (const Gate& g : failed_gates(report.gates)) {
    diagnostics.report(Severity::error, codes::kGateFailed,
                       "quality gate " + g.name + " failed: " + std::to_string(g.value) + " against " +
                           std::to_string(g.threshold) + (g.where.empty() ? "" : ", " + g.where));
  }
  if (view) {
    ViewIndexInput in;
    in.report = &report;
    in.model = &built->model;
    in.network = &network;
    in.raw = &raw;
    in.paper = paper ? &paper->profiles : nullptr;
    in.fitted = fit ? &fit->profiles : nullptr;
    in.sight = sight_result ? &*sight_result : nullptr;
    write_view_page(options, *view, in, files, timer, result.written, report.outputs);
  }
  if (options.outputs.contains(Output::html)) {
    report.outputs.emplace_back("report.html");
    result.written.push_back(options.out_dir / "report.html");
    report.timings_s = timer.timings();
    report.wall_s = timer.elapsed();
    timer.run("write report.html", [&] {
      HtmlReportInput in;
      in.report = &report;
      in.network = &network;
      in.raw = &raw;
      in.paper = paper ? &paper->profiles : nullptr;
      in.fitted = fit ? &fit->profiles : nullptr;
      in.sight = sight_result ? &*sight_result : nullptr;
      in.view_page = view ? "view.html" : "";
      in.overview_png = std::move(overview_png);
      files.add(options.out_dir / "report.html", [&](std::ostream& out) { write_report_html(out, in); });
      return 0;
    });
  }
  if (options.outputs.contains(Output::report)) {
    report.outputs.emplace_back("report.json");
    result.written.push_back(options.out_dir / "report.json");
    report.timings_s = timer.timings();
    report.wall_s = timer.elapsed();
    files.add(options.out_dir / "report.json", [&](std::ostream& out) { out << report_json(report); });
  }
  files.commit();
  report.timings_s = timer.timings();
  report.wall_s = timer.elapsed();
  return result;
}

}  // namespace relief
