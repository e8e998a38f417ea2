// `relief info`: what the inputs hold and how well they fit, without building.
#include <iostream>
#include <memory>

#include "commands.h"
#include "console.h"
#include "options.h"
#include "relief/pipeline/info.h"

namespace relief::cli {
namespace {

std::string box_text(const LonLatBox& b) {
  return fixed(b.min_lon, 6) + "," + fixed(b.min_lat, 6) + "," + fixed(b.max_lon, 6) + "," +
         fixed(b.max_lat, 6);
}

void print_info(const InfoResult& info) {
  std::cout << "OSM        " << info.osm_path << "\n"
            << "  ways     " << info.ways_read << " read, " << info.highway_ways << " with highway, "
            << info.road_ways << " built as roads\n";
  if (info.osm_header_bounds)
    std::cout << "  bounds   " << box_text(*info.osm_header_bounds) << " (file header)\n";
  std::cout << "  roads    " << box_text(info.roads_bounds) << " (lon/lat of the road nodes)\n"
            << "frame      " << info.frame.crs() << ", origin " << fixed(info.frame.origin().x(), 1) << " "
            << fixed(info.frame.origin().y(), 1) << "\n"
            << "network    " << info.network.roads << " roads, " << info.network.junctions << " junctions ("
            << info.network.intersections << " intersections), " << info.network.dead_ends << " dead ends, "
            << fixed(info.network.length_km, 2) << " km, " << info.network.bridges << " bridges, "
            << info.network.tunnels << " tunnels\n";
  for (const DemInfo& d : info.dems) {
    std::cout << "DEM        " << d.path << "\n"
              << "  grid     " << d.width << " x " << d.height << " px of " << d.pixel_size.x() << " x "
              << d.pixel_size.y() << " (" << d.crs << ")\n"
              << "  unit     " << to_string(d.unit)
              << (d.unit_stated_by_user  ? " (stated)"
                  : d.unit_from_metadata ? " (metadata)"
                                         : " (assumed: metadata silent)")
              << ", nodata " << (d.nodata ? fixed(*d.nodata, 1) : std::string("none")) << "\n"
              << "  datum    " << d.transform_name;
    if (d.transform_accuracy_m) std::cout << ", accuracy " << fixed(*d.transform_accuracy_m, 2) << " m";
    std::cout << "\n";
    if (!d.missing_grids.empty())
      std::cout << "  note     a more accurate shift needs grid(s) " << d.missing_grids << "\n";
    if (d.extent_wgs84) std::cout << "  extent   " << box_text(*d.extent_wgs84) << "\n";
    std::cout << "  checks   " << d.implausible_cells << " cells of implausible height, " << d.spike_cells
              << " one-cell spikes or pits (treated as voids)\n";
    if (d.off_ground_cells > 0)
      std::cout << "  ground   " << d.off_ground_cells
                << " cells of buildings, trees or pits taken to the ground\n";
  }
  std::cout << "coverage   " << info.samples << " road samples: " << fixed(info.covered_percent, 2)
            << " % with height, " << fixed(info.void_percent, 2) << " % in voids, "
            << fixed(info.uncovered_percent, 2) << " % outside the DEM(s)\n";
}

}  // namespace

Runner add_info_command(CLI::App& app) {
  auto* cmd =
      app.add_subcommand("info", "Describe the OSM and DEM inputs and their coverage, without building");
  auto options = std::make_shared<BuildOptions>();
  add_input_options(*cmd, *options);
  return [options] {
    return run_reporting_errors([&] {
      Diagnostics diagnostics;
      print_diagnostics_live(diagnostics, false);
      print_info(inspect(*options, diagnostics));
      print_diagnostics_summary(diagnostics);
      return static_cast<int>(kOk);
    });
  };
}

}  // namespace relief::cli
