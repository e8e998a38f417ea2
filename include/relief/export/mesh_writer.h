#pragma once
// Writing and reading 3D scenes: glTF 2.0 binary (.glb), Wavefront OBJ (+ .mtl) and binary
// FBX 7.4. Vertices are relief's local frame (metres) converted to float only here; the
// georeference (frame PROJ string, origin) goes into the file's metadata where the format has
// any. Axes: every file is written Y-up, right-handed, metres (glTF's convention; OBJ and FBX
// declare/assume the same), i.e. file (x, y, z) = local (x, z, -y); readers convert back.
// assimp stays behind this interface (src/export/); the FBX bytes are relief's own writer
// because Debian's assimp 5.2.5 writes corrupt binary FBX.

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "relief/geometry/triangle_mesh.h"

namespace relief {

enum class MeshFormat { glb, obj, fbx };
[[nodiscard]] std::optional<MeshFormat> parse_mesh_format(std::string_view text);  ///< "glb", "obj", "fbx"
[[nodiscard]] std::string_view to_string(MeshFormat format);
[[nodiscard]] std::string_view extension(MeshFormat format);  ///< ".glb", ".obj", ".fbx"

/// One file of an encoded scene: its name (no directory) and its bytes.
struct EncodedFile {
  std::string filename;
  std::string bytes;
};

/// Encodes `scene` as `base_name` + extension(format); OBJ also yields `base_name`.mtl.
/// One mesh per TriangleMesh (name kept), one material per SurfaceKind used, normals and UVs
/// when present. Throws InvalidInput for an index out of range, IoError when assimp fails.
[[nodiscard]] std::vector<EncodedFile> encode_mesh_scene(const MeshScene& scene, MeshFormat format,
                                                         const std::string& base_name);

/// Reads any mesh file assimp can import (.glb, .gltf, .obj, .fbx, .ply, .stl, ...) back into
/// relief's axes: one TriangleMesh per mesh (polygons triangulated, no vertex joining, so the
/// counts are the file's). Files relief wrote come back in the local frame with their metadata.
/// Throws IoError naming the file and assimp's reason.
[[nodiscard]] MeshScene read_mesh_file(const std::filesystem::path& path);

}  // namespace relief
