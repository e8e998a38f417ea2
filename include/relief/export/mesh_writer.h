#pragma once
// Writing and reading 3D scenes: glTF 2.0 binary (.glb), Wavefront OBJ (+ .mtl) and binary
// FBX 7.4. Vertices are relief's local frame (metres) converted to float only here (the same
// float values in every format; half a float step is 0.24 mm at 4 km from the origin); the
// georeference (frame PROJ string, origin) goes into the file's metadata where the format has
// any. Axes: every file is written Y-up, right-handed, metres (glTF's convention; OBJ and FBX
// declare/assume the same), i.e. file (x, y, z) = local (x, z, -y); readers convert back.
// relief writes all three itself (Debian's assimp 5.2.5 writes corrupt binary FBX, takes
// seconds on a city's OBJ and 0.7 s on its glTF, and writes no glTF extras); assimp reads them
// back and stays behind this interface (src/export/).
//
// Metadata: the writer adds "relief:crs" (frame CRS), "relief:origin" ("x y", the frame origin
// in CRS metres) and "relief:proj" (GeoFrame::proj_string()) to MeshScene::metadata (entries of
// the scene override these). Where it goes:
//   .glb  glTF "extras" of the asset and of the root node (Blender shows the root node's as
//         custom properties of its empty).
//   .obj  comment lines "# relief-metadata <key>\t<value>" before the first statement.
//   .fbx  user properties (KString, flag "U") of every Model and of the document SceneInfo;
//         Blender shows them as object custom properties.
//
// Counts through read_mesh_file (measured with assimp 5.2.5): triangles, their order, corner
// order (winding) and the set of unique positions survive every format; vertex counts survive
// .glb only. assimp's OBJ and FBX importers make one vertex per triangle corner (3 x triangles).
// The OBJ writer also shares equal positions between meshes in its "v" list (Blender's importer
// gives each object back only the vertices it uses, so Blender's counts equal relief's for all
// three formats).

#include <filesystem>
#include <functional>
#include <optional>
#include <ostream>
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

/// Encodes `scene` as `base_name` + extension(format); OBJ also yields `base_name`.mtl (and the
/// .obj's "mtllib" names it). One mesh per TriangleMesh (name kept; in OBJ an "o" and a "g"
/// statement of that name), one material per SurfaceKind used (named "Road", "Marking",
/// "Sidewalk", "Shoulder", "Junction", "Terrain", distinct diffuse colours), normals and UVs
/// when present. Equal scenes give equal bytes. Throws InvalidInput for an index out of range,
/// ProjectionError when the frame's CRS is unknown and metadata has no "relief:proj".
[[nodiscard]] std::vector<EncodedFile> encode_mesh_scene(const MeshScene& scene, MeshFormat format,
                                                         const std::string& base_name);

/// Receives one file of a scene being written: its name (no directory) and a function that
/// writes its bytes to a stream.
using MeshFileSink =
    std::function<void(const std::string& filename, const std::function<void(std::ostream&)>& write)>;

/// Writes `scene` as encode_mesh_scene encodes it, each file through `sink`: the OBJ text is
/// streamed (never whole in memory), the binary formats are encoded first. Throws as
/// encode_mesh_scene.
void write_mesh_scene(const MeshScene& scene, MeshFormat format, const std::string& base_name,
                      const MeshFileSink& sink);

/// One vehicle of a replay: a box of its size, posed at its keys (local frame).
struct ReplayKey {
  double t_s = 0.0;          ///< time of the key, seconds (>= 0, strictly increasing)
  Vec3 position;             ///< the point under the body's centre on the surface
  double heading_rad = 0.0;  ///< counter-clockwise from +x
  double pitch_rad = 0.0;    ///< nose up positive
  double roll_rad = 0.0;     ///< right side down positive
};
struct ReplayTrack {
  std::string name;  ///< the vehicle's id
  double length_m = 4.5, width_m = 1.8, height_m = 1.5;
  std::vector<ReplayKey> keys;
  double hide_after_s = 0.0;  ///< the box disappears at this time (after the last key)
};

/// A replay as glTF binary: `scene` (as encode_mesh_scene writes it) plus every track as a box
/// node (material "Vehicle") with glTF node animation "replay": translation and rotation
/// LINEAR between the keys, a STEP scale that shows the box from its first key until
/// hide_after_s, so that any glTF viewer plays the traffic over the surface. Tracks without
/// keys are left out. Throws InvalidInput for keys out of order or a time < 0, a hide time not
/// after the last key, or a size that is not > 0.
[[nodiscard]] std::string encode_replay_glb(const MeshScene& scene, const std::vector<ReplayTrack>& tracks);

/// Reads any mesh file assimp can import (.glb, .gltf, .obj, .fbx, .ply, .stl, ...) back into
/// relief's axes, taking every file as Y-up (assimp's convention; relief's files are): one
/// TriangleMesh per mesh reference of a node, in world coordinates (node transforms applied),
/// named after the mesh (else its node), SurfaceKind from the material name (road when unknown).
/// Polygons are triangulated, vertices never joined (see above for the counts per format);
/// points and lines are dropped. Metadata: the string entries of the scene and of its nodes
/// (without assimp's own "SourceAsset_*" and FBX "UserProperties") and the OBJ comments above;
/// `frame` is restored from "relief:crs" and "relief:origin" when both are present.
/// Files relief wrote come back in the local frame with their metadata.
/// Throws IoError naming the file and assimp's reason.
[[nodiscard]] MeshScene read_mesh_file(const std::filesystem::path& path);

}  // namespace relief
