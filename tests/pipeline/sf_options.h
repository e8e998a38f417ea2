#pragma once
// Build options for the real San Francisco data in ../shared/data, shared by the pipeline tests
// (callers skip with RELIEF_REQUIRE_SHARED_DATA when the data is absent).

#include <cstddef>
#include <map>
#include <string>

#include "relief/pipeline/build.h"

namespace relief::test {

/// Potrero Hill: the small OSM extract on the 1/3" USGS DEM subsection; outputs into the
/// scratch directory `out`.
[[nodiscard]] BuildOptions potrero_options(const std::string& out);

/// North-east San Francisco (2017 drive network) on the 30 m USGS 24k DEM.
[[nodiscard]] BuildOptions ne_options(const std::string& out);

/// One build of an SF set with the default BuildOptions (every output, every mesh format, the
/// methods compared), shared by the tests that only read its outputs.
struct SfBuild {
  BuildOptions options;
  BuildResult result;
  std::map<std::string, std::size_t> diagnostics;  ///< count per code
};

/// Potrero (potrero_options) built once per process, into <tmp>/shared/sf-potrero; the tests
/// that read it are the suite SfPotrero, which ctest runs in one process (tests/CMakeLists.txt).
/// A failed build throws in every test that asks for it.
[[nodiscard]] const SfBuild& sf_potrero();

/// The north-east quadrant (ne_options) built once per process, into <tmp>/shared/sf-ne; read
/// by the suite SfNortheast.
[[nodiscard]] const SfBuild& sf_northeast();

}  // namespace relief::test
