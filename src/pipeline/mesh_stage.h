#pragma once
// The 3D scene part of `build`: road and junction surfaces, terrain conforming to them, the
// scene files (.glb, .obj + .mtl, .fbx) and mesh_report.json.

#include <filesystem>
#include <string>
#include <vector>

#include "pipeline/stages.h"
#include "relief/core/atomic_file.h"
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
/// for report.json; appends the paths written and their names.
[[nodiscard]] MeshSummary write_mesh_outputs(const MeshStageInput& in, const Scene& built, OutputSet& files,
                                             StageTimer& timer, std::vector<std::filesystem::path>& written,
                                             std::vector<std::string>& names);

}  // namespace relief
