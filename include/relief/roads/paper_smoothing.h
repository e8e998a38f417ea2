#pragma once
// The seed paper's profile smoothing, kept as a baseline to compare against: per road, check
// every segment's grade against the class table, and while any exceeds its limit replace each
// interior height by the mean of itself and its two neighbours,
//   z_i <- (z_{i-1} + z_i + z_{i+1}) / 3,
// up to an iteration cap. Road ends stay at their DEM heights (so junctions keep gap 0). Where
// the street is steeper end to end than its limit, no number of iterations can converge.

#include <vector>

#include "relief/roads/elevation_sampling.h"
#include "relief/roads/road_network.h"
#include "relief/roads/validation.h"

namespace relief {

struct PaperSmoothingOptions {
  GradeLimits limits = GradeLimits::paper();
  int max_iterations = 1000;
};

struct PaperSmoothingResult {
  std::vector<RoadProfile> profiles;
  std::vector<int> iterations;           ///< per road
  std::vector<int> not_converged_roads;  ///< roads still over their limit at the cap
  double max_shift_m = 0.0;              ///< largest |z - DEM| the smoothing introduced
  int max_shift_road = -1;
};

[[nodiscard]] PaperSmoothingResult smooth_paper(const RoadNetwork& network,
                                                const std::vector<RoadProfile>& raw,
                                                const PaperSmoothingOptions& options = {});

}  // namespace relief
