#include "pipeline/sf_options.h"

#include <filesystem>

#include "support/test_data.h"

namespace relief::test {
namespace {

// Not scratch_dir: the first test to ask would name the folder, and the build outlives it.
SfBuild build_shared(BuildOptions o, const std::string& folder) {
  o.out_dir = std::filesystem::path(RELIEF_TEST_TMP_DIR) / "shared" / folder;
  std::filesystem::remove_all(o.out_dir);
  std::filesystem::create_directories(o.out_dir);
  SfBuild b{o, {}, {}};
  Diagnostics d;
  b.result = build(o, d);
  b.diagnostics = d.counts();
  return b;
}

}  // namespace

BuildOptions potrero_options(const std::string& out) {
  BuildOptions o;
  o.osm_path = shared_data("sf-potrero/sf-potrero.osm.gz");
  o.dem_paths = {shared_data("sf-potrero/USGS_13_n38w123-subsection-small-potrero.tif").string()};
  o.out_dir = scratch_dir(out);
  return o;
}

BuildOptions ne_options(const std::string& out) {
  BuildOptions o;
  o.osm_path = shared_data("sf-ne/sf_ne_drive_2017.osm.gz");
  o.dem_paths = {shared_data("sf-ne/sf_ne_usgs24k_30m_nad27utm10_m.tif").string()};
  o.out_dir = scratch_dir(out);
  return o;
}

const SfBuild& sf_potrero() {
  static const SfBuild b = build_shared(potrero_options("sf_potrero"), "sf-potrero");
  return b;
}

const SfBuild& sf_northeast() {
  static const SfBuild b = build_shared(ne_options("sf_ne"), "sf-ne");
  return b;
}

}  // namespace relief::test
