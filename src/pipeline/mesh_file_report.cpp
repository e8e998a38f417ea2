#include "relief/pipeline/mesh_file_report.h"

#include "relief/export/mesh_report.h"
#include "relief/export/mesh_writer.h"

namespace relief {

MeshFileReport report_mesh_file(const std::filesystem::path& path, const MeshQualityOptions& options) {
  const MeshScene scene = read_mesh_file(path);
  MeshFileReport report;
  for (const TriangleMesh& mesh : scene.meshes) {
    report.meshes.push_back(analyse_mesh(weld_identical_vertices(mesh), options));
  }
  MeshReportExtras extras;
  extras.file = path.filename().string();
  report.json = mesh_report_json(report.meshes, extras);
  return report;
}

}  // namespace relief
