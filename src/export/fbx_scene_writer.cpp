#include "export/fbx_scene_writer.h"

#include "export/fbx_binary_writer.h"
#include "relief/core/errors.h"

namespace relief::fbx {
namespace {

// Fixed creation time and the FileId that goes with it (the pair Blender writes; FBX readers
// that check the file id against the time accept it).
constexpr char kCreationTime[] = "1970-01-01 10:00:00:000";
constexpr unsigned char kFileId[16] = {0x28, 0xb3, 0x2a, 0xeb, 0xb6, 0x24, 0xcc, 0xc2,
                                       0xbf, 0xc8, 0xb0, 0x2a, 0xa9, 0x2b, 0xfc, 0xf1};

// Object names in binary FBX are "name\0\x01Class".
std::string object_name(const std::string& name, const char* fbx_class) {
  return name + std::string("\0\x01", 2) + fbx_class;
}

// One Properties70 entry: P: name, type, label, flags, values...
void add_p(Node& props, const char* name, const char* type, const char* label, const char* flags,
           std::vector<Property> values) {
  std::vector<Property> p{std::string(name), std::string(type), std::string(label), std::string(flags)};
  for (auto& v : values) p.push_back(std::move(v));
  props.add("P", std::move(p));
}

void add_user_properties(Node& props, const SceneDesc& scene) {
  for (const auto& [key, value] : scene.user_properties) {
    add_p(props, key.c_str(), "KString", "", "U", {value});
  }
}

Node header_extension(const SceneDesc& scene) {
  Node h{"FBXHeaderExtension", {}, {}};
  h.add("FBXHeaderVersion", {std::int32_t{1003}});
  h.add("FBXVersion", {static_cast<std::int32_t>(kVersion)});
  h.add("EncryptionType", {std::int32_t{0}});
  Node& stamp = h.add("CreationTimeStamp");
  stamp.add("Version", {std::int32_t{1000}});
  stamp.add("Year", {std::int32_t{1970}});
  stamp.add("Month", {std::int32_t{1}});
  stamp.add("Day", {std::int32_t{1}});
  stamp.add("Hour", {std::int32_t{10}});
  stamp.add("Minute", {std::int32_t{0}});
  stamp.add("Second", {std::int32_t{0}});
  stamp.add("Millisecond", {std::int32_t{0}});
  h.add("Creator", {scene.creator});
  // Document-level user data: the same georeference for tools that read SceneInfo.
  Node& info = h.add("SceneInfo", {object_name("GlobalInfo", "SceneInfo"), std::string("UserData")});
  info.add("Type", {std::string("UserData")});
  info.add("Version", {std::int32_t{100}});
  Node& meta = info.add("MetaData");
  meta.add("Version", {std::int32_t{100}});
  for (const char* field : {"Title", "Subject", "Author", "Keywords", "Revision", "Comment"}) {
    meta.add(field, {std::string()});
  }
  add_user_properties(info.add("Properties70"), scene);
  return h;
}

// Y up, front +Z, coord +X (right-handed, glTF's axes); 1 unit = 100 cm.
Node global_settings() {
  Node g{"GlobalSettings", {}, {}};
  g.add("Version", {std::int32_t{1000}});
  Node& p = g.add("Properties70");
  add_p(p, "UpAxis", "int", "Integer", "", {std::int32_t{1}});
  add_p(p, "UpAxisSign", "int", "Integer", "", {std::int32_t{1}});
  add_p(p, "FrontAxis", "int", "Integer", "", {std::int32_t{2}});
  add_p(p, "FrontAxisSign", "int", "Integer", "", {std::int32_t{1}});
  add_p(p, "CoordAxis", "int", "Integer", "", {std::int32_t{0}});
  add_p(p, "CoordAxisSign", "int", "Integer", "", {std::int32_t{1}});
  add_p(p, "OriginalUpAxis", "int", "Integer", "", {std::int32_t{1}});
  add_p(p, "OriginalUpAxisSign", "int", "Integer", "", {std::int32_t{1}});
  add_p(p, "UnitScaleFactor", "double", "Number", "", {100.0});
  add_p(p, "OriginalUnitScaleFactor", "double", "Number", "", {100.0});
  return g;
}

Node geometry(std::int64_t id, const MeshDesc& mesh, const std::array<double, 3>& offset) {
  Node g{"Geometry", {id, object_name(mesh.name, "Geometry"), std::string("Mesh")}, {}};
  g.add("GeometryVersion", {std::int32_t{124}});
  std::vector<double> xyz;
  xyz.reserve(3 * mesh.positions.size());
  for (const auto& p : mesh.positions) {
    for (std::size_t k = 0; k < 3; ++k) xyz.push_back(double{p[k]} + offset[k]);
  }
  g.add_one("Vertices", std::move(xyz));
  // The last index of each polygon is stored as -(index + 1).
  std::vector<std::int32_t> polygon_vertices;
  polygon_vertices.reserve(3 * mesh.triangles.size());
  for (const auto& t : mesh.triangles) {
    polygon_vertices.push_back(static_cast<std::int32_t>(t[0]));
    polygon_vertices.push_back(static_cast<std::int32_t>(t[1]));
    polygon_vertices.push_back(-static_cast<std::int32_t>(t[2]) - 1);
  }
  g.add_one("PolygonVertexIndex", std::move(polygon_vertices));

  std::vector<const char*> layer_elements;
  if (!mesh.normals.empty()) {
    Node& n = g.add("LayerElementNormal", {std::int32_t{0}});
    n.add("Version", {std::int32_t{101}});
    n.add("Name", {std::string()});
    n.add("MappingInformationType", {std::string("ByVertice")});
    n.add("ReferenceInformationType", {std::string("Direct")});
    std::vector<double> normals;
    normals.reserve(3 * mesh.normals.size());
    for (const auto& v : mesh.normals) normals.insert(normals.end(), v.begin(), v.end());
    n.add_one("Normals", std::move(normals));
    layer_elements.push_back("LayerElementNormal");
  }
  if (!mesh.uvs.empty()) {
    Node& n = g.add("LayerElementUV", {std::int32_t{0}});
    n.add("Version", {std::int32_t{101}});
    n.add("Name", {std::string("UVMap")});
    n.add("MappingInformationType", {std::string("ByVertice")});
    n.add("ReferenceInformationType", {std::string("Direct")});
    std::vector<double> uvs;
    uvs.reserve(2 * mesh.uvs.size());
    for (const auto& v : mesh.uvs) uvs.insert(uvs.end(), v.begin(), v.end());
    n.add_one("UV", std::move(uvs));
    layer_elements.push_back("LayerElementUV");
  }
  {
    Node& n = g.add("LayerElementMaterial", {std::int32_t{0}});
    n.add("Version", {std::int32_t{101}});
    n.add("Name", {std::string()});
    n.add("MappingInformationType", {std::string("AllSame")});
    n.add("ReferenceInformationType", {std::string("IndexToDirect")});
    n.add("Materials", {std::vector<std::int32_t>{0}});
    layer_elements.push_back("LayerElementMaterial");
  }
  Node& layer = g.add("Layer", {std::int32_t{0}});
  layer.add("Version", {std::int32_t{100}});
  for (const char* type : layer_elements) {
    Node& e = layer.add("LayerElement");
    e.add("Type", {std::string(type)});
    e.add("TypedIndex", {std::int32_t{0}});
  }
  return g;
}

Node model(std::int64_t id, const MeshDesc& mesh, const SceneDesc& scene) {
  Node m{"Model", {id, object_name(mesh.name, "Model"), std::string("Mesh")}, {}};
  m.add("Version", {std::int32_t{232}});
  add_user_properties(m.add("Properties70"), scene);
  m.add("Shading", {true});
  m.add("Culling", {std::string("CullingOff")});
  return m;
}

Node material(std::int64_t id, const MaterialDesc& mat) {
  Node m{"Material", {id, object_name(mat.name, "Material"), std::string()}, {}};
  m.add("Version", {std::int32_t{102}});
  m.add("ShadingModel", {std::string("lambert")});
  m.add("MultiLayer", {std::int32_t{0}});
  Node& p = m.add("Properties70");
  const auto& c = mat.diffuse_rgb;
  add_p(p, "DiffuseColor", "Color", "", "A", {double{c[0]}, double{c[1]}, double{c[2]}});
  add_p(p, "DiffuseFactor", "Number", "", "A", {1.0});
  return m;
}

Node object_type(const char* type, std::int32_t count) {
  Node t{"ObjectType", {std::string(type)}, {}};
  t.add("Count", {count});
  return t;
}

}  // namespace

std::string encode_scene(const SceneDesc& scene) {
  for (const MeshDesc& mesh : scene.meshes) {
    if (mesh.material >= scene.materials.size()) {
      throw InvalidInput("FBX: mesh '" + mesh.name + "' uses material " + std::to_string(mesh.material) +
                         " of " + std::to_string(scene.materials.size()));
    }
  }
  // Object ids: any distinct non-zero int64 (0 is the scene root).
  constexpr std::int64_t kDocumentId = 1000;
  const auto material_id = [](std::size_t i) { return std::int64_t{2000000} + static_cast<std::int64_t>(i); };
  const auto model_id = [](std::size_t i) { return std::int64_t{3000000} + static_cast<std::int64_t>(i); };
  const auto geometry_id = [](std::size_t i) { return std::int64_t{4000000} + static_cast<std::int64_t>(i); };
  const auto n_meshes = static_cast<std::int32_t>(scene.meshes.size());
  const auto n_materials = static_cast<std::int32_t>(scene.materials.size());

  std::vector<Node> root;
  root.push_back(header_extension(scene));
  root.push_back(
      Node{"FileId", {Raw{std::string(reinterpret_cast<const char*>(kFileId), sizeof kFileId)}}, {}});
  root.push_back(Node{"CreationTime", {std::string(kCreationTime)}, {}});
  root.push_back(Node{"Creator", {scene.creator}, {}});
  root.push_back(global_settings());

  Node documents{"Documents", {}, {}};
  documents.add("Count", {std::int32_t{1}});
  Node& document = documents.add("Document", {kDocumentId, std::string("Scene"), std::string("Scene")});
  Node& doc_props = document.add("Properties70");
  add_p(doc_props, "SourceObject", "object", "", "", {});
  add_p(doc_props, "ActiveAnimStackName", "KString", "", "", {std::string()});
  document.add("RootNode", {std::int64_t{0}});
  root.push_back(std::move(documents));

  root.push_back(Node{"References", {}, {}});

  Node definitions{"Definitions", {}, {}};
  definitions.add("Version", {std::int32_t{100}});
  definitions.add("Count", {1 + 2 * n_meshes + n_materials});
  definitions.children.push_back(object_type("GlobalSettings", 1));
  definitions.children.push_back(object_type("Model", n_meshes));
  definitions.children.push_back(object_type("Geometry", n_meshes));
  definitions.children.push_back(object_type("Material", n_materials));
  root.push_back(std::move(definitions));

  Node objects{"Objects", {}, {}};
  for (std::size_t i = 0; i < scene.meshes.size(); ++i) {
    objects.children.push_back(geometry(geometry_id(i), scene.meshes[i], scene.offset));
    objects.children.push_back(model(model_id(i), scene.meshes[i], scene));
  }
  for (std::size_t i = 0; i < scene.materials.size(); ++i) {
    objects.children.push_back(material(material_id(i), scene.materials[i]));
  }
  root.push_back(std::move(objects));

  // Connections: model -> root, geometry -> model, material -> model (object-object links).
  Node connections{"Connections", {}, {}};
  for (std::size_t i = 0; i < scene.meshes.size(); ++i) {
    connections.add("C", {std::string("OO"), model_id(i), std::int64_t{0}});
    connections.add("C", {std::string("OO"), geometry_id(i), model_id(i)});
    connections.add("C", {std::string("OO"), material_id(scene.meshes[i].material), model_id(i)});
  }
  root.push_back(std::move(connections));
  return encode_binary(root);
}

}  // namespace relief::fbx
