#include "export/obj_writer.h"

#include <charconv>

namespace relief {
namespace {

// Shortest text that reads back as the same float.
void append_float(std::string& out, float value) {
  char buffer[32];
  const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, value);
  out.append(buffer, ec == std::errc() ? end : buffer);
}

// Shortest text that reads back as the same double.
void append_double(std::string& out, double value) {
  char buffer[32];
  const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, value);
  out.append(buffer, ec == std::errc() ? end : buffer);
}

void append_uint(std::string& out, std::size_t value) {
  char buffer[24];
  const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, value);
  out.append(buffer, ec == std::errc() ? end : buffer);
}

}  // namespace

void write_obj(const fbx::SceneDesc& scene, const std::string& mtl_name, const std::string& metadata_lines,
               std::ostream& out) {
  constexpr std::size_t kChunk = std::size_t{1} << 20;
  std::string o;
  o.reserve(kChunk + 4096);
  // Hands the text so far to the stream once it fills a chunk.
  const auto flush = [&](bool always) {
    if (!always && o.size() < kChunk) return;
    out.write(o.data(), static_cast<std::streamsize>(o.size()));
    o.clear();
  };
  o += "# written by relief\n";
  o += metadata_lines;
  o += "\nmtllib " + mtl_name + "\n";
  // Indices in OBJ are global and 1-based: each mesh's vertices follow the previous ones.
  std::size_t v_base = 1, vt_base = 1, vn_base = 1;
  for (const fbx::MeshDesc& mesh : scene.meshes) {
    o +=
        "\no " + mesh.name + "\ng " + mesh.name + "\nusemtl " + scene.materials.at(mesh.material).name + "\n";
    const bool offset = scene.offset != std::array<double, 3>{0.0, 0.0, 0.0};
    for (const auto& p : mesh.positions) {
      o += "v";
      for (std::size_t k = 0; k < 3; ++k) {
        o += ' ';
        if (offset) {
          append_double(o, double{p[k]} + scene.offset[k]);  // exact: see SceneDesc::offset
        } else {
          append_float(o, p[k]);
        }
      }
      o += '\n';
      flush(false);
    }
    for (const auto& uv : mesh.uvs) {
      o += "vt ";
      append_float(o, uv[0]);
      o += ' ';
      append_float(o, uv[1]);
      o += '\n';
      flush(false);
    }
    for (const auto& n : mesh.normals) {
      o += "vn ";
      append_float(o, n[0]);
      o += ' ';
      append_float(o, n[1]);
      o += ' ';
      append_float(o, n[2]);
      o += '\n';
      flush(false);
    }
    const bool uvs = !mesh.uvs.empty(), normals = !mesh.normals.empty();
    for (const auto& t : mesh.triangles) {
      o += 'f';
      for (const std::uint32_t i : t) {
        o += ' ';
        append_uint(o, v_base + i);
        if (uvs || normals) {
          o += '/';
          if (uvs) append_uint(o, vt_base + i);
          if (normals) {
            o += '/';
            append_uint(o, vn_base + i);
          }
        }
      }
      o += '\n';
      flush(false);
    }
    v_base += mesh.positions.size();
    vt_base += mesh.uvs.size();
    vn_base += mesh.normals.size();
  }
  flush(true);
}

std::string encode_mtl(const fbx::SceneDesc& scene) {
  std::string m = "# written by relief\n";
  for (const fbx::MaterialDesc& mat : scene.materials) {
    m += "\nnewmtl " + mat.name + "\nKd ";
    append_float(m, mat.diffuse_rgb[0]);
    m += ' ';
    append_float(m, mat.diffuse_rgb[1]);
    m += ' ';
    append_float(m, mat.diffuse_rgb[2]);
    m += "\nillum 1\n";
  }
  return m;
}

}  // namespace relief
