// `relief sight --xodr NAME.xodr [--scene NAME.glb] --out DIR`: every lane's sight distance on
// a built network (relief/pipeline/sight_files.h).
#include <iostream>
#include <memory>
#include <sstream>

#include "commands.h"
#include "console.h"
#include "options.h"
#include "relief/pipeline/sight_files.h"

namespace relief::cli {
namespace {

struct SightArgs {
  std::string xodr, scene, out;
  SightOptions options;
};

}  // namespace

Runner add_sight_command(CLI::App& app) {
  auto args = std::make_shared<SightArgs>();
  CLI::App* cmd = app.add_subcommand(
      "sight", "Sight distance of every lane of a relief build against AASHTO's stopping sight distance");
  cmd->add_option("--xodr", args->xodr, "the build's OpenDRIVE file")->required();
  cmd->add_option("--scene", args->scene, "the build's 3D scene (default: NAME.glb beside the .xodr)");
  cmd->add_option("--out", args->out, "output directory (NAME.sight.geojson, sight.json)")->required();
  cmd->add_option("--step", args->options.step_m, "stations along every lane, and the object's steps, m")
      ->capture_default_str()
      ->check(finite_positive());
  cmd->add_option("--eye-height", args->options.eye_height_m, "the driver's eye above the lane, m")
      ->capture_default_str()
      ->check(finite_positive());
  cmd->add_option("--object-height", args->options.object_height_m, "the object's height on the lane, m")
      ->capture_default_str()
      ->check(finite_positive());
  cmd->add_option("--reaction", args->options.reaction_s, "brake reaction time, s")
      ->capture_default_str()
      ->check(finite_positive());
  cmd->add_option("--deceleration", args->options.deceleration_mps2, "deceleration, m/s2")
      ->capture_default_str()
      ->check(finite_positive());
  cmd->add_flag("--measure", args->options.measure_beyond_required,
                "measure every station's sight distance up to 300 m (default: only as far as it needs)");
  cmd->add_flag("--junction-roads", args->options.junction_roads,
                "give the roads inside junctions stations too");
  return [args] {
    return run_reporting_errors([&] {
      const SightFilesResult r = sight_from_files(args->xodr, args->scene, args->out, args->options);
      const SightSummary& s = r.summary;
      std::ostringstream out;
      out << "relief sight: " << args->xodr << "\n"
          << "  checked    " << fixed(s.km_checked, 2) << " lane-km, " << s.stations << " stations\n"
          << "  short      " << fixed(s.km_short, 3) << " lane-km ("
          << fixed(s.km_checked > 0.0 ? 100.0 * s.km_short / s.km_checked : 0.0, 2) << " %) in "
          << s.stretches << " stretches\n";
      if (!s.worst.empty()) {
        const SightPlace& w = s.worst.front();
        out << "  worst      " << (w.name.empty() ? "road " + std::to_string(w.road) : w.name) << " (road "
            << w.road << ", lane " << w.lane << ", s " << fixed(w.s_from, 1) << "-" << fixed(w.s_to, 1)
            << "): " << fixed(w.available_m, 1) << " m of " << fixed(w.required_m, 1) << " m, hidden by "
            << w.obstacle << "\n";
      }
      out << "  rays       " << s.rays << " against " << s.obstacle_triangles << " triangles in "
          << fixed(s.seconds, 2) << " s\n";
      for (const auto& p : r.written) out << "  wrote      " << p.string() << "\n";
      std::cout << out.str();
      return static_cast<int>(kOk);
    });
  };
}

}  // namespace relief::cli
