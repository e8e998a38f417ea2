#pragma once
// A minimal FBX 7.4 scene over fbx_binary_writer.h: one Model + Geometry "Mesh" per mesh, one
// Lambert Material per material, connected to the scene root. Coordinates are written as given,
// declared Y-up, right-handed (front +Z, coord +X) and metres (UnitScaleFactor 100 cm), so that
// Blender, Unreal and the FBX SDK import them 1:1 in metres.

#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace relief::fbx {

struct MaterialDesc {
  std::string name;
  std::array<float, 3> diffuse_rgb{0.8f, 0.8f, 0.8f};  ///< linear 0..1
};

/// A triangle mesh already in the file's axes (Y up, metres). `normals` and `uvs` are empty or
/// one per position; `material` indexes SceneDesc::materials.
struct MeshDesc {
  std::string name;
  std::vector<std::array<float, 3>> positions;
  std::vector<std::array<std::uint32_t, 3>> triangles;
  std::vector<std::array<float, 3>> normals;
  std::vector<std::array<float, 2>> uvs;
  std::size_t material = 0;
};

struct SceneDesc {
  std::vector<MeshDesc> meshes;
  std::vector<MaterialDesc> materials;
  /// Written as user properties (KString, flag "U") of every Model and of the document's
  /// SceneInfo: Blender shows them as object custom properties, assimp as node metadata.
  std::vector<std::pair<std::string, std::string>> user_properties;
  std::string creator = "relief";
  /// Added to every position (file axes; whole metres): the file origin the positions are
  /// relative to (MeshScene::file_origin), zero for positions in the frame itself. The glb puts
  /// it in its root node's translation; FBX and OBJ write the sums, in double.
  std::array<double, 3> offset{0.0, 0.0, 0.0};
};

/// The binary FBX file. Deterministic: the creation time is fixed (1970-01-01 10:00, with the
/// matching FileId Blender uses), so equal scenes give equal bytes.
/// Throws InvalidInput when a material index is out of range.
[[nodiscard]] std::string encode_scene(const SceneDesc& scene);

}  // namespace relief::fbx
