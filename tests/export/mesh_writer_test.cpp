#include "relief/export/mesh_writer.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstring>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <numbers>
#include <set>

#include "relief/core/errors.h"
#include "relief/geometry/mesh_tiles.h"
#include "support/blender.h"
#include "support/test_data.h"

namespace relief {
namespace {

constexpr double kTolM = 1e-3;

// A unit square at height 2 m: 4 vertices, 2 triangles (counter-clockwise from above).
TriangleMesh unit_square(const std::string& name, SurfaceKind kind) {
  TriangleMesh m;
  m.name = name;
  m.kind = kind;
  m.vertices = {{0, 0, 2}, {1, 0, 2}, {1, 1, 2}, {0, 1, 2}};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  m.normals.assign(4, Vec3::UnitZ());
  m.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  return m;
}

// An n x n grid of 10 m cells far from the origin (x ~ 4.5 km, y ~ -3.2 km, z ~ 30 m), so that
// float rounding at a realistic magnitude (half a float step at 4.5 km: 0.24 mm) is part of
// the round trip.
TriangleMesh grid(const std::string& name, SurfaceKind kind, int n) {
  TriangleMesh m;
  m.name = name;
  m.kind = kind;
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) {
      const double x = 4500.37 + 10.0 * i;
      const double y = -3200.61 + 10.0 * j;
      m.vertices.emplace_back(x, y, 30.0 + 0.3 * i + 0.01 * i * j);
      m.uvs.emplace_back(static_cast<double>(i) / n, static_cast<double>(j) / n);
    }
  }
  const auto at = [n](int i, int j) { return static_cast<std::uint32_t>(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      m.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      m.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  }
  m.normals = vertex_normals(m);
  return m;
}

MeshScene test_scene() {
  MeshScene s;
  s.frame = GeoFrame("EPSG:32610", Vec2(551000.0, 4180000.0));
  s.meshes.push_back(unit_square("Road_Road", SurfaceKind::road));
  s.meshes.push_back(unit_square("Road_Marking", SurfaceKind::marking));
  s.meshes.back().vertices[2].z() = 2.5;  // not a copy of Road_Road
  s.meshes.push_back(grid("Terrain", SurfaceKind::terrain, 10));
  s.metadata["relief:proj"] = s.frame.proj_string();
  s.metadata["relief:source"] = "unit test";
  return s;
}

std::filesystem::path write_files(const std::vector<EncodedFile>& files, const std::filesystem::path& dir) {
  for (const EncodedFile& f : files) {
    std::ofstream out(dir / f.filename, std::ios::binary);
    out.write(f.bytes.data(), static_cast<std::streamsize>(f.bytes.size()));
  }
  return dir / files.front().filename;
}

const TriangleMesh* find_mesh(const MeshScene& scene, const std::string& name) {
  for (const TriangleMesh& m : scene.meshes) {
    if (m.name == name) return &m;
  }
  return nullptr;
}

std::set<std::array<long long, 3>> unique_positions_mm(const TriangleMesh& m) {
  std::set<std::array<long long, 3>> out;
  for (const Vec3& v : m.vertices) {
    out.insert({std::llround(v.x() * 1000), std::llround(v.y() * 1000), std::llround(v.z() * 1000)});
  }
  return out;
}

// Round trip through a file: same names, triangle count, unique positions; each triangle the
// same corners in the same order (so the winding survives) within 1 mm; and the vertex count
// `expected_vertices(original)` (the importers differ: see mesh_writer.h).
void expect_round_trip(MeshFormat format,
                       const std::function<std::size_t(const TriangleMesh&)>& expected_vertices) {
  const MeshScene scene = test_scene();
  const auto dir = test::scratch_dir(std::string("mesh_writer_round_trip_") + std::string(to_string(format)));
  const auto path = write_files(encode_mesh_scene(scene, format, "scene"), dir);
  const MeshScene back = read_mesh_file(path);
  ASSERT_EQ(back.meshes.size(), scene.meshes.size());
  double max_error_m = 0.0;
  for (const TriangleMesh& original : scene.meshes) {
    SCOPED_TRACE(original.name);
    const TriangleMesh* read = find_mesh(back, original.name);
    ASSERT_NE(read, nullptr);
    EXPECT_EQ(read->kind, original.kind);
    EXPECT_EQ(read->vertices.size(), expected_vertices(original));
    ASSERT_EQ(read->triangles.size(), original.triangles.size());
    EXPECT_EQ(unique_positions_mm(*read), unique_positions_mm(original));
    for (std::size_t t = 0; t < original.triangles.size(); ++t) {
      for (int k = 0; k < 3; ++k) {
        const Vec3& a = original.vertices[original.triangles[t][k]];
        const Vec3& b = read->vertices[read->triangles[t][k]];
        max_error_m = std::max(max_error_m, (a - b).cwiseAbs().maxCoeff());
      }
    }
    ASSERT_EQ(read->normals.size(), read->vertices.size());
    for (std::size_t t = 0; t < original.triangles.size(); ++t) {
      const Vec3& a = original.normals[original.triangles[t][0]];
      const Vec3& b = read->normals[read->triangles[t][0]];
      EXPECT_NEAR((a - b).norm(), 0.0, 1e-4);
    }
  }
  EXPECT_LT(max_error_m, kTolM);
  EXPECT_EQ(back.metadata.at("relief:proj"), scene.metadata.at("relief:proj"));
  EXPECT_EQ(back.metadata.at("relief:source"), "unit test");
  EXPECT_EQ(back.frame.crs(), "EPSG:32610");
  EXPECT_NEAR(back.frame.origin().x(), 551000.0, 1e-9);
  EXPECT_NEAR(back.frame.origin().y(), 4180000.0, 1e-9);
}

TEST(MeshWriter, ParsesFormatNamesAndExtensions) {
  EXPECT_EQ(parse_mesh_format("glb"), MeshFormat::glb);
  EXPECT_EQ(parse_mesh_format("obj"), MeshFormat::obj);
  EXPECT_EQ(parse_mesh_format("fbx"), MeshFormat::fbx);
  EXPECT_EQ(parse_mesh_format("stl"), std::nullopt);
  EXPECT_EQ(to_string(MeshFormat::fbx), "fbx");
  EXPECT_EQ(extension(MeshFormat::glb), ".glb");
}

TEST(MeshWriter, ObjYieldsObjAndMtlThatReferencesIt) {
  const auto files = encode_mesh_scene(test_scene(), MeshFormat::obj, "roads");
  ASSERT_EQ(files.size(), 2u);
  EXPECT_EQ(files[0].filename, "roads.obj");
  EXPECT_EQ(files[1].filename, "roads.mtl");
  EXPECT_NE(files[0].bytes.find("\nmtllib roads.mtl\n"), std::string::npos);
  EXPECT_NE(files[1].bytes.find("newmtl Marking"), std::string::npos);
  EXPECT_NE(files[0].bytes.find("# relief-metadata relief:proj\t+proj=tmerc"), std::string::npos);
}

TEST(MeshWriter, EqualScenesGiveEqualBytes) {
  for (const MeshFormat f : {MeshFormat::glb, MeshFormat::obj, MeshFormat::fbx}) {
    const auto a = encode_mesh_scene(test_scene(), f, "x");
    const auto b = encode_mesh_scene(test_scene(), f, "x");
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i) EXPECT_EQ(a[i].bytes, b[i].bytes) << a[i].filename;
  }
}

TEST(MeshWriter, ThrowsInvalidInputForIndexOutOfRange) {
  MeshScene s = test_scene();
  s.meshes[0].triangles.push_back({0, 1, 4});
  for (const MeshFormat f : {MeshFormat::glb, MeshFormat::obj, MeshFormat::fbx}) {
    EXPECT_THROW((void)encode_mesh_scene(s, f, "bad"), InvalidInput);
  }
}

TEST(MeshWriter, ReadThrowsIoErrorNamingTheFile) {
  const auto dir = test::scratch_dir("mesh_writer_read_error");
  try {
    (void)read_mesh_file(dir / "missing.glb");
    FAIL() << "no exception";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("missing.glb"), std::string::npos) << e.what();
  }
  std::ofstream(dir / "garbage.fbx") << "not an fbx file";
  EXPECT_THROW((void)read_mesh_file(dir / "garbage.fbx"), IoError);
}

// glTF keeps the indexed vertices: every count round-trips.
TEST(MeshWriter, GlbRoundTripKeepsCountsPositionsAndMetadata) {
  expect_round_trip(MeshFormat::glb, [](const TriangleMesh& m) { return m.vertices.size(); });
}

// A strip of triangles 4 mm wide in 2 km tile (-68, -1) of a region, 135 km from the frame's
// origin, where a float step is 15.6 mm: written in the frame's coordinates the strip's sides
// collapse onto one line (the 2 000 km region's merge had 34 "self-intersecting" Road_Road pairs
// of such zero-area triangles). With the tile's file origin every format holds the positions to
// the quantum (2^-12 m); the .glb reads back exact to it, and a vertex two tiles share reads back
// with the same bits from both.
MeshScene far_strip(const std::optional<FileOrigin>& origin) {
  MeshScene s;
  s.frame = GeoFrame("EPSG:32610", Vec2(701044.0, 4180022.0));
  TriangleMesh m;
  m.name = "Road_Road";
  for (int i = 0; i <= 10; ++i) {
    m.vertices.emplace_back(-134594.3 + 0.3 * i, -320.37 - 1.625 * i, 300.0 + 0.01 * i);
    m.vertices.emplace_back(-134594.3 + 0.3 * i + 0.004, -320.37 - 1.625 * i, 300.0 + 0.01 * i);
  }
  for (std::uint32_t i = 0; i < 10; ++i) {
    m.triangles.push_back({2 * i, 2 * i + 3, 2 * i + 1});  // counter-clockwise from above
    m.triangles.push_back({2 * i, 2 * i + 2, 2 * i + 3});
  }
  s.meshes.push_back(m);
  s.file_origin = origin;
  return s;
}

double smallest_plan_area(const TriangleMesh& m) {
  double smallest = std::numeric_limits<double>::infinity();
  for (const auto& t : m.triangles) {
    const Vec2 a = m.vertices[t[0]].head<2>(), b = m.vertices[t[1]].head<2>(), c = m.vertices[t[2]].head<2>();
    const Vec2 u = b - a, v = c - a;
    smallest = std::min(smallest, 0.5 * (u.x() * v.y() - u.y() * v.x()));
  }
  return smallest;
}

TEST(MeshWriter, AFileOriginKeepsATileFarFromTheFrameOriginExact) {
  const FileOrigin tile = cell_file_origin(2000.0, -68, -1);
  EXPECT_EQ(tile.at, Vec2(-135000.0, -1000.0));
  EXPECT_EQ(tile.quantum_m, std::exp2(-12.0));
  EXPECT_EQ(cell_file_origin(500.0, 3, 0).quantum_m, std::exp2(-14.0));
  const auto dir = test::scratch_dir("mesh_writer_file_origin");
  // Without: the 4 mm strip collapses (every triangle's plan area 0 or folded).
  const MeshScene plain = far_strip(std::nullopt);
  ASSERT_GT(smallest_plan_area(plain.meshes[0]), 5e-4);
  const MeshScene lost = read_mesh_file(write_files(encode_mesh_scene(plain, MeshFormat::glb, "lost"), dir));
  EXPECT_LE(smallest_plan_area(lost.meshes[0]), 0.0);

  const MeshScene scene = far_strip(tile);
  const double q = tile.quantum_m;
  const auto quantised = [q](const Vec3& v) {
    return Vec3(std::round(v.x() / q) * q, std::round(v.y() / q) * q,
                static_cast<double>(static_cast<float>(v.z())));
  };
  const MeshScene back = read_mesh_file(write_files(encode_mesh_scene(scene, MeshFormat::glb, "kept"), dir));
  ASSERT_EQ(back.meshes.size(), 1U);
  ASSERT_EQ(back.meshes[0].vertices.size(), scene.meshes[0].vertices.size());
  for (std::size_t i = 0; i < scene.meshes[0].vertices.size(); ++i) {
    EXPECT_EQ(back.meshes[0].vertices[i], quantised(scene.meshes[0].vertices[i])) << i;
    EXPECT_LE((back.meshes[0].vertices[i] - scene.meshes[0].vertices[i]).head<2>().cwiseAbs().maxCoeff(),
              q / 2);
  }
  EXPECT_NEAR(smallest_plan_area(back.meshes[0]), smallest_plan_area(scene.meshes[0]),
              1.625 * q);                     // side 1.625 m, width to q
  ASSERT_TRUE(back.file_origin.has_value());  // kept for writing it again
  EXPECT_EQ(back.file_origin->at, tile.at);
  EXPECT_EQ(back.file_origin->quantum_m, q);
  EXPECT_FALSE(back.metadata.contains("relief:file_origin"));
  EXPECT_EQ(back.frame.origin(), scene.frame.origin());
  // The glb's root node carries the origin (file axes, y up), its positions are relative to it.
  const std::string glb = encode_mesh_scene(scene, MeshFormat::glb, "kept").front().bytes;
  std::uint32_t json_length = 0;
  std::memcpy(&json_length, glb.data() + 12, 4);
  const nlohmann::json j = nlohmann::json::parse(glb.substr(20, json_length));
  EXPECT_EQ(j["nodes"][0]["translation"], nlohmann::json({-135000.0, 0.0, 1000.0}));
  EXPECT_LT(j["accessors"][0]["max"][0].get<double>(), 500.0);

  // OBJ: the same quantised positions, absolute, as text that reads back as the same double.
  const std::vector<EncodedFile> obj = encode_mesh_scene(scene, MeshFormat::obj, "kept");
  std::istringstream lines(obj.front().bytes);
  std::vector<Vec3> written;
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("v ", 0) != 0) continue;
    std::istringstream v(line.substr(2));
    double x = 0, y = 0, z = 0;
    v >> x >> y >> z;
    written.emplace_back(x, -z, y);  // file axes back to the frame's
  }
  ASSERT_EQ(written.size(), scene.meshes[0].vertices.size());
  for (std::size_t i = 0; i < written.size(); ++i)
    EXPECT_EQ(written[i], quantised(scene.meshes[0].vertices[i])) << i;

  // A vertex on the line between tiles (-68, -1) and (-67, -1), near it, and near a corner:
  // the same bits from either tile's file.
  for (const Vec3& p : {Vec3(-134000.0, -1234.5678, 301.0), Vec3(-133999.99987, -1.00003, 302.0),
                        Vec3(-134000.00011, -1999.99991, 303.0)}) {
    MeshScene a = far_strip(tile);
    a.meshes[0].vertices[0] = p;
    MeshScene b = far_strip(cell_file_origin(2000.0, -67, -1));
    b.meshes[0].vertices[0] = p;
    const MeshScene ra = read_mesh_file(write_files(encode_mesh_scene(a, MeshFormat::glb, "a"), dir));
    const MeshScene rb = read_mesh_file(write_files(encode_mesh_scene(b, MeshFormat::glb, "b"), dir));
    EXPECT_EQ(ra.meshes[0].vertices[0], rb.meshes[0].vertices[0]);
    EXPECT_EQ(ra.meshes[0].vertices[0], quantised(p));
  }
  // A vertex beyond 2^24 quanta of the origin doubles the quantum rather than lose exactness.
  MeshScene wide = far_strip(tile);
  wide.meshes[0].vertices[0].x() += 5000.0;
  const MeshScene rw = read_mesh_file(write_files(encode_mesh_scene(wide, MeshFormat::glb, "wide"), dir));
  ASSERT_TRUE(rw.file_origin.has_value());
  EXPECT_EQ(rw.file_origin->quantum_m, 2 * q);
  MeshScene bad = far_strip(FileOrigin{Vec2(0.5, 0.0), q});
  EXPECT_THROW((void)encode_mesh_scene(bad, MeshFormat::glb, "bad"), InvalidInput);
  bad.file_origin = FileOrigin{Vec2::Zero(), 0.001};
  EXPECT_THROW((void)encode_mesh_scene(bad, MeshFormat::glb, "bad"), InvalidInput);
}

// The .glb's own layout, as the glTF 2.0 spec has it: header and two 4-byte aligned chunks,
// POSITION accessors with min/max, one material per surface type, the metadata as extras of
// the asset and of the root node, no extensions.
TEST(MeshWriter, GlbLayoutFollowsTheSpec) {
  const std::string glb = encode_mesh_scene(test_scene(), MeshFormat::glb, "layout").front().bytes;
  const auto u32 = [&](std::size_t at) {
    std::uint32_t v = 0;
    std::memcpy(&v, glb.data() + at, sizeof v);
    return v;
  };
  ASSERT_GE(glb.size(), 28u);
  EXPECT_EQ(glb.substr(0, 4), "glTF");
  EXPECT_EQ(u32(4), 2u);
  EXPECT_EQ(u32(8), glb.size());
  const std::uint32_t json_bytes = u32(12);
  EXPECT_EQ(json_bytes % 4, 0u);
  EXPECT_EQ(glb.substr(16, 4), "JSON");
  const std::uint32_t bin_bytes = u32(20 + json_bytes);
  EXPECT_EQ(glb.substr(24 + json_bytes, 3), "BIN");
  EXPECT_EQ(bin_bytes % 4, 0u);
  EXPECT_EQ(20u + json_bytes + 8u + bin_bytes, glb.size());
  const nlohmann::json j = nlohmann::json::parse(glb.substr(20, json_bytes));
  EXPECT_EQ(j["asset"]["version"], "2.0");
  EXPECT_EQ(j["asset"]["extras"]["relief:source"], "unit test");
  EXPECT_EQ(j["nodes"][0]["extras"]["relief:crs"], "EPSG:32610");
  EXPECT_FALSE(j.contains("extensionsUsed"));
  EXPECT_EQ(j["buffers"][0]["byteLength"], bin_bytes);
  ASSERT_EQ(j["meshes"].size(), 3u);
  std::set<std::string> materials;
  for (const auto& m : j["materials"]) materials.insert(m["name"].get<std::string>());
  EXPECT_EQ(materials.size(), j["materials"].size());
  for (const auto& mesh : j["meshes"]) {
    const auto& prim = mesh["primitives"][0];
    const auto& position = j["accessors"][prim["attributes"]["POSITION"].get<std::size_t>()];
    ASSERT_TRUE(position.contains("min") && position.contains("max")) << mesh["name"];
    EXPECT_EQ(position["min"].size(), 3u);
    EXPECT_EQ(j["accessors"][prim["indices"].get<std::size_t>()]["count"].get<std::size_t>() % 3, 0u);
    for (const auto& [attribute, index] : prim["attributes"].items()) {
      const auto& view =
          j["bufferViews"][j["accessors"][index.get<std::size_t>()]["bufferView"].get<std::size_t>()];
      EXPECT_LE(view["byteOffset"].get<std::size_t>() + view["byteLength"].get<std::size_t>(), bin_bytes)
          << attribute;
    }
  }
  // The terrain grid: 11 x 11 vertices over x 4500.37..4600.37, y -3200.61..-3100.61, z 30..34;
  // in the file's axes (y up, z = -y) its bounds are these.
  const auto& terrain = j["meshes"][2];
  EXPECT_EQ(terrain["name"], "Terrain");
  const auto& bounds = j["accessors"][terrain["primitives"][0]["attributes"]["POSITION"].get<std::size_t>()];
  EXPECT_EQ(bounds["count"], 121);
  const std::array<double, 3> lo{4500.37, 30.0, 3100.61}, hi{4600.37, 34.0, 3200.61};
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_NEAR(bounds["min"][k].get<double>(), lo[k], 1e-3) << k;
    EXPECT_NEAR(bounds["max"][k].get<double>(), hi[k], 1e-3) << k;
  }
}

// assimp's OBJ and FBX importers make one vertex per triangle corner.
TEST(MeshWriter, ObjRoundTripKeepsTrianglesPositionsAndMetadata) {
  expect_round_trip(MeshFormat::obj, [](const TriangleMesh& m) { return 3 * m.triangles.size(); });
}

TEST(MeshWriter, FbxRoundTripKeepsTrianglesPositionsAndMetadata) {
  expect_round_trip(MeshFormat::fbx, [](const TriangleMesh& m) { return 3 * m.triangles.size(); });
}

TEST(MeshWriter, UvsRoundTripThroughEveryFormat) {
  for (const MeshFormat f : {MeshFormat::glb, MeshFormat::obj, MeshFormat::fbx}) {
    SCOPED_TRACE(std::string(to_string(f)));
    MeshScene s;
    s.meshes.push_back(grid("Terrain", SurfaceKind::terrain, 3));
    const auto dir = test::scratch_dir(std::string("mesh_writer_uv_") + std::string(to_string(f)));
    const MeshScene back = read_mesh_file(write_files(encode_mesh_scene(s, f, "uv"), dir));
    ASSERT_EQ(back.meshes.size(), 1u);
    const TriangleMesh& a = s.meshes[0];
    const TriangleMesh& b = back.meshes[0];
    ASSERT_EQ(b.uvs.size(), b.vertices.size());
    ASSERT_EQ(b.triangles.size(), a.triangles.size());
    for (std::size_t t = 0; t < a.triangles.size(); ++t) {
      for (int k = 0; k < 3; ++k) {
        EXPECT_NEAR((a.uvs[a.triangles[t][k]] - b.uvs[b.triangles[t][k]]).norm(), 0.0, 1e-6);
      }
    }
  }
}

// --- an independent look at the FBX bytes ---------------------------------------------------

std::uint32_t u32_at(const std::string& b, std::size_t at) {
  std::uint32_t v = 0;
  std::memcpy(&v, b.data() + at, 4);
  return v;
}

// Names of the top-level node records, walking the end offsets; stops at the null record.
std::vector<std::string> fbx_top_level_names(const std::string& bytes, std::size_t& null_record_at) {
  std::vector<std::string> names;
  std::size_t at = 27;
  while (at + 13 <= bytes.size()) {
    const std::uint32_t end = u32_at(bytes, at);
    if (end == 0) break;
    const auto name_length = static_cast<unsigned char>(bytes[at + 12]);
    names.push_back(bytes.substr(at + 13, name_length));
    if (end <= at || end > bytes.size()) return {};
    at = end;
  }
  null_record_at = at;
  return names;
}

TEST(MeshWriter, FbxBytesHaveMagicVersionNodesAndFooter) {
  const auto files = encode_mesh_scene(test_scene(), MeshFormat::fbx, "scene");
  ASSERT_EQ(files.size(), 1u);
  EXPECT_EQ(files[0].filename, "scene.fbx");
  const std::string& b = files[0].bytes;
  ASSERT_GT(b.size(), 200u);
  EXPECT_EQ(b.substr(0, 23), std::string("Kaydara FBX Binary  \0\x1a\0", 23));
  EXPECT_EQ(u32_at(b, 23), 7400u);
  std::size_t null_at = 0;
  const std::vector<std::string> expected{
      "FBXHeaderExtension", "FileId",     "CreationTime", "Creator", "GlobalSettings",
      "Documents",          "References", "Definitions",  "Objects", "Connections"};
  EXPECT_EQ(fbx_top_level_names(b, null_at), expected);
  // Null record, footer id, padding to 16, version, 120 zeros, 16 bytes closing magic.
  EXPECT_EQ(b.substr(null_at, 13), std::string(13, '\0'));
  EXPECT_EQ(static_cast<unsigned char>(b[null_at + 13]), 0xfa);
  EXPECT_EQ(u32_at(b, b.size() - 16 - 120 - 4), 7400u);
  EXPECT_EQ((b.size() - 16 - 120 - 4) % 16, 0u);
  // Deterministic bytes.
  EXPECT_EQ(encode_mesh_scene(test_scene(), MeshFormat::fbx, "scene")[0].bytes, b);
}

// --- Blender ---------------------------------------------------------------------------------

TEST(MeshWriter, BlenderImportsFbxGlbAndObjInMetresZUp) {
  if (!test::have_blender()) GTEST_SKIP() << "blender is not on PATH";
  const MeshScene scene = test_scene();
  const auto dir = test::scratch_dir("mesh_writer_blender");
  std::vector<std::filesystem::path> paths;
  for (const MeshFormat f : {MeshFormat::fbx, MeshFormat::glb, MeshFormat::obj}) {
    paths.push_back(write_files(encode_mesh_scene(scene, f, "scene"), dir));
  }
  const test::BlenderImports imports = test::import_in_blender(paths, dir);
  const auto& by_file = imports.by_file;
  ASSERT_EQ(by_file.size(), 3u) << imports.output;
  for (const auto& p : paths) {
    SCOPED_TRACE(p.filename().string());
    const nlohmann::json& imported = by_file.at(p.string());
    const nlohmann::json& objects = imported["objects"];
    ASSERT_EQ(objects.size(), scene.meshes.size()) << objects.dump();
    for (const TriangleMesh& m : scene.meshes) {
      SCOPED_TRACE(m.name);
      ASSERT_TRUE(objects.contains(m.name)) << objects.dump();
      const nlohmann::json& o = objects[m.name];
      EXPECT_EQ(o["vertices"].get<std::size_t>(), m.vertices.size());
      EXPECT_EQ(o["polygons"].get<std::size_t>(), m.triangles.size());
      Vec3 lo = Vec3::Constant(1e300);
      Vec3 hi = Vec3::Constant(-1e300);
      for (const Vec3& v : m.vertices) {
        lo = lo.cwiseMin(v);
        hi = hi.cwiseMax(v);
      }
      for (int k = 0; k < 3; ++k) {
        EXPECT_NEAR(o["min"][k].get<double>(), lo[k], 0.01);
        EXPECT_NEAR(o["max"][k].get<double>(), hi[k], 0.01);
      }
      if (p.extension() == ".fbx") {
        EXPECT_EQ(o["proj"].get<std::string>(), scene.metadata.at("relief:proj"));
      }
    }
    // The georeference as custom properties: on every mesh object from FBX, on the root empty
    // ("relief") from glTF; OBJ has none in Blender (only comments).
    if (p.extension() != ".obj") {
      EXPECT_EQ(imported["proj"].get<std::string>(), scene.metadata.at("relief:proj"));
    }
    std::cout << p.filename().string() << ": relief:proj on " << imported["proj_carriers"].dump() << "\n";
  }
}

// The float values of accessor `index` of a .glb (JSON `j`, binary chunk `bin`).
std::vector<float> accessor_floats(const nlohmann::json& j, const std::string& bin, std::size_t index) {
  const auto& a = j["accessors"][index];
  const auto& view = j["bufferViews"][a["bufferView"].get<std::size_t>()];
  const std::map<std::string, std::size_t> width = {{"SCALAR", 1}, {"VEC3", 3}, {"VEC4", 4}};
  std::vector<float> out(a["count"].get<std::size_t>() * width.at(a["type"].get<std::string>()));
  std::memcpy(out.data(), bin.data() + view["byteOffset"].get<std::size_t>(), out.size() * sizeof(float));
  return out;
}

// Rotates v by the unit quaternion (x, y, z, w).
std::array<double, 3> rotate(const float* q, const std::array<double, 3>& v) {
  const double x = q[0], y = q[1], z = q[2], w = q[3];
  const std::array<double, 3> u{x, y, z};
  const auto cross = [](const std::array<double, 3>& a, const std::array<double, 3>& b) {
    return std::array<double, 3>{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                                 a[0] * b[1] - a[1] * b[0]};
  };
  const auto t = cross(u, v);
  const std::array<double, 3> t2{2 * t[0], 2 * t[1], 2 * t[2]};
  const auto c = cross(u, t2);
  return {v[0] + w * t2[0] + c[0], v[1] + w * t2[1] + c[1], v[2] + w * t2[2] + c[2]};
}

// A replay: the scene plus a box per vehicle with its keys as node animation in the file's axes
// (y up, z = -local y): the translation is the key's position, the rotation turns the box's
// forward axis (file x) to the heading with the pitch, its up axis by the roll; the scale shows
// the box from the first key until it hides.
TEST(MeshWriter, ReplayGlbAnimatesEveryVehicleBoxInTheFilesAxes) {
  ReplayTrack car;
  car.name = "car 1";
  car.length_m = 4.0;
  car.keys = {{1.0, Vec3(10.0, 20.0, 30.0), 0.0, 0.0, 0.0},
              {1.5, Vec3(11.0, 20.0, 30.1), std::numbers::pi / 2, 0.1, 0.0},
              {2.0, Vec3(11.0, 21.0, 30.2), 0.0, 0.0, 0.2}};
  car.hide_after_s = 2.5;
  ReplayTrack empty;
  empty.name = "never placed";
  const std::string glb = encode_replay_glb(test_scene(), {car, empty});
  std::uint32_t json_bytes = 0;
  std::memcpy(&json_bytes, glb.data() + 12, 4);
  const nlohmann::json j = nlohmann::json::parse(glb.substr(20, json_bytes));
  const std::string bin = glb.substr(20 + json_bytes + 8);
  ASSERT_EQ(j["animations"].size(), 1u);
  const auto& animation = j["animations"][0];
  EXPECT_EQ(animation["name"], "replay");
  ASSERT_EQ(animation["channels"].size(), 3u);  // the empty track is left out
  const auto sampler_of = [&](const std::string& path) {
    for (const auto& c : animation["channels"])
      if (c["target"]["path"] == path) return animation["samplers"][c["sampler"].get<std::size_t>()];
    return nlohmann::json();
  };
  const auto node = animation["channels"][0]["target"]["node"].get<std::size_t>();
  EXPECT_EQ(j["nodes"][node]["name"], "car 1");
  const auto& box = j["nodes"][j["nodes"][node]["children"][0].get<std::size_t>()];
  EXPECT_EQ(box["scale"], nlohmann::json({4.0f, 1.5f, 1.8f}));  // length, height, width
  EXPECT_EQ(j["materials"].back()["name"], "Vehicle");

  const auto times = accessor_floats(j, bin, sampler_of("translation")["input"].get<std::size_t>());
  EXPECT_EQ(times, (std::vector<float>{1.0f, 1.5f, 2.0f}));
  const auto& input = j["accessors"][sampler_of("translation")["input"].get<std::size_t>()];
  EXPECT_EQ(input["min"][0], 1.0);
  EXPECT_EQ(input["max"][0], 2.0);
  const auto t = accessor_floats(j, bin, sampler_of("translation")["output"].get<std::size_t>());
  EXPECT_EQ(t, (std::vector<float>{10.0f, 30.0f, -20.0f, 11.0f, 30.1f, -20.0f, 11.0f, 30.2f, -21.0f}));
  const auto r = accessor_floats(j, bin, sampler_of("rotation")["output"].get<std::size_t>());
  ASSERT_EQ(r.size(), 12u);
  // Key 0: no turn. Key 1: heading north (local +y = file -z), nose up 0.1 rad.
  const auto f0 = rotate(&r[0], {1, 0, 0});
  EXPECT_NEAR(f0[0], 1.0, 1e-6);
  const auto f1 = rotate(&r[4], {1, 0, 0});
  EXPECT_NEAR(f1[0], 0.0, 1e-6);
  EXPECT_NEAR(f1[1], std::sin(0.1), 1e-6);
  EXPECT_NEAR(f1[2], -std::cos(0.1), 1e-6);
  // Key 2: rolled 0.2 rad, right side down: the up axis leans to the right (local -y = file +z).
  const auto u2 = rotate(&r[8], {0, 1, 0});
  EXPECT_NEAR(u2[1], std::cos(0.2), 1e-6);
  EXPECT_NEAR(u2[2], std::sin(0.2), 1e-6);
  const auto scale = sampler_of("scale");
  EXPECT_EQ(scale["interpolation"], "STEP");
  EXPECT_EQ(accessor_floats(j, bin, scale["input"].get<std::size_t>()),
            (std::vector<float>{0.0f, 1.0f, 2.5f}));
  EXPECT_EQ(accessor_floats(j, bin, scale["output"].get<std::size_t>()),
            (std::vector<float>{0, 0, 0, 1, 1, 1, 0, 0, 0}));

  // Consecutive rotations on one side of the quaternion sphere: a viewer's slerp turns the short way.
  for (std::size_t k = 1; k < 3; ++k) {
    const double dot = r[4 * k] * r[4 * k - 4] + r[4 * k + 1] * r[4 * k - 3] + r[4 * k + 2] * r[4 * k - 2] +
                       r[4 * k + 3] * r[4 * k - 1];
    EXPECT_GT(dot, 0.0) << k;
  }
  ReplayTrack spin;  // heading 170 then -170 degrees: 20 degrees apart, not 340
  spin.name = "spin";
  spin.keys = {{0.0, Vec3::Zero(), 170.0 * std::numbers::pi / 180.0, 0.0, 0.0},
               {1.0, Vec3::Zero(), -170.0 * std::numbers::pi / 180.0, 0.0, 0.0}};
  spin.hide_after_s = 2.0;
  const std::string spun = encode_replay_glb(test_scene(), {spin});
  std::memcpy(&json_bytes, spun.data() + 12, 4);
  const nlohmann::json js = nlohmann::json::parse(spun.substr(20, json_bytes));
  const std::string bs = spun.substr(20 + json_bytes + 8);
  std::size_t rotation_output = 0;
  for (const auto& c : js["animations"][0]["channels"])
    if (c["target"]["path"] == "rotation")
      rotation_output =
          js["animations"][0]["samplers"][c["sampler"].get<std::size_t>()]["output"].get<std::size_t>();
  const auto q = accessor_floats(js, bs, rotation_output);
  EXPECT_GT(q[0] * q[4] + q[1] * q[5] + q[2] * q[6] + q[3] * q[7],
            std::cos(10.0 * std::numbers::pi / 180.0) - 1e-6);

  car.keys[2].t_s = 1.5;
  EXPECT_THROW((void)encode_replay_glb(test_scene(), {car}), InvalidInput);
  car.keys[2].t_s = 2.0;
  car.hide_after_s = 2.0;
  EXPECT_THROW((void)encode_replay_glb(test_scene(), {car}), InvalidInput);
}

}  // namespace
}  // namespace relief
