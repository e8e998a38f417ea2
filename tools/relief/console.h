#pragma once
// What the CLI prints: progress and diagnostics on stderr, summaries on stdout.

#include <string>

#include "relief/core/diagnostics.h"
#include "relief/pipeline/build.h"

namespace relief::cli {

/// Progress callback printing "relief: <stage> ... <seconds> s" to stderr (silent if quiet).
[[nodiscard]] ProgressFn stderr_progress(bool quiet);

/// Prints the first few diagnostics of each code to stderr as they arrive.
void print_diagnostics_live(Diagnostics& diagnostics, bool quiet);

/// Prints how many diagnostics of each code were reported, to stderr.
void print_diagnostics_summary(const Diagnostics& diagnostics);

/// Formats a number with `digits` decimals.
[[nodiscard]] std::string fixed(double value, int digits);

}  // namespace relief::cli
