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
    nlohmann::json view = {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bytes}};
    if (target != 0) view["target"] = target;  // animation data has none
    json_["bufferViews"].push_back(std::move(view));
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

// Appends the unit box (a mesh of its own), a node per track and the animation "replay".
void add_tracks(Document& doc, const std::vector<GlbTrack>& tracks, std::size_t material) {
  nlohmann::json& j = doc.json();
  std::vector<std::array<float, 3>> corners;
  corners.reserve(8);
  for (int k = 0; k < 8; ++k)
    corners.push_back({(k & 1) ? 0.5f : -0.5f, (k & 2) ? 0.5f : -0.5f, (k & 4) ? 0.5f : -0.5f});
  // Outward, counter-clockwise seen from outside.
  const std::vector<std::array<std::uint32_t, 3>> faces = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6},
                                                           {0, 1, 5}, {0, 5, 4}, {2, 6, 7}, {2, 7, 3},
                                                           {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
  const int positions = doc.add(corners, "VEC3", kFloat, kArrayBuffer, /*bounds=*/true);
  const int indices = doc.add(faces, "SCALAR", kUnsignedInt, kElementArrayBuffer, false);
  j["accessors"][static_cast<std::size_t>(indices)]["count"] = 3 * faces.size();
  j["meshes"].push_back({{"name", "Vehicle_Box"},
                         {"primitives", nlohmann::json::array({{{"attributes", {{"POSITION", positions}}},
                                                                {"indices", indices},
                                                                {"material", material},
                                                                {"mode", 4}}})}});
  const std::size_t box = j["meshes"].size() - 1;
  nlohmann::json samplers = nlohmann::json::array(), channels = nlohmann::json::array();
  for (const GlbTrack& t : tracks) {
    j["nodes"].push_back({{"name", t.name + "_box"},
                          {"mesh", box},
                          {"scale", t.size},
                          {"translation", {0.0f, 0.5f * t.size[1], 0.0f}}});
    const std::size_t child = j["nodes"].size() - 1;
    j["nodes"].push_back({{"name", t.name}, {"children", {child}}, {"scale", {0.0f, 0.0f, 0.0f}}});
    const std::size_t node = j["nodes"].size() - 1;
    j["nodes"][0]["children"].push_back(node);
    std::vector<std::array<float, 1>> times;
    for (const float time : t.times) times.push_back({time});
    const int input = doc.add(times, "SCALAR", kFloat, 0, /*bounds=*/true);
    const auto sampler = [&](int output, const char* interpolation) {
      samplers.push_back({{"input", input}, {"output", output}, {"interpolation", interpolation}});
      return samplers.size() - 1;
    };
    channels.push_back({{"sampler", sampler(doc.add(t.translations, "VEC3", kFloat, 0, false), "LINEAR")},
                        {"target", {{"node", node}, {"path", "translation"}}}});
    channels.push_back({{"sampler", sampler(doc.add(t.rotations, "VEC4", kFloat, 0, false), "LINEAR")},
                        {"target", {{"node", node}, {"path", "rotation"}}}});
    // Shown from its first key to hide_after_s: a STEP scale of 1 there, 0 before and after.
    std::vector<std::array<float, 1>> scale_times;
    std::vector<std::array<float, 3>> scales;
    if (t.times.front() > 0.0f) {
      scale_times.push_back({0.0f});
      scales.push_back({0.0f, 0.0f, 0.0f});
    }
    scale_times.push_back({t.times.front()});
    scales.push_back({1.0f, 1.0f, 1.0f});
    scale_times.push_back({t.hide_after_s});
    scales.push_back({0.0f, 0.0f, 0.0f});
    const int scale_input = doc.add(scale_times, "SCALAR", kFloat, 0, /*bounds=*/true);
    samplers.push_back({{"input", scale_input},
                        {"output", doc.add(scales, "VEC3", kFloat, 0, false)},
                        {"interpolation", "STEP"}});
    channels.push_back({{"sampler", samplers.size() - 1}, {"target", {{"node", node}, {"path", "scale"}}}});
  }
  j["animations"] =
      nlohmann::json::array({{{"name", "replay"}, {"samplers", samplers}, {"channels", channels}}});
}

std::string encode_glb(const fbx::SceneDesc& scene, const std::vector<GlbTrack>& tracks,
                       std::size_t track_material) {
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
  if (scene.offset != std::array<double, 3>{0.0, 0.0, 0.0}) j["nodes"][0]["translation"] = scene.offset;
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
  if (!tracks.empty()) add_tracks(doc, tracks, track_material);
  j["scenes"] = nlohmann::json::array({{{"nodes", {0}}}});
  j["scene"] = 0;
  return doc.glb();
}

}  // namespace relief
