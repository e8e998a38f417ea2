#include "tiles/model_alignment.h"

#include <algorithm>
#include <optional>

#include "tiles/point_index.h"

namespace relief::detail {
namespace {

constexpr double kEndTolerance = 0.05;

Vec2 start_of(const ModelRoad& r) {
  return r.plan.at(0.0).position;
}
Vec2 end_of(const ModelRoad& r) {
  return r.plan.at(r.length()).position;
}

}  // namespace

WholeBuildComparison compare_with_whole(const RoadModel& whole, const RoadModel& merged) {
  PointIndex<std::size_t> starts;
  for (std::size_t i = 0; i < merged.roads.size(); ++i) starts.add(start_of(merged.roads[i]), i);
  // Each matched pair measured on its own (the merged road under its whole-build id), so that
  // the roads apart by more than a millimetre or a centimetre are counted.
  WholeBuildComparison c;
  c.roads = whole.roads.size();
  RoadModel reference, aligned;
  reference.frame = whole.frame;
  aligned.frame = merged.frame;
  for (const ModelRoad& w : whole.roads) {
    std::optional<std::size_t> match;
    // Several roads may start at one place (a junction's connecting roads): the one that also
    // ends where w ends.
    for (const std::size_t i : starts.all_near(start_of(w), kEndTolerance)) {
      const ModelRoad& m = merged.roads[i];
      if ((m.junction == -1) == (w.junction == -1) && (end_of(m) - end_of(w)).norm() <= kEndTolerance) {
        match = i;
        break;
      }
    }
    if (!match) {
      ++c.unmatched;
      continue;
    }
    reference.roads.assign(1, w);
    aligned.roads.assign(1, merged.roads[*match]);
    aligned.roads.front().id = w.id;
    const ModelDeviation d = compare_models(reference, aligned);
    c.deviation.points += d.points;
    if (d.max_xy_m > c.deviation.max_xy_m || d.max_z_m > c.deviation.max_z_m) c.deviation.worst_road = w.id;
    c.deviation.max_xy_m = std::max(c.deviation.max_xy_m, d.max_xy_m);
    c.deviation.max_z_m = std::max(c.deviation.max_z_m, d.max_z_m);
    if (d.max_z_m > 1e-3) ++c.roads_over_1mm;
    if (d.max_z_m > 1e-2) ++c.roads_over_1cm;
  }
  return c;
}

}  // namespace relief::detail
