#pragma once
// Sub-commands of the relief CLI. Each registers its options on the parent app and returns a
// runner that is called after parsing; runners return the process exit code.

#include <CLI/CLI.hpp>

#include <functional>

namespace relief::cli {

/// Documented exit codes.
/// 4: built, and every output written, but outputs failed quality gates (quality_gates.h).
enum ExitCode : int { kOk = 0, kInternalError = 1, kUsage = 2, kBadInput = 3, kGateFailed = 4 };

using Runner = std::function<int()>;

Runner add_build_command(CLI::App& app);
Runner add_info_command(CLI::App& app);
Runner add_mesh_report_command(CLI::App& app);
Runner add_cosim_command(CLI::App& app);
Runner add_demand_command(CLI::App& app);
Runner add_sight_command(CLI::App& app);
Runner add_lidar_command(CLI::App& app);
Runner add_tiles_command(CLI::App& app);

}  // namespace relief::cli
