#pragma once
// Wavefront OBJ + MTL text of a scene already in the file's axes (fbx_scene_writer.h's
// SceneDesc): one "o"/"g" object per mesh, "usemtl" per material, v/vt/vn, metadata as
// "# relief-metadata key<TAB>value" comments. Written directly because assimp's OBJ exporter
// takes seconds on a city (it de-duplicates every position through a map).

#include <string>

#include "export/fbx_scene_writer.h"

namespace relief {

struct ObjText {
  std::string obj;
  std::string mtl;
};

/// `mtl_name` is the file name the .obj's mtllib line refers to; `metadata_lines` the comment
/// lines to put in the header (each ending in '\n').
[[nodiscard]] ObjText encode_obj(const fbx::SceneDesc& scene, const std::string& mtl_name,
                                 const std::string& metadata_lines);

}  // namespace relief
