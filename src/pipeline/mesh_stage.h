#pragma once
// The 3D scene part of `build`: road and junction surfaces, terrain conforming to them, the
// scene files (.glb, .obj + .mtl, .fbx) and mesh_report.json.

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "pipeline/stages.h"
#include "relief/core/atomic_file.h"
#include "relief/export/mesh_writer.h"
#include "relief/export/report_writer.h"
#include "relief/roads/road_model.h"
#include "relief/scene/scene.h"
#include "relief/terrain/dem_sampler.h"

namespace relief {

struct MeshStageInput {
  const BuildOptions& options;
  const RoadNetwork& network;
  const RoadModel& model;
  const DemSampler& dem;
  const std::string& name;
  Diagnostics& diagnostics;
};

/// Builds the meshes (without their checks, which write_mesh_outputs runs).
[[nodiscard]] Scene build_scene_stage(const MeshStageInput& in, StageTimer& timer);

/// The FBX files the CARLA package takes: NAME.fbx, or the tiles NAME_Tile_X_Y.fbx and, for the
/// tiles of the grid's rectangle without triangles (CARLA's cook stops a row at its first
/// missing tile), a placeholder each: one triangle named "Placeholder", 10 cm wide, at the
/// tile's centre 50 m under the scene's lowest point. The placeholders go into the package only.
struct CarlaFbx {
  std::vector<EncodedFile> files;
  std::vector<std::string> placeholders;  ///< "X Y" of the tiles given a placeholder
};

/// Writes the scene files and mesh_report.json of `built` into `files` and returns the summary
/// for report.json; appends the paths written and their names. With `carla_fbx`, also keeps
/// there the FBX files the CARLA package takes (the tiles when there are tiles, else NAME.fbx).
[[nodiscard]] MeshSummary write_mesh_outputs(const MeshStageInput& in, const Scene& built, OutputSet& files,
                                             StageTimer& timer, std::vector<std::filesystem::path>& written,
                                             std::vector<std::string>& names, CarlaFbx* carla_fbx = nullptr);

/// Writes NAME.carla.tar.gz of `xodr` and `fbx` into `files`, records it in `summary` and
/// reports the placeholder tiles (carla.tile_grid_gap).
void write_carla_package_output(const MeshStageInput& in, std::string xodr, CarlaFbx fbx,
                                std::int64_t mtime_s, OutputSet& files, StageTimer& timer,
                                MeshSummary& summary, std::vector<std::filesystem::path>& written,
                                std::vector<std::string>& names);

}  // namespace relief
