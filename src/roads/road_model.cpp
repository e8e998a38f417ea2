#include "relief/roads/road_model.h"

namespace relief {

int RoadModel::road_index(int id) const {
  for (std::size_t i = 0; i < roads.size(); ++i) {
    if (roads[i].id == id) return static_cast<int>(i);
  }
  return -1;
}

}  // namespace relief
