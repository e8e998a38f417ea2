#pragma once
// The interactive view part of `build` (output `view`, relief/viewer/view_writer.h): the scene's
// tiles as soon as the scene is built (view/tile_X_Y.js), then, once the gates are known,
// view/index.js and view.html.

#include <filesystem>
#include <string>
#include <vector>

#include "pipeline/mesh_stage.h"
#include "pipeline/stages.h"
#include "relief/core/atomic_file.h"
#include "relief/viewer/view_writer.h"

namespace relief {

/// The tiles of `built` into `files` (under out_dir/view, created here); what the index needs
/// later is returned.
struct ViewStage {
  ViewTiles tiles;
  std::vector<std::pair<int, Vec3>> failed_junctions;
};
[[nodiscard]] ViewStage write_view_tiles(const MeshStageInput& in, const Scene& built, OutputSet& files,
                                         StageTimer& timer, std::vector<std::filesystem::path>& written);

/// view/index.js and view.html into `files`; appends their paths and view.html's name.
void write_view_page(const BuildOptions& options, const ViewStage& stage, ViewIndexInput input,
                     OutputSet& files, StageTimer& timer, std::vector<std::filesystem::path>& written,
                     std::vector<std::string>& names);

}  // namespace relief
