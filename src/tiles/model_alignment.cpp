#include "tiles/model_alignment.h"

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
  // `merged` with each matched road under its whole-build id; the rest left out.
  RoadModel aligned;
  aligned.frame = merged.frame;
  WholeBuildComparison c;
  c.roads = whole.roads.size();
  RoadModel reference;
  reference.frame = whole.frame;
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
    reference.roads.push_back(w);
    ModelRoad m = merged.roads[*match];
    m.id = w.id;
    aligned.roads.push_back(std::move(m));
  }
  c.deviation = compare_models(reference, aligned);
  return c;
}

}  // namespace relief::detail
