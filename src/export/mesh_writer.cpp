#include "relief/export/mesh_writer.h"

#include <Eigen/Geometry>

#include <assimp/material.h>
#include <assimp/metadata.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/Importer.hpp>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>

#include "export/fbx_scene_writer.h"
#include "export/glb_writer.h"
#include "export/obj_writer.h"
#include "relief/core/errors.h"

namespace relief {
namespace {

// OBJ has no metadata: entries go into comment lines "# relief-metadata <key>\t<value>" (tab,
// newline and backslash escaped), which read_mesh_file parses again.
constexpr std::string_view kObjMetadataPrefix = "# relief-metadata ";

struct KindStyle {
  SurfaceKind kind;
  const char* material_name;
  std::array<float, 3> diffuse_rgb;
};

// One material per surface kind: distinct diffuse colours (asphalt, paint, concrete, ...).
constexpr std::array<KindStyle, 6> kKindStyles{{
    {SurfaceKind::road, "Road", {0.20f, 0.20f, 0.22f}},
    {SurfaceKind::marking, "Marking", {0.95f, 0.95f, 0.90f}},
    {SurfaceKind::sidewalk, "Sidewalk", {0.62f, 0.60f, 0.57f}},
    {SurfaceKind::shoulder, "Shoulder", {0.40f, 0.36f, 0.30f}},
    {SurfaceKind::junction, "Junction", {0.27f, 0.27f, 0.30f}},
    {SurfaceKind::terrain, "Terrain", {0.33f, 0.45f, 0.22f}},
}};

const KindStyle& style_of(SurfaceKind kind) {
  for (const KindStyle& s : kKindStyles) {
    if (s.kind == kind) return s;
  }
  return kKindStyles[0];
}

// File axes (Y up) from relief's local axes (Z up): file (x, y, z) = local (x, z, -y).
std::array<float, 3> to_file_axes(const Vec3& v) {
  return {static_cast<float>(v.x()), static_cast<float>(v.z()), static_cast<float>(-v.y())};
}
// ... and back: local (x, y, z) = file (x, -z, y).
Vec3 from_file_axes(double x, double y, double z) {
  return {x, -z, y};
}

constexpr const char* kFileOriginKey = "relief:file_origin";

// Where the positions of `scene` are written from: its file origin, with the quantum doubled
// until every vertex lies within 2^24 quanta of it (so that a float holds each exactly), or
// nothing. Throws InvalidInput for an origin off whole metres or a quantum not a power of two.
std::optional<FileOrigin> placement_of(const MeshScene& scene) {
  if (!scene.file_origin) return std::nullopt;
  FileOrigin o = *scene.file_origin;
  int exponent = 0;
  if (!o.at.allFinite() || o.at != o.at.array().round().matrix() || !std::isfinite(o.quantum_m) ||
      !(o.quantum_m > 0.0) || std::frexp(o.quantum_m, &exponent) != 0.5) {
    throw InvalidInput(
        "mesh scene: a file origin must lie on whole metres and its quantum be a power of two");
  }
  double far = 0.0;
  for (const TriangleMesh& mesh : scene.meshes)
    for (const Vec3& v : mesh.vertices) far = std::max(far, (v.head<2>() - o.at).cwiseAbs().maxCoeff());
  constexpr double kFloatIntegers = 16777216.0;  // 2^24
  while (far + o.quantum_m > kFloatIntegers * o.quantum_m) o.quantum_m *= 2.0;
  o.at = (o.at / o.quantum_m).array().round().matrix() * o.quantum_m;  // on the quantum's grid too
  return o;
}

// The scene in file axes and float, one material per kind used (in order of first use);
// shared by the assimp and the FBX encoders. Throws InvalidInput for a bad index.
fbx::SceneDesc prepare_scene(const MeshScene& scene) {
  fbx::SceneDesc out;
  const std::optional<FileOrigin> placement = placement_of(scene);
  // x and y on the quantum's grid, relative to the origin: exact in a float.
  const auto position = [&placement](const Vec3& v) {
    if (!placement) return to_file_axes(v);
    const double q = placement->quantum_m;
    const Vec2 p = (v.head<2>() / q).array().round().matrix() * q - placement->at;
    return to_file_axes(Vec3(p.x(), p.y(), v.z()));
  };
  if (placement) out.offset = {placement->at.x(), 0.0, -placement->at.y()};
  std::vector<SurfaceKind> kinds;
  for (const TriangleMesh& mesh : scene.meshes) {
    fbx::MeshDesc m;
    m.name = mesh.name;
    const std::size_t n = mesh.vertices.size();
    for (const auto& t : mesh.triangles) {
      for (const std::uint32_t i : t) {
        if (i >= n) {
          throw InvalidInput("mesh '" + mesh.name + "': triangle index " + std::to_string(i) +
                             " out of range (" + std::to_string(n) + " vertices)");
        }
      }
    }
    m.triangles = mesh.triangles;
    m.positions.reserve(n);
    for (const Vec3& v : mesh.vertices) m.positions.push_back(position(v));
    if (mesh.normals.size() == n) {
      for (const Vec3& v : mesh.normals) m.normals.push_back(to_file_axes(v));
    }
    if (mesh.uvs.size() == n) {
      for (const Vec2& uv : mesh.uvs)
        m.uvs.push_back({static_cast<float>(uv.x()), static_cast<float>(uv.y())});
    }
    auto k = std::find(kinds.begin(), kinds.end(), mesh.kind);
    if (k == kinds.end()) k = kinds.insert(kinds.end(), mesh.kind);
    m.material = static_cast<std::size_t>(k - kinds.begin());
    out.meshes.push_back(std::move(m));
  }
  for (const SurfaceKind kind : kinds) {
    const KindStyle& s = style_of(kind);
    out.materials.push_back({s.material_name, s.diffuse_rgb});
  }
  // Georeference first (the frame's CRS, origin and PROJ string), then the caller's entries,
  // which override a default of the same key.
  std::map<std::string, std::string> metadata;
  metadata["relief:crs"] = scene.frame.crs();
  std::ostringstream origin;
  origin.precision(17);
  origin << scene.frame.origin().x() << ' ' << scene.frame.origin().y();
  metadata["relief:origin"] = origin.str();
  if (!scene.metadata.contains("relief:proj")) metadata["relief:proj"] = scene.frame.proj_string();
  for (const auto& [key, value] : scene.metadata) metadata[key] = value;
  metadata.erase(kFileOriginKey);
  if (placement) {
    std::ostringstream at;
    at.precision(17);
    at << placement->at.x() << ' ' << placement->at.y() << ' ' << placement->quantum_m;
    metadata[kFileOriginKey] = at.str();
  }
  out.user_properties.assign(metadata.begin(), metadata.end());
  return out;
}

std::string escape_obj_comment(const std::string& text) {
  std::string out;
  for (const char c : text) {
    switch (c) {
      case '\\':
        out += "\\\\";
        break;
      case '\t':
        out += "\\t";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\r':
        out += "\\r";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::string unescape_obj_comment(std::string_view text) {
  std::string out;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] != '\\' || i + 1 == text.size()) {
      out += text[i];
      continue;
    }
    const char c = text[++i];
    out += c == 't' ? '\t' : c == 'n' ? '\n' : c == 'r' ? '\r' : c;
  }
  return out;
}

// The metadata as OBJ comment lines.
std::string obj_metadata_lines(const fbx::SceneDesc& desc) {
  std::string out;
  for (const auto& [key, value] : desc.user_properties) {
    out += kObjMetadataPrefix;
    out += escape_obj_comment(key) + '\t' + escape_obj_comment(value) + '\n';
  }
  return out;
}

// --- reading ---------------------------------------------------------------------------------

void collect_string_metadata(const aiMetadata* meta, std::map<std::string, std::string>& out) {
  if (meta == nullptr) return;
  for (unsigned i = 0; i < meta->mNumProperties; ++i) {
    if (meta->mValues[i].mType != AI_AISTRING || meta->mValues[i].mData == nullptr) continue;
    const std::string key = meta->mKeys[i].C_Str();
    // assimp's own entries (importer name, source generator, FBX "UserProperties" text).
    if (key.starts_with("SourceAsset_") || key == "UserProperties") continue;
    out.emplace(key, static_cast<const aiString*>(meta->mValues[i].mData)->C_Str());
  }
}

SurfaceKind kind_of_material(const aiScene& scene, unsigned material_index) {
  if (material_index >= scene.mNumMaterials) return SurfaceKind::road;
  aiString name;
  if (scene.mMaterials[material_index]->Get(AI_MATKEY_NAME, name) != AI_SUCCESS) return SurfaceKind::road;
  for (const KindStyle& s : kKindStyles) {
    if (name.C_Str() == std::string_view(s.material_name)) return s.kind;
  }
  return SurfaceKind::road;
}

TriangleMesh convert_mesh(const aiScene& scene, const aiMesh& src, const aiMatrix4x4& to_world,
                          const std::string& fallback_name) {
  TriangleMesh mesh;
  mesh.name = src.mName.length > 0 ? src.mName.C_Str() : fallback_name;
  mesh.kind = kind_of_material(scene, src.mMaterialIndex);
  aiMatrix3x3 normal_matrix(to_world);
  normal_matrix.Inverse().Transpose();
  mesh.vertices.reserve(src.mNumVertices);
  // In double: a file origin's translation plus a position relative to it is exact only there.
  Eigen::Matrix4d m;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) m(r, c) = to_world[static_cast<unsigned>(r)][static_cast<unsigned>(c)];
  for (unsigned i = 0; i < src.mNumVertices; ++i) {
    const aiVector3D& v = src.mVertices[i];
    const Eigen::Vector3d p =
        m.topLeftCorner<3, 3>() * Eigen::Vector3d(v.x, v.y, v.z) + m.topRightCorner<3, 1>();
    mesh.vertices.push_back(from_file_axes(p.x(), p.y(), p.z()));
  }
  if (src.mNormals != nullptr) {
    mesh.normals.reserve(src.mNumVertices);
    for (unsigned i = 0; i < src.mNumVertices; ++i) {
      const aiVector3D n = (normal_matrix * src.mNormals[i]).NormalizeSafe();
      mesh.normals.push_back(from_file_axes(n.x, n.y, n.z));
    }
  }
  if (src.mTextureCoords[0] != nullptr) {
    mesh.uvs.reserve(src.mNumVertices);
    for (unsigned i = 0; i < src.mNumVertices; ++i) {
      mesh.uvs.emplace_back(src.mTextureCoords[0][i].x, src.mTextureCoords[0][i].y);
    }
  }
  // Points and lines (faces of 1 or 2 indices) have no place in a TriangleMesh.
  for (unsigned f = 0; f < src.mNumFaces; ++f) {
    const aiFace& face = src.mFaces[f];
    if (face.mNumIndices == 3)
      mesh.triangles.push_back({face.mIndices[0], face.mIndices[1], face.mIndices[2]});
  }
  return mesh;
}

// Depth-first over the node tree: one TriangleMesh per mesh reference, in world coordinates.
void convert_nodes(const aiScene& scene, const aiNode& node, const aiMatrix4x4& parent_to_world,
                   std::vector<bool>& used, MeshScene& out) {
  const aiMatrix4x4 to_world = parent_to_world * node.mTransformation;
  collect_string_metadata(node.mMetaData, out.metadata);
  for (unsigned i = 0; i < node.mNumMeshes; ++i) {
    const unsigned m = node.mMeshes[i];
    if (m >= scene.mNumMeshes) continue;
    used[m] = true;
    out.meshes.push_back(convert_mesh(scene, *scene.mMeshes[m], to_world, node.mName.C_Str()));
  }
  for (unsigned c = 0; c < node.mNumChildren; ++c)
    convert_nodes(scene, *node.mChildren[c], to_world, used, out);
}

void read_obj_metadata(const std::filesystem::path& path, std::map<std::string, std::string>& out) {
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (!line.starts_with('#')) {
      if (line.empty()) continue;
      break;  // the metadata comments precede the first statement
    }
    if (!line.starts_with(kObjMetadataPrefix)) continue;
    const std::string_view entry = std::string_view(line).substr(kObjMetadataPrefix.size());
    const std::size_t tab = entry.find('\t');
    if (tab == std::string_view::npos) continue;
    out[unescape_obj_comment(entry.substr(0, tab))] = unescape_obj_comment(entry.substr(tab + 1));
  }
}

// The frame from "relief:crs" and "relief:origin" ("x y" in the CRS's metres), when present.
void restore_frame(MeshScene& scene) {
  const auto crs = scene.metadata.find("relief:crs");
  const auto origin = scene.metadata.find("relief:origin");
  if (crs == scene.metadata.end() || origin == scene.metadata.end()) return;
  std::istringstream xy(origin->second);
  double x = 0.0;
  double y = 0.0;
  if (xy >> x >> y) scene.frame = GeoFrame(crs->second, Vec2(x, y));
}

}  // namespace

std::optional<MeshFormat> parse_mesh_format(std::string_view text) {
  if (text == "glb") return MeshFormat::glb;
  if (text == "obj") return MeshFormat::obj;
  if (text == "fbx") return MeshFormat::fbx;
  return std::nullopt;
}

std::string_view to_string(MeshFormat format) {
  switch (format) {
    case MeshFormat::glb:
      return "glb";
    case MeshFormat::obj:
      return "obj";
    case MeshFormat::fbx:
      return "fbx";
  }
  return "?";
}

std::string_view extension(MeshFormat format) {
  switch (format) {
    case MeshFormat::glb:
      return ".glb";
    case MeshFormat::obj:
      return ".obj";
    case MeshFormat::fbx:
      return ".fbx";
  }
  return "";
}

void write_mesh_scene(const MeshScene& scene, MeshFormat format, const std::string& base_name,
                      const MeshFileSink& sink) {
  const fbx::SceneDesc desc = prepare_scene(scene);
  if (format == MeshFormat::obj) {
    const std::string mtl_name = base_name + ".mtl";
    const std::string metadata = obj_metadata_lines(desc);
    sink(base_name + ".obj", [&](std::ostream& out) { write_obj(desc, mtl_name, metadata, out); });
    const std::string mtl = encode_mtl(desc);
    sink(mtl_name, [&](std::ostream& out) { out << mtl; });
    return;
  }
  const std::string bytes = format == MeshFormat::fbx ? fbx::encode_scene(desc) : encode_glb(desc);
  sink(base_name + std::string(extension(format)), [&](std::ostream& out) { out << bytes; });
}

std::vector<EncodedFile> encode_mesh_scene(const MeshScene& scene, MeshFormat format,
                                           const std::string& base_name) {
  std::vector<EncodedFile> files;
  write_mesh_scene(scene, format, base_name,
                   [&](const std::string& filename, const std::function<void(std::ostream&)>& write) {
                     std::ostringstream out;
                     write(out);
                     files.push_back({filename, std::move(out).str()});
                   });
  return files;
}

std::string encode_replay_glb(const MeshScene& scene, const std::vector<ReplayTrack>& tracks) {
  fbx::SceneDesc desc = prepare_scene(scene);
  const std::size_t material = desc.materials.size();
  desc.materials.push_back({"Vehicle", {0.95f, 0.45f, 0.1f}});
  // local -> file axes: file = C local, C = [1 0 0; 0 0 1; 0 -1 0]; a rotation R becomes C R C'.
  Eigen::Matrix3d c;
  c << 1, 0, 0, 0, 0, 1, 0, -1, 0;
  std::vector<GlbTrack> out;
  for (const ReplayTrack& t : tracks) {
    if (t.keys.empty()) continue;
    if (!(t.length_m > 0.0 && t.width_m > 0.0 && t.height_m > 0.0))
      throw InvalidInput("replay track '" + t.name + "': its size must be > 0");
    if (!(t.hide_after_s > t.keys.back().t_s))
      throw InvalidInput("replay track '" + t.name + "': it must hide after its last key");
    GlbTrack g;
    g.name = t.name;
    g.size = {static_cast<float>(t.length_m), static_cast<float>(t.height_m), static_cast<float>(t.width_m)};
    g.hide_after_s = static_cast<float>(t.hide_after_s);
    for (std::size_t k = 0; k < t.keys.size(); ++k) {
      const ReplayKey& key = t.keys[k];
      if (!(key.t_s >= 0.0) || (k > 0 && !(key.t_s > t.keys[k - 1].t_s)))
        throw InvalidInput("replay track '" + t.name + "': key times must be >= 0 and strictly increasing");
      const Eigen::Matrix3d r = (Eigen::AngleAxisd(key.heading_rad, Eigen::Vector3d::UnitZ()) *
                                 Eigen::AngleAxisd(-key.pitch_rad, Eigen::Vector3d::UnitY()) *
                                 Eigen::AngleAxisd(key.roll_rad, Eigen::Vector3d::UnitX()))
                                    .toRotationMatrix();
      Eigen::Quaterniond q(c * r * c.transpose());
      // q and -q are the same turn; keep each key on the side of the last, so that a viewer's
      // slerp between them takes the short way.
      if (!g.rotations.empty()) {
        const auto& p = g.rotations.back();
        if (q.x() * p[0] + q.y() * p[1] + q.z() * p[2] + q.w() * p[3] < 0.0) q.coeffs() = -q.coeffs();
      }
      g.times.push_back(static_cast<float>(key.t_s));
      g.translations.push_back(to_file_axes(key.position));
      g.rotations.push_back({static_cast<float>(q.x()), static_cast<float>(q.y()), static_cast<float>(q.z()),
                             static_cast<float>(q.w())});
    }
    out.push_back(std::move(g));
  }
  return encode_glb(desc, out, material);
}

MeshScene read_mesh_file(const std::filesystem::path& path) {
  Assimp::Importer importer;
  // Triangulate only: no vertex joining, so the vertex counts are what the importer makes of
  // the file (see the header for which counts survive per format).
  const aiScene* scene = importer.ReadFile(path.string(), aiProcess_Triangulate);
  if (scene == nullptr || scene->mRootNode == nullptr || (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE) != 0) {
    throw IoError("cannot read mesh file '" + path.string() + "': " + importer.GetErrorString());
  }
  MeshScene out;
  collect_string_metadata(scene->mMetaData, out.metadata);
  std::vector<bool> used(scene->mNumMeshes, false);
  convert_nodes(*scene, *scene->mRootNode, aiMatrix4x4(), used, out);
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    if (!used[m]) out.meshes.push_back(convert_mesh(*scene, *scene->mMeshes[m], aiMatrix4x4(), ""));
  }
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  if (ext == ".obj") read_obj_metadata(path, out.metadata);
  restore_frame(out);
  // The file origin it was written with, so that writing it again keeps it (the positions read
  // are in the frame already).
  if (const auto it = out.metadata.find(kFileOriginKey); it != out.metadata.end()) {
    std::istringstream in(it->second);
    FileOrigin o;
    if (in >> o.at.x() >> o.at.y() >> o.quantum_m) out.file_origin = o;
    out.metadata.erase(it);
  }
  return out;
}

}  // namespace relief
