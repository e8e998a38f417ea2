#pragma once
// The summary `relief build` prints on stdout: the failed quality gates first, then one line per
// figure of the run (network, elevation, fit, each output), the time and the files written.

#include <string>

#include "relief/pipeline/build.h"

namespace relief::cli {

/// The summary of a finished build, as lines ending in "\n"; the first names the run.
[[nodiscard]] std::string format_build_summary(const BuildResult& result);

}  // namespace relief::cli
