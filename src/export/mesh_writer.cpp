#include "relief/export/mesh_writer.h"

#include <assimp/material.h>
#include <assimp/metadata.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/Exporter.hpp>
#include <assimp/Importer.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cctype>
#include <cstring>
#include <fstream>
#include <map>
#include <memory>
#include <set>
#include <sstream>

#include "export/fbx_scene_writer.h"
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

// The scene in file axes and float, one material per kind used (in order of first use);
// shared by the assimp and the FBX encoders. Throws InvalidInput for a bad index.
fbx::SceneDesc prepare_scene(const MeshScene& scene) {
  fbx::SceneDesc out;
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
    for (const Vec3& v : mesh.vertices) m.positions.push_back(to_file_axes(v));
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
  out.user_properties.assign(metadata.begin(), metadata.end());
  return out;
}

// --- assimp encoding (glb) -------------------------------------------------------------------

aiMetadata* make_metadata(const fbx::SceneDesc& desc) {
  aiMetadata* meta = aiMetadata::Alloc(static_cast<unsigned>(desc.user_properties.size()));
  for (unsigned i = 0; i < meta->mNumProperties; ++i) {
    const auto& [key, value] = desc.user_properties[i];
    meta->Set(i, key, aiString(value));
  }
  return meta;
}

// The aiScene: a root node with one child node per mesh (named like the mesh, so that no
// exporter merges meshes), metadata on the scene and on the root node.
std::unique_ptr<aiScene> make_ai_scene(const fbx::SceneDesc& desc) {
  auto scene = std::make_unique<aiScene>();
  scene->mNumMaterials = static_cast<unsigned>(desc.materials.size());
  scene->mMaterials = new aiMaterial*[scene->mNumMaterials];
  for (unsigned i = 0; i < scene->mNumMaterials; ++i) {
    auto* mat = new aiMaterial();
    scene->mMaterials[i] = mat;
    const aiString name(desc.materials[i].name);
    mat->AddProperty(&name, AI_MATKEY_NAME);
    const auto& c = desc.materials[i].diffuse_rgb;
    const aiColor4D diffuse(c[0], c[1], c[2], 1.0f);
    mat->AddProperty(&diffuse, 1, AI_MATKEY_COLOR_DIFFUSE);
    mat->AddProperty(&diffuse, 1, AI_MATKEY_BASE_COLOR);
  }

  scene->mNumMeshes = static_cast<unsigned>(desc.meshes.size());
  scene->mMeshes = new aiMesh*[scene->mNumMeshes];
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const fbx::MeshDesc& src = desc.meshes[m];
    auto* mesh = new aiMesh();
    scene->mMeshes[m] = mesh;
    mesh->mName = aiString(src.name);
    mesh->mMaterialIndex = static_cast<unsigned>(src.material);
    mesh->mPrimitiveTypes = aiPrimitiveType_TRIANGLE;
    mesh->mNumVertices = static_cast<unsigned>(src.positions.size());
    mesh->mVertices = new aiVector3D[mesh->mNumVertices];
    for (unsigned i = 0; i < mesh->mNumVertices; ++i) {
      const auto& p = src.positions[i];
      mesh->mVertices[i] = aiVector3D(p[0], p[1], p[2]);
    }
    if (!src.normals.empty()) {
      mesh->mNormals = new aiVector3D[mesh->mNumVertices];
      for (unsigned i = 0; i < mesh->mNumVertices; ++i) {
        const auto& v = src.normals[i];
        mesh->mNormals[i] = aiVector3D(v[0], v[1], v[2]);
      }
    }
    if (!src.uvs.empty()) {
      mesh->mTextureCoords[0] = new aiVector3D[mesh->mNumVertices];
      mesh->mNumUVComponents[0] = 2;
      for (unsigned i = 0; i < mesh->mNumVertices; ++i) {
        mesh->mTextureCoords[0][i] = aiVector3D(src.uvs[i][0], src.uvs[i][1], 0.0f);
      }
    }
    mesh->mNumFaces = static_cast<unsigned>(src.triangles.size());
    mesh->mFaces = new aiFace[mesh->mNumFaces];
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      aiFace& face = mesh->mFaces[f];
      face.mNumIndices = 3;
      face.mIndices = new unsigned[3];
      std::copy(src.triangles[f].begin(), src.triangles[f].end(), face.mIndices);
    }
  }

  scene->mRootNode = new aiNode("relief");
  aiNode* root = scene->mRootNode;
  root->mNumChildren = scene->mNumMeshes;
  root->mChildren = new aiNode*[root->mNumChildren];
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    auto* node = new aiNode(desc.meshes[m].name);
    node->mParent = root;
    node->mNumMeshes = 1;
    node->mMeshes = new unsigned[1]{m};
    root->mChildren[m] = node;
  }
  scene->mMetaData = make_metadata(desc);
  root->mMetaData = make_metadata(desc);
  return scene;
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

// Collects the names of the extensions a glTF document uses (keys of every "extensions" object).
void used_gltf_extensions(const nlohmann::json& j, std::set<std::string>& out) {
  if (j.is_object()) {
    for (const auto& [key, value] : j.items()) {
      if (key == "extensions" && value.is_object()) {
        for (const auto& [name, unused] : value.items()) out.insert(name);
      }
      used_gltf_extensions(value, out);
    }
  } else if (j.is_array()) {
    for (const auto& value : j) used_gltf_extensions(value, out);
  }
}

std::uint32_t glb_u32(const std::string& glb, std::size_t at) {
  std::uint32_t v = 0;
  std::memcpy(&v, glb.data() + at, sizeof v);
  return v;
}

void put_glb_u32(std::string& out, std::size_t value) {
  const auto v = static_cast<std::uint32_t>(value);
  out.append(reinterpret_cast<const char*>(&v), sizeof v);
}

// assimp 5.2's glTF exporter writes no extras and lists extensions it does not use
// (KHR_materials_volume, FB_ngon_encoding). Rewrites the JSON chunk of the .glb: metadata into
// asset.extras (the document's place) and the root node's extras (which assimp and Blender read
// back as node metadata / custom properties), extensionsUsed reduced to the used ones.
std::string add_glb_metadata(const std::string& glb, const fbx::SceneDesc& desc,
                             const std::string& filename) {
  constexpr std::uint32_t kJsonChunk = 0x4E4F534A;  // "JSON"
  if (glb.size() < 20 || glb.compare(0, 4, "glTF") != 0 || glb_u32(glb, 16) != kJsonChunk) {
    throw IoError("assimp wrote an unexpected .glb layout for '" + filename + "'");
  }
  const std::size_t json_bytes = glb_u32(glb, 12);
  if (20 + json_bytes > glb.size()) throw IoError("assimp wrote a truncated .glb for '" + filename + "'");
  nlohmann::json j = nlohmann::json::parse(glb.substr(20, json_bytes));
  nlohmann::json extras = nlohmann::json::object();
  for (const auto& [key, value] : desc.user_properties) extras[key] = value;
  j["asset"]["extras"] = extras;
  if (j.contains("scenes") && !j["scenes"].empty() && j["scenes"][0].contains("nodes")) {
    for (const auto& root : j["scenes"][0]["nodes"]) j["nodes"][root.get<std::size_t>()]["extras"] = extras;
  }
  std::set<std::string> used;
  used_gltf_extensions(j, used);
  if (used.empty()) {
    j.erase("extensionsUsed");
  } else {
    j["extensionsUsed"] = used;
  }
  std::string text = j.dump();
  text.append((4 - text.size() % 4) % 4, ' ');  // chunks are 4-byte aligned, JSON padded with spaces
  const std::string rest = glb.substr(20 + json_bytes);
  std::string out = "glTF";
  put_glb_u32(out, 2);
  put_glb_u32(out, 12 + 8 + text.size() + rest.size());
  put_glb_u32(out, text.size());
  put_glb_u32(out, kJsonChunk);
  out += text;
  out += rest;
  return out;
}

std::vector<EncodedFile> encode_with_assimp(const fbx::SceneDesc& desc, MeshFormat format,
                                            const std::string& base_name) {
  const std::unique_ptr<aiScene> scene = make_ai_scene(desc);
  Assimp::Exporter exporter;
  const char* format_id = "glb2";
  const aiExportDataBlob* blob = exporter.ExportToBlob(scene.get(), format_id);
  if (blob == nullptr) {
    throw IoError("assimp could not encode '" + base_name + std::string(extension(format)) +
                  "': " + exporter.GetErrorString());
  }
  const auto bytes_of = [](const aiExportDataBlob* b) {
    return std::string(static_cast<const char*>(b->data), b->size);
  };
  std::vector<EncodedFile> files;
  files.push_back({base_name + std::string(extension(format)), bytes_of(blob)});
  if (format == MeshFormat::glb)
    files.front().bytes = add_glb_metadata(files.front().bytes, desc, files.front().filename);
  return files;
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
  for (unsigned i = 0; i < src.mNumVertices; ++i) {
    const aiVector3D p = to_world * src.mVertices[i];
    mesh.vertices.push_back(from_file_axes(p.x, p.y, p.z));
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

std::vector<EncodedFile> encode_mesh_scene(const MeshScene& scene, MeshFormat format,
                                           const std::string& base_name) {
  const fbx::SceneDesc desc = prepare_scene(scene);
  if (format == MeshFormat::fbx) {
    return {{base_name + ".fbx", fbx::encode_scene(desc)}};
  }
  if (format == MeshFormat::obj) {
    const std::string mtl_name = base_name + ".mtl";
    ObjText text = encode_obj(desc, mtl_name, obj_metadata_lines(desc));
    return {{base_name + ".obj", std::move(text.obj)}, {mtl_name, std::move(text.mtl)}};
  }
  return encode_with_assimp(desc, format, base_name);
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
  return out;
}

}  // namespace relief
