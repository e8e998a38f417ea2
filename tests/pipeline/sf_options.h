#pragma once
// Build options for the real San Francisco data in ../shared/data, shared by the pipeline tests
// (callers skip with RELIEF_REQUIRE_SHARED_DATA when the data is absent).

#include <string>

#include "relief/pipeline/build.h"

namespace relief::test {

/// Potrero Hill: the small OSM extract on the 1/3" USGS DEM subsection; outputs into the
/// scratch directory `out`.
[[nodiscard]] BuildOptions potrero_options(const std::string& out);

/// North-east San Francisco (2017 drive network) on the 30 m USGS 24k DEM.
[[nodiscard]] BuildOptions ne_options(const std::string& out);

}  // namespace relief::test
