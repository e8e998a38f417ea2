#include "relief/export/carla_package.h"

#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <gtest/gtest.h>
#include <assimp/Importer.hpp>
#include <nlohmann/json.hpp>

#include <cstring>
#include <fstream>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "relief/core/errors.h"
#include "relief/geometry/mesh_tiles.h"
#include "support/mesh_grid.h"
#include "support/tar_reader.h"
#include "support/test_data.h"

namespace relief {
namespace {

// A 2 x 2 grid of 10 m squares with its south-west corner at (x0, y0), at heights that tell
// the vertices apart.
TriangleMesh patch(const std::string& name, SurfaceKind kind, double x0, double y0) {
  TriangleMesh m;
  m.name = name;
  m.kind = kind;
  test::add_grid(m, 0.0, 0.0, 2, 2, 0.0);
  for (Vec3& v : m.vertices) v = Vec3(x0 + 10.0 * v.x(), y0 + 10.0 * v.y(), 30.0 + v.x() + 0.5 * v.y());
  m.normals = vertex_normals(m);
  return m;
}

// Roads, marks and terrain over (0..20, 0..20) m and terrain over (100..120, 100..120) m.
MeshScene test_scene() {
  MeshScene s;
  s.frame = GeoFrame("EPSG:32610", Vec2(551000.0, 4180000.0));
  s.meshes.push_back(patch("Road_Road", SurfaceKind::road, 0.0, 0.0));
  s.meshes.push_back(patch("Road_Marking", SurfaceKind::marking, 0.0, 0.0));
  for (Vec3& v : s.meshes.back().vertices) v.z() += 0.005;
  s.meshes.push_back(patch("Road_Sidewalk", SurfaceKind::sidewalk, 0.0, 0.0));
  for (Vec3& v : s.meshes.back().vertices) v.z() += 0.15;
  TriangleMesh terrain = patch("Terrain", SurfaceKind::terrain, 100.0, 100.0);
  s.meshes.push_back(std::move(terrain));
  s.metadata["relief:proj"] = s.frame.proj_string();
  return s;
}

constexpr char kXodr[] = "<?xml version=\"1.0\"?>\n<OpenDRIVE/>\n";

CarlaPackageInput standard_input(const std::string& name = "hill") {
  CarlaPackageInput in;
  in.map_name = name;
  in.xodr = kXodr;
  in.fbx_files = encode_mesh_scene(test_scene(), MeshFormat::fbx, name);
  in.mtime_s = 1700000000;
  return in;
}

// The scene in 100 m tiles: (0, 0) and (1, 1) hold triangles, (1, 0) and (0, 1) none.
CarlaPackageInput tiled_input() {
  CarlaPackageInput in;
  in.map_name = "hill";
  in.xodr = kXodr;
  in.tile_size_m = 100;
  for (const SceneTile& t : split_into_tiles(test_scene(), 100.0)) {
    const std::string base = "hill_Tile_" + std::to_string(t.x) + "_" + std::to_string(t.y);
    for (EncodedFile& f : encode_mesh_scene(t.scene, MeshFormat::fbx, base))
      in.fbx_files.push_back(std::move(f));
  }
  return in;
}

using test::gunzip;
using test::read_tar;
using test::TarEntry;

std::map<std::string, TarEntry> by_path(const std::vector<TarEntry>& entries) {
  std::map<std::string, TarEntry> m;
  for (const TarEntry& e : entries) m[e.path] = e;
  return m;
}

// The file a JSON path names, relative to the package's folder (where NAME.json lies).
std::string resolve(const std::string& root, const std::string& relative) {
  EXPECT_TRUE(relative.starts_with("./")) << relative;
  return root + relative.substr(2);
}

// --- standard map ---------------------------------------------------------------------------

// The JSON holds what tuto_M_manual_map_package.md documents and Import.py reads for a
// standard map: maps[{name, source, use_carla_materials, xodr}], props [].
TEST(CarlaPackage, StandardMapJsonHasEveryKeyImportPyReads) {
  const nlohmann::json j = nlohmann::json::parse(carla_package_json(standard_input()));
  ASSERT_TRUE(j.is_object());
  EXPECT_EQ(j.size(), 2u);
  ASSERT_TRUE(j["props"].is_array());
  EXPECT_TRUE(j["props"].empty());
  ASSERT_TRUE(j["maps"].is_array());
  ASSERT_EQ(j["maps"].size(), 1u);
  const nlohmann::json& map = j["maps"][0];
  EXPECT_EQ(map.size(), 4u) << map.dump();
  EXPECT_EQ(map["name"], "hill");
  EXPECT_EQ(map["source"], "./hill/hill.fbx");
  EXPECT_EQ(map["xodr"], "./hill/hill.xodr");
  ASSERT_TRUE(map["use_carla_materials"].is_boolean());
  EXPECT_TRUE(map["use_carla_materials"].get<bool>());
  EXPECT_FALSE(map.contains("tiles"));
}

// The archive is a gzip of a POSIX tar: the package folder, NAME.json in it, the map folder
// with NAME.fbx and NAME.xodr, byte for byte what went in; every path of the JSON is in it.
TEST(CarlaPackage, StandardArchiveHoldsEveryFileTheJsonNames) {
  const CarlaPackageInput in = standard_input();
  const std::string packed = encode_carla_package(in);
  ASSERT_GE(packed.size(), 18u);
  EXPECT_EQ(static_cast<unsigned char>(packed[0]), 0x1f);  // gzip magic
  EXPECT_EQ(static_cast<unsigned char>(packed[1]), 0x8b);
  const std::vector<TarEntry> entries = read_tar(gunzip(packed));
  std::vector<std::string> paths;
  for (const TarEntry& e : entries) paths.push_back(e.path);
  const std::vector<std::string> expected{"hill/", "hill/hill.json", "hill/hill/", "hill/hill/hill.fbx",
                                          "hill/hill/hill.xodr"};
  EXPECT_EQ(paths, expected);
  EXPECT_EQ(carla_package_entries(in), expected);
  const auto files = by_path(entries);
  for (const TarEntry& e : entries) {
    EXPECT_EQ(e.mtime, 1700000000) << e.path;
    EXPECT_EQ(e.type, e.path.ends_with("/") ? '5' : '0') << e.path;
    EXPECT_EQ(e.mode, e.path.ends_with("/") ? 0755u : 0644u) << e.path;
  }
  const nlohmann::json j = nlohmann::json::parse(files.at("hill/hill.json").bytes);
  EXPECT_EQ(files.at("hill/hill.json").bytes, carla_package_json(in));
  const std::string fbx = resolve("hill/", j["maps"][0]["source"]);
  const std::string xodr = resolve("hill/", j["maps"][0]["xodr"]);
  ASSERT_TRUE(files.contains(fbx)) << fbx;
  ASSERT_TRUE(files.contains(xodr)) << xodr;
  EXPECT_EQ(files.at(fbx).bytes, in.fbx_files[0].bytes);
  EXPECT_EQ(files.at(xodr).bytes, kXodr);
  // Import.py pairs a map's .xodr and .fbx by the map's name.
  EXPECT_EQ(std::filesystem::path(fbx).stem(), "hill");
  EXPECT_EQ(std::filesystem::path(xodr).stem(), "hill");
  // Equal inputs, equal bytes.
  EXPECT_EQ(encode_carla_package(in), packed);
}

// The FBX in the package, imported with assimp: the meshes under the names CARLA's import maps
// to its tags and materials, the vertices in relief's local frame, and the file's axis system
// and unit as Unreal's FBX import converts them (bConvertScene, bConvertSceneUnit in
// Import.py): Y up, front +Z, coord +X (FBX's right-handed "Y-up" system) and 100 cm per unit,
// i.e. metres. Unreal turns that into its Z-up left-handed centimetres, where a point at local
// (x, y, z) lands at 100 * (x, -y, z): the place CARLA gives OpenDRIVE's (x, y, z).
TEST(CarlaPackage, FbxInsideReimportsWithAssimpInMetresYUp) {
  const CarlaPackageInput in = standard_input();
  const auto files = by_path(read_tar(gunzip(encode_carla_package(in))));
  const std::filesystem::path fbx = test::scratch_dir("carla_package_fbx") / "hill.fbx";
  {
    std::ofstream out(fbx, std::ios::binary);
    const std::string& bytes = files.at("hill/hill/hill.fbx").bytes;
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  }
  const MeshScene back = read_mesh_file(fbx);
  const MeshScene scene = test_scene();
  std::set<std::string> names;
  for (const TriangleMesh& m : back.meshes) names.insert(m.name);
  EXPECT_EQ(names, (std::set<std::string>{"Road_Road", "Road_Marking", "Road_Sidewalk", "Terrain"}));
  for (const TriangleMesh& want : scene.meshes) {
    SCOPED_TRACE(want.name);
    const auto got = std::find_if(back.meshes.begin(), back.meshes.end(),
                                  [&](const TriangleMesh& m) { return m.name == want.name; });
    ASSERT_NE(got, back.meshes.end());
    ASSERT_EQ(got->triangles.size(), want.triangles.size());
    // assimp gives one vertex per corner, in the order of the triangles' corners.
    for (std::size_t t = 0; t < want.triangles.size(); ++t)
      for (int c = 0; c < 3; ++c) {
        const Vec3 a = want.vertices[want.triangles[t][c]];
        const Vec3 b = got->vertices[got->triangles[t][c]];
        EXPECT_NEAR((a - b).norm(), 0.0, 1e-4) << "triangle " << t << " corner " << c;
      }
  }

  Assimp::Importer importer;
  const aiScene* s = importer.ReadFile(fbx.string(), 0);
  ASSERT_NE(s, nullptr) << importer.GetErrorString();
  ASSERT_NE(s->mMetaData, nullptr);
  const auto int_of = [&](const char* key) {
    int v = -99;
    EXPECT_TRUE(s->mMetaData->Get(key, v)) << key;
    return v;
  };
  EXPECT_EQ(int_of("UpAxis"), 1);  // Y
  EXPECT_EQ(int_of("UpAxisSign"), 1);
  EXPECT_EQ(int_of("FrontAxis"), 2);  // Z
  EXPECT_EQ(int_of("FrontAxisSign"), 1);
  EXPECT_EQ(int_of("CoordAxis"), 0);  // X
  EXPECT_EQ(int_of("CoordAxisSign"), 1);
  float unit_cm = 0.0f;  // assimp keeps it as a float
  ASSERT_TRUE(s->mMetaData->Get("UnitScaleFactor", unit_cm));
  EXPECT_EQ(unit_cm, 100.0f);
  // The first Road_Road vertex in the file's own axes, then as Unreal converts it: the Y-up
  // system's up (+Y) becomes Unreal's +Z and its front (+Z) Unreal's -Y before the mirror to
  // left-handed (y -> -y), times the unit.
  const aiMesh* road = nullptr;
  for (unsigned i = 0; i < s->mNumMeshes; ++i)
    if (std::string(s->mMeshes[i]->mName.C_Str()) == "Road_Road") road = s->mMeshes[i];
  ASSERT_NE(road, nullptr);
  const aiVector3D f = road->mVertices[0];  // corner 0 of triangle 0
  const Vec3 local = scene.meshes[0].vertices[scene.meshes[0].triangles[0][0]];
  const Vec3 unreal_cm = double{unit_cm} * Vec3(f.x, f.z, f.y);  // (x, -(-z), y): front -> -Y, mirrored
  const Vec3 carla_cm = 100.0 * Vec3(local.x(), -local.y(), local.z());
  EXPECT_NEAR((unreal_cm - carla_cm).norm(), 0.0, 0.01);
}

// --- large map ------------------------------------------------------------------------------

// content_authoring_large_maps.md and Import.py: the map has "tile_size" (m, a number) and
// "tiles" (every NAME_Tile_X_Y.fbx) instead of "source"; the files lie beside NAME.json.
TEST(CarlaPackage, LargeMapJsonListsTheTilesAndTheirSize) {
  const CarlaPackageInput in = tiled_input();
  ASSERT_EQ(in.fbx_files.size(), 2u);
  const nlohmann::json j = nlohmann::json::parse(carla_package_json(in));
  ASSERT_EQ(j["maps"].size(), 1u);
  const nlohmann::json& map = j["maps"][0];
  EXPECT_EQ(map.size(), 5u) << map.dump();
  EXPECT_EQ(map["name"], "hill");
  EXPECT_EQ(map["xodr"], "./hill.xodr");
  EXPECT_TRUE(map["use_carla_materials"].get<bool>());
  ASSERT_TRUE(map["tile_size"].is_number_integer());
  EXPECT_EQ(map["tile_size"].get<int>(), 100);
  EXPECT_FALSE(map.contains("source"));
  EXPECT_EQ(map["tiles"], nlohmann::json::parse(R"(["./hill_Tile_0_0.fbx", "./hill_Tile_1_1.fbx"])"));
  EXPECT_TRUE(j["props"].is_array() && j["props"].empty());

  const auto files = by_path(read_tar(gunzip(encode_carla_package(in))));
  const std::vector<std::string> expected{"hill/", "hill/hill.json", "hill/hill.xodr",
                                          "hill/hill_Tile_0_0.fbx", "hill/hill_Tile_1_1.fbx"};
  EXPECT_EQ(carla_package_entries(in), expected);
  EXPECT_EQ(files.size(), expected.size());
  EXPECT_EQ(files.at(resolve("hill/", map["xodr"])).bytes, kXodr);
  for (const auto& tile : map["tiles"]) {
    const std::string path = resolve("hill/", tile);
    ASSERT_TRUE(files.contains(path)) << path;
    const std::filesystem::path file =
        test::scratch_dir("carla_package_tiles") / std::filesystem::path(path).filename();
    {
      std::ofstream out(file, std::ios::binary);
      out.write(files.at(path).bytes.data(), static_cast<std::streamsize>(files.at(path).bytes.size()));
    }
    const MeshScene back = read_mesh_file(file);
    std::set<std::string> names;
    for (const TriangleMesh& m : back.meshes) names.insert(m.name);
    // Tile (0, 0) holds the roads, tile (1, 1) the far terrain patch.
    if (path.ends_with("_0_0.fbx"))
      EXPECT_EQ(names, (std::set<std::string>{"Road_Road", "Road_Marking", "Road_Sidewalk"}));
    else
      EXPECT_EQ(names, (std::set<std::string>{"Terrain"}));
  }
}

// CARLA's cook stops a row at its first missing tile: the package lists the gaps.
TEST(CarlaPackage, GapsInTheTileGridAreListed) {
  EXPECT_EQ(carla_tile_grid_gaps(tiled_input()), (std::vector<std::string>{"1 0", "0 1"}));
  EXPECT_TRUE(carla_tile_grid_gaps(standard_input()).empty());
  CarlaPackageInput one = tiled_input();
  one.fbx_files.resize(1);  // (0, 0) alone: a whole grid
  EXPECT_TRUE(carla_tile_grid_gaps(one).empty());
}

// A 64-character name makes paths over ustar's 100-byte name field: the prefix field holds
// the folders, and the archive reads back with the full paths.
TEST(CarlaPackage, LongPathsGoIntoTheUstarPrefix) {
  const std::string name(64, 'n');
  const CarlaPackageInput in = standard_input(name);
  const auto files = by_path(read_tar(gunzip(encode_carla_package(in))));
  const std::string xodr = name + "/" + name + "/" + name + ".xodr";
  ASSERT_GT(xodr.size(), 100u);
  ASSERT_TRUE(files.contains(xodr));
  EXPECT_EQ(files.at(xodr).bytes, kXodr);
}

TEST(CarlaPackage, ThrowsInvalidInputForWhatCarlaCannotImport) {
  CarlaPackageInput bad = standard_input();
  bad.map_name = "sf.potrero";  // '.' is not allowed in Unreal package paths
  EXPECT_THROW((void)encode_carla_package(bad), InvalidInput);
  EXPECT_FALSE(is_valid_carla_map_name("sf potrero"));
  EXPECT_FALSE(is_valid_carla_map_name(""));
  EXPECT_FALSE(is_valid_carla_map_name(std::string(65, 'n')));
  EXPECT_TRUE(is_valid_carla_map_name("sf-potrero_2"));

  bad = standard_input();
  bad.fbx_files[0].filename = "other.fbx";  // not the map's name
  EXPECT_THROW((void)encode_carla_package(bad), InvalidInput);
  bad = standard_input();
  bad.fbx_files.clear();
  EXPECT_THROW((void)encode_carla_package(bad), InvalidInput);
  bad = standard_input();
  bad.mtime_s = -1;
  EXPECT_THROW((void)encode_carla_package(bad), InvalidInput);

  bad = tiled_input();
  bad.tile_size_m = kCarlaMaxTileSizeM + 1;
  EXPECT_THROW((void)encode_carla_package(bad), InvalidInput);
  bad = tiled_input();
  bad.fbx_files[1].filename = "hill_Tile_1.fbx";
  EXPECT_THROW((void)carla_package_json(bad), InvalidInput);
  bad = tiled_input();
  bad.fbx_files[1].filename = "hill_Tile_0_0.fbx";  // twice
  EXPECT_THROW((void)carla_package_entries(bad), InvalidInput);
  bad = tiled_input();
  bad.fbx_files[1].filename = "hill_Tile_-1_0.fbx";
  EXPECT_THROW((void)carla_tile_grid_gaps(bad), InvalidInput);
}

}  // namespace
}  // namespace relief
