#include "relief/roads/road_model.h"

#include <string>

namespace relief {

int RoadModel::road_index(int id) const {
  // Models relief builds (and files it wrote, read back) number roads 1, 2, ... in order.
  if (id >= 1 && static_cast<std::size_t>(id) <= roads.size() &&
      roads[static_cast<std::size_t>(id) - 1].id == id) {
    return id - 1;
  }
  for (std::size_t i = 0; i < roads.size(); ++i) {
    if (roads[i].id == id) return static_cast<int>(i);
  }
  return -1;
}

std::string osm_way_note(const ModelRoad& road) {
  return road.osm_way_ids.empty() ? std::string()
                                  : " (OSM way " + std::to_string(road.osm_way_ids.front()) + ")";
}

}  // namespace relief
