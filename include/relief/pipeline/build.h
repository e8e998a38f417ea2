#pragma once
// The main job: OSM + DEM(s) -> 3D road network and its outputs, as one library call that the
// CLI (and any other program) strings together: read, project, build the network, sample the
// DEM, validate, write.

#include <filesystem>
#include <functional>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "relief/core/diagnostics.h"
#include "relief/export/mesh_writer.h"
#include "relief/export/quality_gates.h"
#include "relief/export/report_writer.h"
#include "relief/export/sumo_network.h"
#include "relief/export/sumo_tools.h"
#include "relief/roads/elevation_sampling.h"
#include "relief/roads/osm_reader.h"
#include "relief/roads/paper_smoothing.h"
#include "relief/roads/profile_fit.h"
#include "relief/roads/road_model_builder.h"
#include "relief/roads/validation.h"
#include "relief/scene/scene.h"
#include "relief/sight/sight_distance.h"
#include "relief/terrain/dem_sampler.h"

namespace relief {

/// How the road profiles that the outputs carry are made.
enum class ProfileMethod {
  raw,     ///< the DEM drape as sampled
  paper,   ///< the seed paper's iterated three-point moving average
  relief,  ///< relief's network-wide constrained fit (profile_fit.h)
};
[[nodiscard]] std::optional<ProfileMethod> parse_profile_method(std::string_view text);
[[nodiscard]] std::string_view to_string(ProfileMethod method);

/// Outputs `build` can write into the output directory.
enum class Output { geojson, report, html, xodr, sumo, mesh, sight, view };
[[nodiscard]] std::optional<Output> parse_output(std::string_view text);
[[nodiscard]] std::string_view to_string(Output output);

struct BuildOptions {
  std::filesystem::path osm_path;
  std::vector<std::string> dem_paths;            ///< >= 1, mosaic in the order given
  std::vector<std::string> reference_dem_paths;  ///< optional independent check
  std::filesystem::path out_dir;
  std::string name;                ///< default: the OSM file's stem
  std::optional<std::string> crs;  ///< default: the WGS84 UTM zone of the frame's centre
  /// Centre of the local frame (its origin, rounded to whole metres of the CRS); default: the
  /// centre of the roads read. Builds that share it (region tiles) share one frame.
  std::optional<LonLat> frame_centre;
  OsmReadOptions osm;
  DemOptions dem;
  DemOptions reference_dem;
  SamplingOptions sampling;
  ProfileMethod profile_method = ProfileMethod::relief;
  /// The fit's options, used as given. `fit.limits` is the run's one table of class grade
  /// limits: the design policy's limits, the paper smoothing's, and the compliance every
  /// method's profiles are reported against (report.json "grade_limits_percent").
  ProfileFitOptions fit;
  int paper_max_iterations = 1000;
  /// Also run the other methods and put the comparison in the report.
  bool compare_methods = true;
  std::set<Output> outputs = {Output::geojson, Output::report, Output::html,  Output::xodr,
                              Output::sumo,    Output::mesh,   Output::sight, Output::view};
  RoadModelOptions road_model;
  int opendrive_rev_minor = 7;  ///< OpenDRIVE 1.4, 1.7 or 1.8
  /// SUMO's options, used as given, except that `sumo.signalled_junctions` (OpenDRIVE junction
  /// ids of this build's model) is joined by the junctions the OSM signals give (signal_snap_m):
  /// a caller's ids add lights, never replace them.
  SumoOptions sumo;
  /// Random trips for a quick SUMO run (NAME.rou.xml + NAME.sumocfg); trips = 0: none.
  DemandOptions demand;
  double signal_snap_m = 30.0;  ///< an OSM signal this close to an intersection controls it
  /// The 3D scene (road meshes, the terrain, its openings at tunnel mouths), as given; the
  /// pipeline runs the scene's checks beside the file writers whatever `scene.checks` says.
  SceneOptions scene;
  std::set<MeshFormat> mesh_formats = {MeshFormat::glb, MeshFormat::obj, MeshFormat::fbx};
  /// Thresholds of the quality gates checked on the outputs (quality_gates.h).
  GateThresholds gates;
  /// Besides the whole scene, the scene cut into tiles of this size (m) in every format, as
  /// NAME_Tile_X_Y (see split_into_tiles); 0: no tiles.
  double mesh_tile_size_m = 0.0;
  /// Region tiles: the scene files (and the CARLA package) hold only the triangles of this cell
  /// of the grid of mesh_core_size_m (scene_in_cell, mesh_tiles.h); the checks still see the
  /// whole window. 0: the whole scene.
  double mesh_core_size_m = 0.0;
  long long mesh_core_column = 0, mesh_core_row = 0;
  /// Also NAME.carla.tar.gz: the package CARLA's `make import` ingests (export/carla_package.h),
  /// of NAME.xodr and NAME.fbx, or of the FBX tiles when mesh_tile_size_m > 0 (CARLA's large
  /// map). Needs the xodr and mesh outputs with the fbx format, a name CARLA takes and a tile
  /// size of whole metres up to 2000: otherwise build() throws OptionError before any work.
  bool carla_package = false;
  /// Output `sight`: every lane's sight distance on the scene (relief/sight/sight_distance.h).
  SightOptions sight;
  /// Region tiles (relief/tiles): called once the elevation is sampled, returns what the fit
  /// holds (ProfileFitOptions::holds, which it replaces); and called once the road model is built
  /// with the network, the fit and the model (relief's fit only). Unset: neither.
  std::function<FitHolds(const RoadNetwork&, const std::vector<RoadProfile>& raw)> hold_profiles;
  std::function<void(const RoadNetwork&, const ProfileFitResult&, const RoadModel&)> fitted;
  /// Region tiles: called once the scene is built (before its files are written), with the model
  /// it was built from. Unset: not called.
  std::function<void(const RoadModel&, const Scene&)> meshed;
};

struct BuildResult {
  RunReport report;                            ///< what report.json says
  std::vector<std::filesystem::path> written;  ///< final paths of the outputs
};

/// Runs the whole job. Outputs are written to temporaries and renamed only when everything
/// succeeded: a failed run leaves no output. Throws IoError, InvalidInput (incl.
/// CoverageError), ProjectionError with messages that name the file and the problem;
/// OptionError right after reading the roads when the sampling options would take more
/// samples than sampling.max_samples (check_sample_budget), or a spacing that is not > 0.
/// `diagnostics` collects data defects; `progress` is told each stage.
[[nodiscard]] BuildResult build(const BuildOptions& options, Diagnostics& diagnostics,
                                const ProgressFn& progress = {});

/// "sf-potrero" for "…/sf-potrero.osm.gz" (all of .osm, .osm.gz, .osm.bz2, .osm.pbf, .pbf).
[[nodiscard]] std::string default_name(const std::filesystem::path& osm_path);

}  // namespace relief
