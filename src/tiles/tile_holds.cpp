#include "tiles/tile_holds.h"

#include <cmath>
#include <limits>
#include <string>

#include "relief/core/atomic_file.h"
#include "relief/core/errors.h"
#include "tiles/binary_file.h"
#include "tiles/xodr_merge.h"

namespace relief::detail {
namespace {

constexpr char kMagic[] = "relief-tile-holds 1\n";

}  // namespace

RoadKey road_key(const Road& road) {
  const std::vector<std::int64_t>& n = road.osm_node_ids;
  if (n.size() < 2) return {};
  return {n.front(), n[1], n[n.size() - 2], n.back()};
}

TileHolds tile_holds(const RoadNetwork& network, const ProfileFitResult& fit, const RoadModel& model,
                     const Aabb2& core) {
  // What the tile owns, by the network's roads and junctions.
  std::vector<std::uint8_t> owned_road(network.roads.size(), 0), owned_junction(network.junctions.size(), 0);
  for (const ModelRoad& r : model.roads) {
    if (r.junction == -1 && r.source_road >= 0 && owns(core, road_anchor(r)))
      owned_road[static_cast<std::size_t>(r.source_road)] = 1;
  }
  for (const JunctionModel& j : model.junctions) {
    if (!owns(core, junction_anchor(model, j))) continue;
    for (const int source : j.source_junctions) owned_junction[static_cast<std::size_t>(source)] = 1;
  }
  // A transition road (no network road of its own, between two roads) is its attribute change's
  // junction in the merge: the tile keeping it owns that junction, so that a neighbour built
  // later holds both roads' ends there as this tile fitted them (the generated 2 000 km region:
  // a tunnel's end 4.3 cm off the transition road the next tile built).
  for (const ModelRoad& t : model.roads) {
    if (t.junction != -1 || t.source_road >= 0 || !t.predecessor || !t.successor ||
        t.predecessor->element != RoadLink::Element::road ||
        t.successor->element != RoadLink::Element::road || !owns(core, road_anchor(t)))
      continue;
    const int a = model.road_index(t.predecessor->id), b = model.road_index(t.successor->id);
    if (a < 0 || b < 0) continue;
    const int ra = model.roads[static_cast<std::size_t>(a)].source_road;
    const int rb = model.roads[static_cast<std::size_t>(b)].source_road;
    if (ra < 0 || rb < 0) continue;
    const Road& na = network.roads[static_cast<std::size_t>(ra)];
    const Road& nb = network.roads[static_cast<std::size_t>(rb)];
    for (const int ja : {na.start_junction, na.end_junction}) {
      if (ja >= 0 && (ja == nb.start_junction || ja == nb.end_junction))
        owned_junction[static_cast<std::size_t>(ja)] = 1;
    }
  }
  // At every junction it owns or one of its roads ends at: the plane, and the stations within
  // reach of the junction of every road there it owns (of every road, at a junction it owns),
  // never past the road's middle: the far end's junction is its owner's to hold, with its plane.
  // (Holding a short road whole pinned the far junction's roads to this window's view while the
  // junction's plane stayed free: NE in 500 m tiles came out 9.7 cm from the whole build.)
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<std::vector<double>> held(network.roads.size());
  TileHolds out;
  for (const Junction& junction : network.junctions) {
    const bool owns_junction = owned_junction[static_cast<std::size_t>(junction.id)] != 0;
    bool touched = owns_junction;
    for (const RoadEnd& end : junction.ends) {
      if (!owns_junction && !owned_road[static_cast<std::size_t>(end.road)]) continue;
      const RoadProfile& p = fit.profiles[static_cast<std::size_t>(end.road)];
      if (!p.has_height || p.size() == 0) continue;
      touched = true;
      std::vector<double>& z = held[static_cast<std::size_t>(end.road)];
      if (z.empty()) z.assign(p.size(), nan);
      const double length = p.s.back();
      for (std::size_t i = 0; i < p.size(); ++i) {
        const double from_end = end.at_start ? p.s[i] : length - p.s[i];
        if (from_end <= kJunctionHoldReachM && from_end < 0.5 * length) z[i] = p.z[i];
      }
    }
    if (touched && junction.ends.size() >= 2 &&
        static_cast<std::size_t>(junction.id) < fit.junction_gradient.size())
      out.junction_gradient.emplace(junction.osm_node_id,
                                    fit.junction_gradient[static_cast<std::size_t>(junction.id)]);
  }
  for (std::size_t r = 0; r < held.size(); ++r) {
    if (!held[r].empty()) out.road_z.emplace(road_key(network.roads[r]), std::move(held[r]));
  }
  return out;
}

void add_holds(TileHolds& into, const TileHolds& from) {
  for (const auto& [key, z] : from.road_z) {
    auto [it, added] = into.road_z.try_emplace(key, z);
    if (added || it->second.size() != z.size()) continue;
    for (std::size_t i = 0; i < z.size(); ++i)
      if (std::isnan(it->second[i])) it->second[i] = z[i];
  }
  for (const auto& [id, g] : from.junction_gradient) into.junction_gradient.try_emplace(id, g);
}

FitHolds index_holds(const RoadNetwork& network, const std::vector<RoadProfile>& raw, const TileHolds& holds,
                     std::size_t& mismatched) {
  FitHolds out;
  mismatched = 0;
  if (holds.road_z.empty() && holds.junction_gradient.empty()) return out;
  out.road_z.resize(network.roads.size());
  out.junction_gradient.resize(network.junctions.size());
  for (const Road& road : network.roads) {
    const auto it = holds.road_z.find(road_key(road));
    if (it == holds.road_z.end()) continue;
    if (it->second.size() != raw[static_cast<std::size_t>(road.id)].size()) {
      ++mismatched;
      continue;
    }
    out.road_z[static_cast<std::size_t>(road.id)] = it->second;
  }
  for (const Junction& j : network.junctions) {
    if (const auto it = holds.junction_gradient.find(j.osm_node_id); it != holds.junction_gradient.end())
      out.junction_gradient[static_cast<std::size_t>(j.id)] = it->second;
  }
  return out;
}

void write_holds(const std::filesystem::path& path, const TileHolds& holds) {
  std::string out(kMagic);
  put<std::uint64_t>(out, holds.road_z.size());
  for (const auto& [key, z] : holds.road_z) {
    for (const std::int64_t id : {key.first, key.second, key.penultimate, key.last}) put(out, id);
    put<std::uint64_t>(out, z.size());
    for (const double v : z) put(out, v);
  }
  put<std::uint64_t>(out, holds.junction_gradient.size());
  for (const auto& [id, g] : holds.junction_gradient) {
    put(out, id);
    put(out, g.x());
    put(out, g.y());
  }
  write_file_atomically(path, out);
}

TileHolds read_holds(const std::filesystem::path& path) {
  BinaryReader r(path, "tile holds");
  r.expect(kMagic);
  TileHolds holds;
  const auto roads = r.get<std::uint64_t>();
  for (std::uint64_t k = 0; k < roads; ++k) {
    RoadKey key;
    key.first = r.get<std::int64_t>();
    key.second = r.get<std::int64_t>();
    key.penultimate = r.get<std::int64_t>();
    key.last = r.get<std::int64_t>();
    const auto n = r.get<std::uint64_t>();
    std::vector<double> z(n);
    for (double& v : z) v = r.get<double>();
    holds.road_z.emplace(key, std::move(z));
  }
  const auto junctions = r.get<std::uint64_t>();
  for (std::uint64_t k = 0; k < junctions; ++k) {
    const auto id = r.get<std::int64_t>();
    const auto gx = r.get<double>();
    const auto gy = r.get<double>();
    holds.junction_gradient.emplace(id, Vec2(gx, gy));
  }
  r.finish();
  return holds;
}

}  // namespace relief::detail
