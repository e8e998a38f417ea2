#pragma once
// glTF 2.0 binary (.glb) of a scene already in the file's axes (fbx_scene_writer.h's SceneDesc):
// one node per mesh under a root node "relief", one triangle primitive per mesh (POSITION with
// min/max, NORMAL, TEXCOORD_0 with v flipped as glTF wants, uint32 indices), one metallic-roughness material
// per surface type (base colour = the diffuse colour, metallic 0), and the metadata as extras of the asset
// and of the root node (assimp and Blender read the latter back as node metadata / custom
// properties). Written directly: assimp 5.2's exporter took 0.7 s on the NE city, wrote no
// extras and listed extensions it did not use.

#include <string>

#include "export/fbx_scene_writer.h"

namespace relief {

[[nodiscard]] std::string encode_glb(const fbx::SceneDesc& scene);

}  // namespace relief
