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

/// Writes the scene files and mesh_report.json of `built` into `files` and returns the summary
/// for report.json; appends the paths written and their names. With `carla_fbx`, also keeps
/// there the FBX files the CARLA package takes: the tiles when there are tiles, else NAME.fbx.
[[nodiscard]] MeshSummary write_mesh_outputs(const MeshStageInput& in, const Scene& built, OutputSet& files,
                                             StageTimer& timer, std::vector<std::filesystem::path>& written,
                                             std::vector<std::string>& names,
                                             std::vector<EncodedFile>* carla_fbx = nullptr);

/// Writes NAME.carla.tar.gz of `xodr` and `fbx` (write_mesh_outputs' carla_fbx) into `files`,
/// records it in `summary` and reports the gaps of a large map's tile grid (carla.tile_grid_gap).
void write_carla_package_output(const MeshStageInput& in, std::string xodr, std::vector<EncodedFile> fbx,
                                std::int64_t mtime_s, OutputSet& files, StageTimer& timer,
                                MeshSummary& summary, std::vector<std::filesystem::path>& written,
                                std::vector<std::string>& names);

}  // namespace relief
