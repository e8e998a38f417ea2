#include "relief/roads/road_network.h"

#include <algorithm>

namespace relief {

std::string_view to_string(JunctionKind kind) {
  switch (kind) {
    case JunctionKind::intersection:
      return "intersection";
    case JunctionKind::attribute_change:
      return "attribute_change";
    case JunctionKind::dead_end:
      return "dead_end";
  }
  return "unknown";
}

std::size_t RoadNetwork::count(JunctionKind kind) const {
  return static_cast<std::size_t>(std::count_if(junctions.begin(), junctions.end(),
                                                [kind](const Junction& j) { return j.kind == kind; }));
}

}  // namespace relief
