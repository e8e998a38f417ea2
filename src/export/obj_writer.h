#pragma once
// Wavefront OBJ + MTL text of a scene already in the file's axes (fbx_scene_writer.h's
// SceneDesc): one "o"/"g" object per mesh, "usemtl" per material, v/vt/vn, metadata as
// "# relief-metadata key<TAB>value" comments. Written directly because assimp's OBJ exporter
// takes seconds on a city (it de-duplicates every position through a map).

#include <ostream>
#include <string>

#include "export/fbx_scene_writer.h"

namespace relief {

/// Writes the .obj to `out` in pieces of about 1 MB: a city's OBJ text is hundreds of MB
/// (central Portland's 309 MB) and is never whole in memory. `mtl_name` is the file name the
/// mtllib line refers to; `metadata_lines` the comment lines to put in the header (each ending
/// in '\n').
void write_obj(const fbx::SceneDesc& scene, const std::string& mtl_name, const std::string& metadata_lines,
               std::ostream& out);

/// The .mtl: one material per entry of the scene's.
[[nodiscard]] std::string encode_mtl(const fbx::SceneDesc& scene);

}  // namespace relief
