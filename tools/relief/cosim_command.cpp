// `relief cosim`: SUMO's traffic set down on the 3D road surface of a relief build, every step.
#include <csignal>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <memory>

#include "commands.h"
#include "console.h"
#include "options.h"
#include "relief/cosim/cosim.h"
#include "relief/sight/lidar.h"

namespace relief::cli {
namespace {

volatile std::sig_atomic_t interrupted = 0;

extern "C" void on_interrupt(int /*signal*/) {
  interrupted = 1;
}

struct CosimArgs {
  std::string sumocfg;
  std::string out;
  CosimOptions options;
  double end_s = 0.0;
  double lidar_height_m = 1.9;
  bool traci = false, gui = false;
};

void print_spread(const char* label, const Spread& s, const char* unit, int digits) {
  std::cout << "  " << std::left << std::setw(16) << label << "p50 " << fixed(s.p50, digits) << unit
            << ", p99 " << fixed(s.p99, digits) << unit << ", max " << fixed(s.max, digits) << unit << "\n";
}

void print_result(const CosimResult& r, const std::string& out) {
  std::cout << "cosim      " << r.steps << " steps, " << fixed(r.simulated_s, 2) << " s simulated"
            << (r.stopped ? " (interrupted)" : "") << ", " << r.vehicles << " vehicles (at most "
            << r.max_vehicles << " at once), " << r.vehicle_steps << " placements\n";
  print_spread("z vs OpenDRIVE", r.z_error_m, " m", 4);
  print_spread("  on roads", r.z_error_on_roads_m, " m", 4);
  print_spread("  in junctions", r.z_error_in_junctions_m, " m", 4);
  print_spread("SUMO z vs ODR", r.sumo_z_error_m, " m", 4);
  print_spread("pitch vs slope", r.pitch_error_deg, " deg", 3);
  std::cout << "  wheels under   " << r.wheels_under_road << " (deepest " << fixed(r.wheel_under_m.max, 4)
            << " m)\n"
            << (r.egos > 0
                    ? "egos       " + std::to_string(r.egos) + ", sync error p50 " +
                          fixed(r.sync_error_m.p50, 3) + " m, p99 " + fixed(r.sync_error_m.p99, 3) +
                          " m, max " + fixed(r.sync_error_m.max, 3) + " m, " + std::to_string(r.resyncs) +
                          " resyncs, " + std::to_string(r.ego_steps_wheels_in_air) +
                          " steps with a wheel in the air\n"
                    : std::string())
            << (r.lidar.sensors > 0
                    ? "lidar      " + std::to_string(r.lidar.sensors) + " sensor(s), " +
                          std::to_string(r.lidar.sweeps) + " sweeps (" +
                          std::to_string(r.lidar.sweeps_written) + " written), " +
                          std::to_string(r.lidar.points) + " points; vehicles in range seen " +
                          std::to_string(r.lidar.seen) + " of " + std::to_string(r.lidar.checked) +
                          ", hidden by road " + std::to_string(r.lidar.hidden_by_road) + ", terrain " +
                          std::to_string(r.lidar.hidden_by_terrain) + ", vehicles " +
                          std::to_string(r.lidar.hidden_by_vehicle) + "\n"
                    : std::string())
            << "time       " << fixed(r.wall_s, 2) << " s wall (setup " << fixed(r.setup_s, 2) << " s, SUMO "
            << fixed(r.sumo_s, 2) << " s, relief " << fixed(r.relief_s, 2) << " s), "
            << fixed(r.real_time_factor(), 1) << "x real time\n"
            << "wrote      " << (std::filesystem::path(out) / kCosimReportFile).string()
            << ", the trajectories and the replay\n";
}

}  // namespace

Runner add_cosim_command(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "cosim", "Run SUMO on a relief build and set every vehicle, every step, on the 3D road surface");
  auto args = std::make_shared<CosimArgs>();
  cmd->add_option("--sumocfg", args->sumocfg,
                  "SUMO configuration whose net-file is a relief build's NAME.net.xml")
      ->required();
  cmd->add_option(
         "--out", args->out,
         std::string("Output directory (") + kCosimReportFile + ", NAME.fcd.xml, NAME.trajectories.csv)")
      ->required();
  cmd->add_option("--step", args->options.step_s, "Lockstep step in seconds (SUMO's --step-length)")
      ->check(finite_positive())
      ->capture_default_str();
  cmd->add_option("--end", args->end_s,
                  "Stop at this simulated time in seconds (default: the configuration's end)")
      ->check(finite_positive());
  cmd->add_option("--trajectory-period", args->options.trajectory_period_s,
                  "Write trajectory rows this often in seconds (0: every step)")
      ->check(finite_non_negative())
      ->capture_default_str();
  cmd->add_option("--replay-period", args->options.replay_period_s,
                  std::string("Key the replay ") + kCosimReplayFile + " this often in seconds (0: no replay)")
      ->check(finite_non_negative())
      ->capture_default_str();
  cmd->add_option("--ego", args->options.egos,
                  "A vehicle the physics drives (Bullet; repeatable): its pose goes back to SUMO every step");
  cmd->add_option("--egos", args->options.ego_count,
                  "Also drive the first N vehicles to depart (of --ego-type when given) as egos")
      ->capture_default_str();
  cmd->add_option("--ego-type", args->options.ego_type, "SUMO vehicle type the --egos are taken from");
  cmd->add_option("--resync", args->options.resync_m,
                  "Set an ego back onto SUMO's lane when the two lie this many metres apart after a step")
      ->check(finite_positive())
      ->capture_default_str();
  cmd->add_option_function<std::vector<std::string>>(
         "--lidar",
         [args](const std::vector<std::string>& items) {
           for (const std::string& item : items) {
             LidarMount m;
             const std::size_t at = item.find('@');
             m.preset = item.substr(0, at);
             if (at != std::string::npos) m.ego = item.substr(at + 1);
             parse_for("--lidar", [&] { (void)lidar_preset(m.preset); });
             args->options.lidars.push_back(m);
           }
         },
         "A LiDAR on an ego, PRESET[@EGO] (carla-default, hdl-32e, hdl-64e, os1-64; default: the first ego); "
         "repeatable. Point clouds in OUT/lidar/EGO/, occlusion figures in cosim.json")
      ->type_name("PRESET[@EGO]");
  cmd->add_option(
         "--lidar-min-returns", args->options.lidar_min_returns,
         "A vehicle in a LiDAR's range and view counts as seen with at least this many returns on it")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--lidar-every", args->options.lidar_every_s,
                  "Write a LiDAR's point cloud (PCD and PLY, one turn) every this many simulated seconds")
      ->check(finite_non_negative())
      ->capture_default_str();
  cmd->add_option("--lidar-height", args->lidar_height_m, "LiDARs' height over the ground under the ego, m")
      ->check(finite_positive())
      ->capture_default_str();
  cmd->add_option("--mesh-tolerance", args->options.mesh_tolerance_m,
                  "Chord tolerance in metres of the road surface the vehicles are set on")
      ->check(finite_positive())
      ->capture_default_str();
  // SUMO in this process by default; over TraCI as CARLA's bridge offers it (run_synchronization.py's
  // --sumo-gui, --sumo-host and --sumo-port).
  auto* traci =
      cmd->add_flag("--traci", args->traci,
                    "Run SUMO as its own process (sumo) and talk TraCI to it instead of in this process");
  auto* gui =
      cmd->add_flag("--sumo-gui", args->gui, "Run sumo-gui over TraCI, to watch the traffic as it runs");
  auto* port = cmd->add_option("--sumo-port", args->options.sumo.port,
                               "Attach over TraCI to a SUMO already running on this configuration with "
                               "--remote-port PORT (and the same --step-length)")
                   ->check(CLI::Range(1, 65535));
  cmd->add_option("--sumo-host", args->options.sumo.host, "Host of the SUMO of --sumo-port")
      ->needs(port)
      ->capture_default_str();
  port->excludes(traci)->excludes(gui);
  traci->excludes(gui);
  return [args, cmd] {
    return run_reporting_errors([&] {
      if (cmd->count("--end") > 0) args->options.end_s = args->end_s;
      for (LidarMount& m : args->options.lidars) m.height_m = args->lidar_height_m;
      SumoEndpoint& sumo = args->options.sumo;
      if (args->traci || args->gui) {
        sumo.mode = SumoEndpoint::Mode::launch;
        sumo.program = args->gui ? "sumo-gui" : "sumo";
      }
      if (cmd->count("--sumo-port") > 0) sumo.mode = SumoEndpoint::Mode::attach;
      args->options.progress = [](double t, std::size_t vehicles) {
        std::cerr << "relief: cosim t = " << fixed(t, 1) << " s, " << vehicles << " vehicles\n";
      };
      args->options.stop_requested = [] { return interrupted != 0; };
      std::signal(SIGINT, on_interrupt);
      Diagnostics diagnostics;
      print_diagnostics_live(diagnostics, false);
      const CosimResult result =
          run_cosim(find_cosim_inputs(args->sumocfg), args->options, args->out, diagnostics);
      std::signal(SIGINT, SIG_DFL);
      print_result(result, args->out);
      print_diagnostics_summary(diagnostics);
      return static_cast<int>(kOk);
    });
  };
}

}  // namespace relief::cli
