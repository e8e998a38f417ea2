#include "pipeline/sf_options.h"

#include "support/test_data.h"

namespace relief::test {

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

}  // namespace relief::test
