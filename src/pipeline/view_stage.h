#pragma once
// The interactive view part of `build` (output `view`, relief/viewer/view_writer.h): the scene's
// tiles as soon as the scene is built (view/tile_X_Y.js), then, once the gates are known,
// view/index.js and view.html.

#include <filesystem>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include "pipeline/mesh_stage.h"
#include "pipeline/stages.h"
#include "relief/core/atomic_file.h"
#include "relief/viewer/view_writer.h"

namespace relief {

/// The folder this run created for the view, removed again if it is still empty when the
/// stage ends (a failed run's temporaries are gone: nothing is left behind).
class CreatedFolder {
 public:
  explicit CreatedFolder(std::filesystem::path path = {}) : path_(std::move(path)) {}
  CreatedFolder(CreatedFolder&& other) noexcept : path_(std::exchange(other.path_, {})) {}
  CreatedFolder& operator=(CreatedFolder&& other) noexcept {
    std::swap(path_, other.path_);
    return *this;
  }
  CreatedFolder(const CreatedFolder&) = delete;
  CreatedFolder& operator=(const CreatedFolder&) = delete;
  ~CreatedFolder() {
    std::error_code ignored;
    if (!path_.empty()) std::filesystem::remove(path_, ignored);  // only an empty folder goes
  }

 private:
  std::filesystem::path path_;
};

/// The tiles of `built` into `files` (under out_dir/view, created here); what the index needs
/// later is returned.
struct ViewStage {
  ViewTiles tiles;
  std::vector<std::pair<int, Vec3>> failed_junctions;
  CreatedFolder folder;
};
[[nodiscard]] ViewStage write_view_tiles(const MeshStageInput& in, const Scene& built, OutputSet& files,
                                         StageTimer& timer, std::vector<std::filesystem::path>& written);

/// view/index.js and view.html into `files`; appends their paths and view.html's name.
void write_view_page(const BuildOptions& options, const ViewStage& stage, ViewIndexInput input,
                     OutputSet& files, StageTimer& timer, std::vector<std::filesystem::path>& written,
                     std::vector<std::string>& names);

}  // namespace relief
