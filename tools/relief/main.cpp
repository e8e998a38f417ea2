// relief: elevation-aware 3D road networks from OpenStreetMap and DEMs.
// Exit codes: 0 done, 1 internal error, 2 bad usage, 3 bad input, 4 built but outputs failed
// quality gates.
#include <iostream>

#include "commands.h"
#include "relief/export/report_writer.h"

// The runners catch every exception (options.cpp); CLI11 throws from the set-up below only for a
// defect in the option definitions, which may abort.
int main(int argc, char** argv) {  // NOLINT(bugprone-exception-escape)
  using namespace relief::cli;
  CLI::App app{"relief " + relief::relief_version() +
               ": elevation-aware 3D road networks from OpenStreetMap and DEMs\n"
               "Exit codes: 0 done, 1 internal error, 2 bad usage, 3 bad input, 4 built but outputs failed "
               "quality gates."};
  app.set_version_flag("--version", relief::relief_version());
  app.require_subcommand(1);
  const Runner build = add_build_command(app);
  const Runner info = add_info_command(app);
  const Runner mesh_report = add_mesh_report_command(app);
  const Runner cosim = add_cosim_command(app);
  const Runner demand = add_demand_command(app);
  const Runner sight = add_sight_command(app);
  const Runner lidar = add_lidar_command(app);
  const Runner tiles = add_tiles_command(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return kUsage;
  }
  if (app.got_subcommand("build")) return build();
  if (app.got_subcommand("info")) return info();
  if (app.got_subcommand("mesh-report")) return mesh_report();
  if (app.got_subcommand("cosim")) return cosim();
  if (app.got_subcommand("demand")) return demand();
  if (app.got_subcommand("sight")) return sight();
  if (app.got_subcommand("lidar")) return lidar();
  if (app.got_subcommand("tiles")) return tiles();
  return kUsage;
}
