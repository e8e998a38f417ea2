#pragma once
// Private to the roads module: road ends that stop on another road. A way that ends on (or
// runs into) another way's pavement without sharing a node with it (an OSM "almost junction",
// a service road drawn to a point inside the street it meets, ways closer than their widths)
// would have its end's lanes lie on the other road's lanes at the same height: two surfaces
// through each other in the mesh, a lane end in the middle of a carriageway in the OpenDRIVE.
// Such a dead end is trimmed back until its end cross-section clears the other road's paved
// area, as junction road ends are at a fork.

#include <array>
#include <vector>

#include "relief/roads/elevation_sampling.h"
#include "relief/roads/road_network.h"

namespace relief::detail {

struct StrayEnd {
  int road = -1;  ///< network road whose dead end was on another road
  bool at_start = false;
  int other_road = -1;     ///< the road it lay on (the first found)
  double trimmed_m = 0.0;  ///< how far it was trimmed back
  bool cleared = false;    ///< false: trimming to the road's least length did not clear it
};

struct StrayEndOptions {
  double gap_m = 0.5;                    ///< the end cross-section keeps this far from the other pavement
  double min_kept_length_m = 1.0;        ///< a road keeps this much between its two trims
  double max_height_difference_m = 2.0;  ///< farther apart in height: a crossing on another level
  double step_m = 0.5;                   ///< trims grow in these steps
};

/// Grows `trim` (per network road: at its start, at its end) at every dead end (a junction of
/// one road end) whose end cross-section (the road's full paved width, `half_width` per road,
/// across its direction at the trimmed end) lies within gap_m of another road's paved area
/// (its centreline buffered by its half width) at a height within max_height_difference_m
/// (`profiles`, per road; roads without height are left alone). Linear in the network: a grid
/// of road segments is searched around each dead end only.
[[nodiscard]] std::vector<StrayEnd> clear_stray_ends(const RoadNetwork& network,
                                                     const std::vector<RoadProfile>& profiles,
                                                     const std::vector<double>& half_width,
                                                     std::vector<std::array<double, 2>>& trim,
                                                     const StrayEndOptions& options);

}  // namespace relief::detail
