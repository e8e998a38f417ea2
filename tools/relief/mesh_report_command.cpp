// `relief mesh-report FILE`: the quality of every mesh in a mesh file, as a table and JSON.
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>

#include "commands.h"
#include "console.h"
#include "options.h"
#include "relief/core/atomic_file.h"
#include "relief/pipeline/mesh_file_report.h"

namespace relief::cli {
namespace {

struct MeshReportArgs {
  std::string file;
  std::string json_out;
  bool no_self_intersections = false;
};

}  // namespace

Runner add_mesh_report_command(CLI::App& app) {
  auto args = std::make_shared<MeshReportArgs>();
  CLI::App* cmd = app.add_subcommand(
      "mesh-report", "Report the quality of every mesh in a mesh file (glb, gltf, obj, fbx, ply, stl, ...)");
  cmd->add_option("file", args->file, "mesh file")->required();
  cmd->add_option("--json", args->json_out,
                  "also write the report as JSON to this file ('-': stdout only JSON)");
  cmd->add_flag("--no-self-intersections", args->no_self_intersections,
                "skip the (costly) self-intersection test");
  return [args] {
    return run_reporting_errors([&] {
      MeshQualityOptions options;
      options.self_intersections = !args->no_self_intersections;
      const MeshFileReport report = report_mesh_file(args->file, options);
      if (args->json_out == "-") {
        std::cout << report.json;
        return static_cast<int>(kOk);
      }
      std::ostringstream out;
      out << "relief mesh-report: " << args->file << "\n";
      out << std::left << std::setw(24) << "  mesh" << std::right << std::setw(9) << "vertices"
          << std::setw(10) << "triangles" << std::setw(6) << "comp" << std::setw(7) << "holes" << std::setw(9)
          << "non-man" << std::setw(9) << "self-x" << std::setw(9) << "flipped" << std::setw(8) << "sliver"
          << std::setw(10) << "min-angle"
          << "\n";
      for (const MeshQuality& q : report.meshes) {
        out << "  " << std::left << std::setw(22) << q.name.substr(0, 22) << std::right << std::setw(9)
            << q.vertices << std::setw(10) << q.triangles << std::setw(6) << q.components << std::setw(7)
            << q.holes << std::setw(9) << q.non_manifold_edges << std::setw(9)
            << (options.self_intersections ? std::to_string(q.self_intersecting_pairs) : "-") << std::setw(9)
            << q.upside_down_triangles << std::setw(8) << q.sliver_triangles << std::setw(10)
            << fixed(q.min_angle_deg, 2) << "\n";
      }
      std::cout << out.str();
      if (!args->json_out.empty()) write_file_atomically(args->json_out, report.json);
      return static_cast<int>(kOk);
    });
  };
}

}  // namespace relief::cli
