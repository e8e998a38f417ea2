#pragma once
// Comparing a region's merged model with a whole build of the same region: their road ids
// differ, so roads are matched by their ends first.

#include "relief/roads/road_model.h"
#include "relief/roads/road_model_checks.h"

namespace relief::detail {

struct WholeBuildComparison {
  std::size_t roads = 0;      ///< roads of the whole build
  std::size_t unmatched = 0;  ///< of them, without a merged road with the same ends (5 cm)
  ModelDeviation deviation;   ///< over the matched roads (compare_models, every metre)
  /// Matched roads whose heights differ by more than 1 mm, 1 cm somewhere.
  std::size_t roads_over_1mm = 0, roads_over_1cm = 0;
};

/// Matches every road of `whole` to the road of `merged` with the same start and end (within
/// 5 cm, same junction-ness) and measures the matched pairs with compare_models.
[[nodiscard]] WholeBuildComparison compare_with_whole(const RoadModel& whole, const RoadModel& merged);

}  // namespace relief::detail
