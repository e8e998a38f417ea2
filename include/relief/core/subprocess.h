#pragma once
// Running an external program (SUMO's netconvert, duarouter, randomTrips.py) and collecting
// what it said: the library drives SUMO's own tools instead of re-implementing them.

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace relief {

struct ProcessResult {
  int exit_code = -1;  ///< the program's exit status; 128 + signal when it was killed
  std::string output;  ///< stdout and stderr, interleaved
};

/// Environment variables set (or replaced) for the child only.
using Environment = std::vector<std::pair<std::string, std::string>>;

/// Runs argv[0] (searched on PATH when it has no '/') with the arguments and this process's
/// environment plus `env`, in `working_dir` when given (tools that drop files in their working
/// directory leave them there), and waits for it. Throws IoError when the program cannot be
/// started.
[[nodiscard]] ProcessResult run_process(
    const std::vector<std::string>& argv, const Environment& env = {},
    const std::optional<std::filesystem::path>& working_dir = std::nullopt);

/// Full path of the executable `name`: looked for in each of `extra_dirs` first, then on PATH.
/// nullopt when none is found.
[[nodiscard]] std::optional<std::filesystem::path> find_executable(
    std::string_view name, const std::vector<std::filesystem::path>& extra_dirs = {});

}  // namespace relief
