#pragma once
// The options of `relief build`, shared by the commands that run builds (`relief tiles`).
#include <CLI/CLI.hpp>
#include <string>

#include "relief/pipeline/build.h"

namespace relief::cli {

// What `relief build` parses into: the library's options, bound field by field, and what only
// the CLI knows (how loud to be, what a failed gate means for the exit code).
struct BuildCommandArgs {
  BuildOptions options;
  bool quiet = false;
  std::string fit_trace;  ///< file for the profile fit solver's progress, or empty
  std::string gate_mode = "enforce";
};

/// Registers every option of `relief build` but --out on `cmd`, bound to `*args` (which must
/// outlive the parse).
void add_build_options(CLI::App* cmd, BuildCommandArgs* args);

}  // namespace relief::cli
