#include "export/fbx_scene_writer.h"

#include <gtest/gtest.h>

#include <fstream>
#include <set>

#include "relief/core/errors.h"
#include "relief/export/mesh_writer.h"
#include "support/test_data.h"

namespace relief::fbx {
namespace {

// A 2 x 1 m rectangle at height 3 (Y up in the file), two triangles on four vertices.
MeshDesc rectangle(const std::string& name, std::size_t material) {
  MeshDesc m;
  m.name = name;
  m.positions = {{0.0f, 3.0f, 0.0f}, {2.0f, 3.0f, 0.0f}, {2.0f, 3.0f, -1.0f}, {0.0f, 3.0f, -1.0f}};
  m.triangles = {{{0, 1, 2}}, {{0, 2, 3}}};
  m.normals.assign(4, {0.0f, 1.0f, 0.0f});
  m.uvs = {{0.0f, 0.0f}, {1.0f, 0.0f}, {1.0f, 1.0f}, {0.0f, 1.0f}};
  m.material = material;
  return m;
}

// One triangle of the second material.
MeshDesc triangle(const std::string& name) {
  MeshDesc m;
  m.name = name;
  m.positions = {{10.0f, 0.0f, 0.0f}, {11.0f, 0.0f, 0.0f}, {10.0f, 0.0f, -1.0f}};
  m.triangles = {{{0, 1, 2}}};
  m.material = 1;
  return m;
}

SceneDesc two_mesh_scene() {
  SceneDesc scene;
  scene.materials = {{"Road", {0.2f, 0.2f, 0.2f}}, {"Terrain", {0.4f, 0.5f, 0.3f}}};
  scene.meshes = {rectangle("Deck", 0), triangle("Ground")};
  scene.user_properties = {{"relief:crs", "EPSG:32610"}};
  return scene;
}

std::filesystem::path write(const std::string& bytes, const std::string& name) {
  const auto path = test::scratch_dir("fbx_scene_writer") / name;
  std::ofstream(path, std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  return path;
}

const TriangleMesh& mesh_named(const MeshScene& scene, const std::string& name) {
  for (const TriangleMesh& m : scene.meshes)
    if (m.name == name) return m;
  throw std::out_of_range("no mesh " + name);
}

// assimp reads the file back: each mesh with its triangles, one vertex per triangle corner (its
// FBX importer does not share them), the rectangle's four corners in relief's axes (z up: the
// file's y), the material's surface kind and the user property.
TEST(FbxSceneWriter, AssimpReadsBackMeshesCornersMaterialsAndProperties) {
  const MeshScene back = read_mesh_file(write(encode_scene(two_mesh_scene()), "two.fbx"));
  ASSERT_EQ(back.meshes.size(), 2u);
  const TriangleMesh& deck = mesh_named(back, "Deck");
  EXPECT_EQ(deck.triangles.size(), 2u);
  EXPECT_EQ(deck.vertices.size(), 6u);
  EXPECT_EQ(deck.kind, SurfaceKind::road);
  std::set<std::array<double, 3>> corners;
  for (const Vec3& v : deck.vertices) corners.insert({v.x(), v.y(), v.z()});
  EXPECT_EQ(corners, (std::set<std::array<double, 3>>{
                         {0.0, 0.0, 3.0}, {2.0, 0.0, 3.0}, {2.0, 1.0, 3.0}, {0.0, 1.0, 3.0}}));
  ASSERT_EQ(deck.uvs.size(), deck.vertices.size());
  const TriangleMesh& ground = mesh_named(back, "Ground");
  EXPECT_EQ(ground.triangles.size(), 1u);
  EXPECT_EQ(ground.vertices.size(), 3u);
  EXPECT_EQ(ground.kind, SurfaceKind::terrain);
  EXPECT_EQ(back.metadata.at("relief:crs"), "EPSG:32610");
}

TEST(FbxSceneWriter, EqualScenesGiveEqualBytes) {
  EXPECT_EQ(encode_scene(two_mesh_scene()), encode_scene(two_mesh_scene()));
  SceneDesc other = two_mesh_scene();
  other.meshes[0].positions[0][1] = 3.5f;
  EXPECT_NE(encode_scene(other), encode_scene(two_mesh_scene()));
}

TEST(FbxSceneWriter, MaterialIndexOutOfRangeIsInvalidInput) {
  SceneDesc scene = two_mesh_scene();
  scene.meshes[1].material = 2;
  EXPECT_THROW((void)encode_scene(scene), InvalidInput);
}

}  // namespace
}  // namespace relief::fbx
