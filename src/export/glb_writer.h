#pragma once
// glTF 2.0 binary (.glb) of a scene already in the file's axes (fbx_scene_writer.h's SceneDesc):
// one node per mesh under a root node "relief", one triangle primitive per mesh (POSITION with
// min/max, NORMAL, TEXCOORD_0 with v flipped as glTF wants, uint32 indices), one metallic-roughness material
// per surface type (base colour = the diffuse colour, metallic 0), and the metadata as extras of the asset
// and of the root node (assimp and Blender read the latter back as node metadata / custom
// properties). Written directly: assimp 5.2's exporter took 0.7 s on the NE city, wrote no
// extras and listed extensions it did not use.

#include <array>
#include <string>
#include <vector>

#include "export/fbx_scene_writer.h"

namespace relief {

/// A box animated over time, in the file's axes: a node per track under the root, posed by
/// LINEAR translation and rotation channels, shown by a STEP scale channel (0 before its first
/// key and after its last); a child node scales one shared unit box (material `material`) to
/// `size` and lifts it by half its height, so the node's position is the box's bottom centre.
struct GlbTrack {
  std::string name;
  std::array<float, 3> size{};  ///< along the node's x, y (up) and z
  std::vector<float> times;     ///< seconds, strictly increasing, >= 0
  std::vector<std::array<float, 3>> translations;
  std::vector<std::array<float, 4>> rotations;  ///< unit quaternions (x, y, z, w)
  float hide_after_s = 0.0f;                    ///< the box disappears at this time (> the last key)
};

/// The scene, and the tracks (with the box mesh and one animation, "replay") when there are any.
[[nodiscard]] std::string encode_glb(const fbx::SceneDesc& scene, const std::vector<GlbTrack>& tracks = {},
                                     std::size_t track_material = 0);

}  // namespace relief
