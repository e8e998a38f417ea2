#pragma once
// `relief mesh-report`: the mesh-quality figures of any mesh file (glTF, OBJ, FBX, PLY, STL, ...).

#include <filesystem>
#include <string>
#include <vector>

#include "relief/geometry/mesh_quality.h"

namespace relief {

struct MeshFileReport {
  std::vector<MeshQuality> meshes;  ///< one per mesh in the file, in file order
  std::string json;                 ///< mesh_report.json text (export/mesh_report.h)
};

/// Reads `path` (export/mesh_writer.h read_mesh_file), welds vertices at identical positions
/// (OBJ and FBX come back with one vertex per triangle corner) and analyses every mesh.
/// Throws IoError naming the file when it cannot be read.
[[nodiscard]] MeshFileReport report_mesh_file(const std::filesystem::path& path,
                                              const MeshQualityOptions& options);

}  // namespace relief
