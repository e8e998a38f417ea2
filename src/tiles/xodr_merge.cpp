#include "tiles/xodr_merge.h"

#include "tiles/point_index.h"

#include <cmath>
#include <limits>
#include <optional>
#include <unordered_map>

namespace relief::detail {
namespace {

struct RoadEnd {
  int id = -1;
  RoadLink::Contact contact = RoadLink::Contact::start;
};

constexpr double kEndTolerance = 0.05;    // the same road end in two tiles: millimetres apart
constexpr double kCentreTolerance = 0.5;  // the same junction's centre in two tiles

Vec2 end_point(const ModelRoad& road, RoadLink::Contact contact) {
  return road.plan.at(contact == RoadLink::Contact::start ? 0.0 : road.length()).position;
}

}  // namespace

bool owns(const Aabb2& core, const Vec2& p) {
  return p.x() >= core.min.x() && p.x() < core.max.x() && p.y() >= core.min.y() && p.y() < core.max.y();
}

Vec2 road_anchor(const ModelRoad& road) {
  return road.plan.at(0.5 * road.length()).position;
}

Vec2 junction_anchor(const RoadModel& model, const JunctionModel& junction) {
  Vec2 sum = Vec2::Zero();
  int n = 0;
  for (const ModelRoad& road : model.roads) {
    if (road.junction != junction.id) continue;
    sum += road_anchor(road);
    ++n;
  }
  return n == 0 ? Vec2(std::numeric_limits<double>::quiet_NaN(), 0.0) : Vec2(sum / n);
}

ModelMergeResult merge_models(std::vector<TileModel>& tiles) {
  ModelMergeResult out;
  if (tiles.empty()) return out;
  out.model.frame = tiles.front().model.frame;
  out.model.name = tiles.front().model.name;

  // Ownership and new ids, tile by tile.
  struct Local {
    std::unordered_map<int, int> road;              // local road id -> merged id (owned roads)
    std::unordered_map<int, int> junction;          // local junction id -> merged id (owned junctions)
    std::unordered_map<int, Vec2> junction_centre;  // local junction id -> its anchor
  };
  std::vector<Local> local(tiles.size());
  PointIndex<RoadEnd> ends;
  PointIndex<int> centres;
  int next_road = 1, next_junction = 1;
  for (std::size_t t = 0; t < tiles.size(); ++t) {
    const RoadModel& m = tiles[t].model;
    for (const JunctionModel& j : m.junctions) {
      const Vec2 c = junction_anchor(m, j);
      local[t].junction_centre[j.id] = c;
      if (!owns(tiles[t].core, c)) continue;
      local[t].junction[j.id] = next_junction;
      centres.add(c, next_junction++);
    }
    for (const ModelRoad& r : m.roads) {
      const bool owned =
          r.junction == -1 ? owns(tiles[t].core, road_anchor(r)) : local[t].junction.contains(r.junction);
      if (!owned) continue;
      local[t].road[r.id] = next_road;
      if (r.junction == -1) {
        ends.add(end_point(r, RoadLink::Contact::start), {next_road, RoadLink::Contact::start});
        ends.add(end_point(r, RoadLink::Contact::end), {next_road, RoadLink::Contact::end});
      }
      ++next_road;
    }
  }

  const auto unresolved = [&](const TileModel& tile, const std::string& what) {
    out.unresolved.push_back("tile " + std::to_string(tile.x) + "," + std::to_string(tile.y) + ": " + what);
    if (out.links_unresolved++ == 0) out.first_unresolved = out.unresolved.back();
  };
  // The owned road end at `p` that is a `contact` end of a road other than `self` (merged id):
  // where two roads link end to start, or start to start, both ends lie at one point, and only
  // the contact and the linking road itself tell them apart.
  const auto end_at = [&](const Vec2& p, RoadLink::Contact contact, int self) -> std::optional<RoadEnd> {
    for (const RoadEnd& e : ends.all_near(p, kEndTolerance)) {
      if (e.contact == contact && e.id != self) return e;
    }
    return std::nullopt;
  };
  // The merged id of local road `id`'s end `contact` (an owned road of any tile), linked from
  // the road with merged id `self`.
  const auto road_end = [&](std::size_t t, int id, RoadLink::Contact contact,
                            int self) -> std::optional<RoadEnd> {
    if (const auto it = local[t].road.find(id); it != local[t].road.end())
      return RoadEnd{it->second, contact};
    const int index = tiles[t].model.road_index(id);
    if (index < 0) return std::nullopt;
    return end_at(end_point(tiles[t].model.roads[static_cast<std::size_t>(index)], contact), contact, self);
  };
  const auto junction_id = [&](std::size_t t, int id) -> std::optional<int> {
    if (const auto it = local[t].junction.find(id); it != local[t].junction.end()) return it->second;
    const auto c = local[t].junction_centre.find(id);
    if (c == local[t].junction_centre.end()) return std::nullopt;
    return centres.nearest(c->second, kCentreTolerance);
  };
  const auto relink = [&](std::size_t t, const ModelRoad& road, int self, std::optional<RoadLink>& link) {
    if (!link) return;
    if (link->element == RoadLink::Element::junction) {
      if (const std::optional<int> j = junction_id(t, link->id)) {
        link->id = *j;
        return;
      }
    } else if (const std::optional<RoadEnd> end = road_end(t, link->id, link->contact, self)) {
      link->id = end->id;
      link->contact = end->contact;
      return;
    }
    unresolved(tiles[t], "road " + std::to_string(road.id) + " links to " +
                             (link->element == RoadLink::Element::junction ? "junction " : "road ") +
                             std::to_string(link->id) + ", which no tile owns");
    link.reset();
  };

  for (std::size_t t = 0; t < tiles.size(); ++t) {
    RoadModel& m = tiles[t].model;
    for (ModelRoad& r : m.roads) {
      const auto it = local[t].road.find(r.id);
      if (it == local[t].road.end()) continue;
      ModelRoad road = std::move(r);
      relink(t, road, it->second, road.predecessor);
      relink(t, road, it->second, road.successor);
      road.id = it->second;
      if (road.junction != -1) road.junction = local[t].junction.at(road.junction);
      out.road_tile.emplace(road.id, std::pair{tiles[t].x, tiles[t].y});
      out.model.roads.push_back(std::move(road));
    }
  }
  // Junctions after roads: a connection's incoming road is found by its end at the junction,
  // which the local model still has (its roads were moved from, their plans kept by index).
  for (std::size_t t = 0; t < tiles.size(); ++t) {
    const RoadModel& m = tiles[t].model;
    for (const JunctionModel& j : m.junctions) {
      const auto it = local[t].junction.find(j.id);
      if (it == local[t].junction.end()) continue;
      JunctionModel junction = j;
      junction.id = it->second;
      junction.connections.clear();
      for (JunctionConnection c : j.connections) {
        c.connecting_road = local[t].road.at(c.connecting_road);
        std::optional<RoadEnd> incoming;
        if (const auto f = local[t].road.find(c.incoming_road); f != local[t].road.end()) {
          incoming = RoadEnd{f->second};
        } else if (const int index = m.road_index(c.incoming_road); index >= 0) {
          // Another tile's road: its end at this junction, in this tile's copy.
          const ModelRoad& in = m.roads[static_cast<std::size_t>(index)];
          const bool at_start = in.predecessor && in.predecessor->element == RoadLink::Element::junction &&
                                in.predecessor->id == j.id;
          const RoadLink::Contact contact = at_start ? RoadLink::Contact::start : RoadLink::Contact::end;
          incoming = end_at(end_point(in, contact), contact, -1);
        }
        if (!incoming) {
          unresolved(tiles[t], "junction " + std::to_string(j.id) + "'s incoming road " +
                                   std::to_string(c.incoming_road) + " is owned by no tile");
          continue;
        }
        c.incoming_road = incoming->id;
        junction.connections.push_back(c);
      }
      if (!junction.connections.empty()) out.model.junctions.push_back(std::move(junction));
    }
  }
  return out;
}

}  // namespace relief::detail
