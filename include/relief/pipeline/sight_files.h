#pragma once
// `relief sight`: the sight-distance pass on a built network, from its files: the OpenDRIVE
// (lanes, links, speeds, the frame) and the 3D scene (the obstacles), as `build` would run it.

#include <filesystem>
#include <string>
#include <vector>

#include "relief/export/sight_writer.h"

namespace relief {

struct SightFilesResult {
  SightSummary summary;
  std::vector<std::filesystem::path> written;  ///< NAME.sight.geojson, sight.json
};

/// Reads `xodr` and `scene` (any mesh file read_mesh_file reads; empty: NAME.glb beside the
/// .xodr), runs sight_distances with `options` (road classes: the OpenDRIVE road types) and
/// writes OUT/NAME.sight.geojson and OUT/sight.json (sight_summary_json), NAME the .xodr's stem,
/// both or neither. Throws IoError / InvalidInput naming the file when one cannot be read.
[[nodiscard]] SightFilesResult sight_from_files(const std::filesystem::path& xodr,
                                                std::filesystem::path scene,
                                                const std::filesystem::path& out_dir,
                                                const SightOptions& options);

}  // namespace relief
