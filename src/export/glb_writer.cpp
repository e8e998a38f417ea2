#include "export/glb_writer.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <limits>

namespace relief {
namespace {

constexpr std::uint32_t kGlbMagic = 0x46546C67;   // "glTF"
constexpr std::uint32_t kJsonChunk = 0x4E4F534A;  // "JSON"
constexpr std::uint32_t kBinChunk = 0x004E4942;   // "BIN\0"
constexpr int kFloat = 5126, kUnsignedInt = 5125;
constexpr int kArrayBuffer = 34962, kElementArrayBuffer = 34963;

void put_u32(std::string& out, std::uint32_t value) {
  out.append(reinterpret_cast<const char*>(&value), sizeof value);
}

// The glTF document and its binary buffer, built view by view.
class Document {
 public:
  /// Appends `count` elements of `components` values each as a buffer view with one accessor;
  /// returns the accessor's index. POSITION accessors carry min and max (the spec requires them).
  template <typename T, std::size_t N>
  int add(const std::vector<std::array<T, N>>& values, const char* type, int component_type, int target,
          bool bounds) {
    const std::size_t bytes = values.size() * N * sizeof(T);
    const std::size_t offset = bin_.size();
    bin_.resize(offset + bytes);
    if (bytes > 0) std::memcpy(bin_.data() + offset, values.data(), bytes);
    json_["bufferViews"].push_back(
        {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bytes}, {"target", target}});
    nlohmann::json accessor = {{"bufferView", json_["bufferViews"].size() - 1},
                               {"componentType", component_type},
                               {"count", values.size()},
                               {"type", type}};
    if (bounds && !values.empty()) {
      std::array<T, N> lo, hi;
      lo.fill(std::numeric_limits<T>::max());
      hi.fill(std::numeric_limits<T>::lowest());
      for (const auto& v : values) {
        for (std::size_t k = 0; k < N; ++k) {
          lo[k] = std::min(lo[k], v[k]);
          hi[k] = std::max(hi[k], v[k]);
        }
      }
      accessor["min"] = lo;
      accessor["max"] = hi;
    }
    json_["accessors"].push_back(std::move(accessor));
    return static_cast<int>(json_["accessors"].size() - 1);
  }

  nlohmann::json& json() { return json_; }

  [[nodiscard]] std::string glb() {
    json_["buffers"] = nlohmann::json::array({{{"byteLength", bin_.size()}}});
    std::string text = json_.dump();
    text.append((4 - text.size() % 4) % 4, ' ');  // chunks are 4-byte aligned: JSON pads with spaces
    bin_.append((4 - bin_.size() % 4) % 4, '\0');
    std::string out;
    out.reserve(12 + 8 + text.size() + 8 + bin_.size());
    put_u32(out, kGlbMagic);
    put_u32(out, 2);
    put_u32(out, static_cast<std::uint32_t>(12 + 8 + text.size() + 8 + bin_.size()));
    put_u32(out, static_cast<std::uint32_t>(text.size()));
    put_u32(out, kJsonChunk);
    out += text;
    put_u32(out, static_cast<std::uint32_t>(bin_.size()));
    put_u32(out, kBinChunk);
    out += bin_;
    return out;
  }

 private:
  nlohmann::json json_ = {{"bufferViews", nlohmann::json::array()}, {"accessors", nlohmann::json::array()}};
  std::string bin_;
};

}  // namespace

std::string encode_glb(const fbx::SceneDesc& scene) {
  Document doc;
  nlohmann::json& j = doc.json();
  nlohmann::json extras = nlohmann::json::object();
  for (const auto& [key, value] : scene.user_properties) extras[key] = value;
  j["asset"] = {{"version", "2.0"}, {"generator", scene.creator}, {"extras", extras}};
  j["materials"] = nlohmann::json::array();
  for (const fbx::MaterialDesc& m : scene.materials) {
    const auto& c = m.diffuse_rgb;
    j["materials"].push_back(
        {{"name", m.name},
         {"pbrMetallicRoughness", {{"baseColorFactor", {c[0], c[1], c[2], 1.0f}}, {"metallicFactor", 0.0}}}});
  }
  j["meshes"] = nlohmann::json::array();
  j["nodes"] = nlohmann::json::array(
      {{{"name", "relief"}, {"extras", extras}, {"children", nlohmann::json::array()}}});
  for (const fbx::MeshDesc& mesh : scene.meshes) {
    nlohmann::json attributes = {
        {"POSITION", doc.add(mesh.positions, "VEC3", kFloat, kArrayBuffer, /*bounds=*/true)}};
    if (!mesh.normals.empty())
      attributes["NORMAL"] = doc.add(mesh.normals, "VEC3", kFloat, kArrayBuffer, false);
    if (!mesh.uvs.empty()) {
      // glTF puts the texture's origin at its top left: v runs down.
      std::vector<std::array<float, 2>> uvs(mesh.uvs);
      for (auto& uv : uvs) uv[1] = 1.0f - uv[1];
      attributes["TEXCOORD_0"] = doc.add(uvs, "VEC2", kFloat, kArrayBuffer, false);
    }
    const int indices = doc.add(mesh.triangles, "SCALAR", kUnsignedInt, kElementArrayBuffer, false);
    // Indices are scalars: three per triangle.
    j["accessors"][static_cast<std::size_t>(indices)]["count"] = 3 * mesh.triangles.size();
    j["meshes"].push_back({{"name", mesh.name},
                           {"primitives", nlohmann::json::array({{{"attributes", attributes},
                                                                  {"indices", indices},
                                                                  {"material", mesh.material},
                                                                  {"mode", 4}}})}});
    j["nodes"].push_back({{"name", mesh.name}, {"mesh", j["meshes"].size() - 1}});
    j["nodes"][0]["children"].push_back(j["nodes"].size() - 1);
  }
  j["scenes"] = nlohmann::json::array({{{"nodes", {0}}}});
  j["scene"] = 0;
  return doc.glb();
}

}  // namespace relief
