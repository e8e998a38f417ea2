#include "scene/junction_surface.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <deque>
#include <limits>
#include <numbers>
#include <numeric>
#include <optional>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <utility>

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wconversion"
#pragma GCC diagnostic ignored "-Wshadow"
#pragma GCC diagnostic ignored "-Wpedantic"
#pragma GCC diagnostic ignored "-Wunused-parameter"
#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#pragma GCC diagnostic pop

#include "geometry/outline_order.h"
#include "relief/core/errors.h"
#include "relief/roads/road_surface.h"
#include "scene/lane_loft.h"

namespace relief::detail {

namespace {

// Exact constructions: constraints of a bad outline may cross, and the crossing points must
// then be computed exactly (they are reported, never kept).
using Kernel = CGAL::Exact_predicates_exact_constructions_kernel;
struct VertexInfo {
  int index = -1;  ///< position in the outline; -1 for a vertex CGAL made at a crossing
};
struct FaceInfo {
  int nesting = -1;  ///< constraints crossed from the outside (odd: inside the outline)
};
using VertexBase = CGAL::Triangulation_vertex_base_with_info_2<VertexInfo, Kernel>;
using FaceBaseInfo = CGAL::Triangulation_face_base_with_info_2<FaceInfo, Kernel>;
using FaceBase = CGAL::Constrained_triangulation_face_base_2<Kernel, FaceBaseInfo>;
using Tds = CGAL::Triangulation_data_structure_2<VertexBase, FaceBase>;
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<Kernel, Tds, CGAL::Exact_intersections_tag>;

constexpr double kKerbCornerGap = 0.01;  // kerb points this close to a corner are dropped (m)
constexpr double kKerbMinAngle = 1e-6;   // kerb points must advance this much around the centre (rad)
constexpr double kLeftOutReach = 30.0;   // a left-out road's edges this far from its end may not be paved (m)
constexpr double kLeftOutStep = 0.5;     // probed this often (m)
constexpr double kOnRoadDepth = 5.0;     // an end this far behind another's edge may lie on its road (m)
constexpr double kEdgeTurnedAway = 1.0;  // a road edge this far outside a straight side has left it (m)
constexpr double kInteriorSpacing = 2.0;    // interior points along a connecting road's lanes (m)
constexpr double kInteriorEndGap = 1.0;     // none this close to a connecting road's ends (m)
constexpr double kInteriorMerge = 1.0;      // interior points this close are merged (m)
constexpr double kInteriorClearance = 0.3;  // none this close to the outline (m)
constexpr double kSurfaceSpacing = 2.0;     // the height surface's points on straight sides and inside (m)
constexpr double kMaxSurfacePoints = 4000;  // a larger junction gets them farther apart
constexpr double kDepartureReach = 4.0;     // a lane point's departure from the surface reaches (m)

/// Nesting level of every face: a flood fill from the infinite face that counts the
/// constrained edges crossed (the usual domain marking of a CDT).
void mark_nesting(Cdt& cdt) {
  for (auto f : cdt.all_face_handles()) f->info().nesting = -1;
  std::deque<Cdt::Edge> borders;
  const auto flood = [&](Cdt::Face_handle start, int level) {
    if (start->info().nesting != -1) return;
    std::deque<Cdt::Face_handle> queue{start};
    while (!queue.empty()) {
      const Cdt::Face_handle f = queue.front();
      queue.pop_front();
      if (f->info().nesting != -1) continue;
      f->info().nesting = level;
      for (int i = 0; i < 3; ++i) {
        const Cdt::Face_handle n = f->neighbor(i);
        if (n->info().nesting != -1) continue;
        if (cdt.is_constrained(Cdt::Edge(f, i))) {
          borders.emplace_back(f, i);
        } else {
          queue.push_back(n);
        }
      }
    }
  };
  flood(cdt.infinite_face(), 0);
  while (!borders.empty()) {
    const Cdt::Edge e = borders.front();
    borders.pop_front();
    const Cdt::Face_handle n = e.first->neighbor(e.second);
    if (n->info().nesting == -1) flood(n, e.first->info().nesting + 1);
  }
}

struct OutlineVertex {
  Vec3 p;
  std::uint32_t mesh_index = kNoVertex;  ///< kNoVertex: a gap point not yet in the mesh
};

double signed_area(const std::vector<OutlineVertex>& outline) {
  double twice = 0.0;
  for (std::size_t i = 0; i < outline.size(); ++i) {
    const Vec3& a = outline[i].p;
    const Vec3& b = outline[(i + 1) % outline.size()].p;
    twice += a.x() * b.y() - b.x() * a.y();
  }
  return 0.5 * twice;
}

/// Key of a road end: 2 * road index + (0 at the start, 1 at the end).
long end_key(int road_index, bool at_start) {
  return 2L * road_index + (at_start ? 0 : 1);
}

/// The two road ends a connecting road joins (-1 where its link is not to a road).
std::pair<long, long> joined_ends(const RoadModel& model, const ModelRoad& road) {
  const auto key = [&](const std::optional<RoadLink>& link) {
    if (!link || link->element != RoadLink::Element::road) return -1L;
    const int index = model.road_index(link->id);
    return index < 0 ? -1L : end_key(index, link->contact == RoadLink::Contact::start);
  };
  return {key(road.predecessor), key(road.successor)};
}

/// Interior points of the kerb from `from` to `to`: the outermost lane border (farthest from
/// `centre` at mid-length) of the connecting roads joining ends a and b.
std::vector<Vec3> kerb_between(const RoadModel& model, const std::vector<int>& connecting, long a, long b,
                               const Vec2& centre, const Vec3& from, const Vec3& to,
                               const RoadMeshOptions& options) {
  const ModelRoad* best_road = nullptr;
  int best_lane = 0;
  double best_distance = -1.0;
  for (const int index : connecting) {
    const ModelRoad& road = model.roads[static_cast<std::size_t>(index)];
    const auto [p, q] = joined_ends(model, road);
    if (!((p == a && q == b) || (p == b && q == a)) || road.sections.empty() || road.plan.records().empty()) {
      continue;
    }
    const double mid = 0.5 * road.length();
    const LaneSection& section = section_at(road, mid);
    const int left = section.left.empty() ? 0 : section.left.back().id;
    const int right = section.right.empty() ? 0 : section.right.back().id;
    for (const int lane : {left, right}) {
      try {
        const Vec3 p3 = surface_point(road, mid, lane_border_t(road, mid, lane));
        const double d = (p3.head<2>() - centre).norm();
        if (d > best_distance) {
          best_distance = d;
          best_road = &road;
          best_lane = lane;
        }
      } catch (const InvalidInput&) {
        // a lane missing in that section: not a candidate
      }
    }
  }
  if (best_road == nullptr) return {};
  std::vector<Vec3> points;
  try {
    points = sample_lane_border(*best_road, best_lane, options);
  } catch (const InvalidInput&) {
    return {};
  }
  if (points.size() < 3) return {};
  if ((points.front() - from).norm() + (points.back() - to).norm() >
      (points.front() - to).norm() + (points.back() - from).norm()) {
    std::reverse(points.begin(), points.end());
  }
  // Keep the points that sweep monotonically counter-clockwise around the centre from `from`
  // to `to`: a tight turn's border loops at its cusps, and such a chain cannot cross itself.
  const auto angle_from = [&](const Vec3& p) {
    const Vec2 d = p.head<2>() - centre;
    const Vec2 f = from.head<2>() - centre;
    double angle = std::atan2(d.y(), d.x()) - std::atan2(f.y(), f.x());
    while (angle < 0.0) angle += 2.0 * std::numbers::pi;
    while (angle >= 2.0 * std::numbers::pi) angle -= 2.0 * std::numbers::pi;
    return angle;
  };
  const double end_angle = angle_from(to);
  double last_angle = 0.0;
  std::vector<Vec3> inner;
  for (std::size_t i = 1; i + 1 < points.size(); ++i) {
    const Vec2 xy = points[i].head<2>();
    if ((xy - from.head<2>()).norm() < kKerbCornerGap || (xy - to.head<2>()).norm() < kKerbCornerGap)
      continue;
    const double angle = angle_from(points[i]);
    if (angle <= last_angle + kKerbMinAngle || angle >= end_angle - kKerbMinAngle) continue;
    inner.push_back(points[i]);
    last_angle = angle;
  }
  return inner;
}

// Distance in plan from p to the closed outline.
double distance_to_outline(const std::vector<OutlineVertex>& outline, const Vec2& p) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < outline.size(); ++i) {
    const Vec2 a = outline[i].p.head<2>(), b = outline[(i + 1) % outline.size()].p.head<2>();
    const Vec2 ab = b - a;
    const double len2 = ab.squaredNorm();
    const double t = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
    best = std::min(best, (a + t * ab - p).norm());
  }
  return best;
}

// Whether the triangles of `mesh` from `first` on cover a point of the roads at `ends` within
// kLeftOutReach of their ends: along each road's outer edges and its end, every
// kLeftOutStep, a point more than kKerbCornerGap inside one of them.
bool patch_covers(const MeshBuilder& mesh, std::size_t first, const std::vector<JunctionEnd>& ends) {
  const auto& v = mesh.mesh.vertices;
  std::vector<Vec2> probes;
  const auto sample = [&](const Vec2& a, const Vec2& b) {
    const int n = std::max(1, static_cast<int>(std::ceil((b - a).norm() / kLeftOutStep)));
    for (int i = 0; i <= n; ++i) probes.emplace_back(a + (b - a) * (static_cast<double>(i) / n));
  };
  for (const JunctionEnd& e : ends) {
    for (std::size_t i = 1; i < e.vertices.size(); ++i)
      sample(v[e.vertices[i - 1]].head<2>(), v[e.vertices[i]].head<2>());
    for (const std::vector<std::uint32_t>* edge : {&e.left_edge, &e.right_edge}) {
      double along = 0.0;
      for (std::size_t i = 1; i < edge->size() && along < kLeftOutReach; ++i) {
        const Vec2 a = v[(*edge)[i - 1]].head<2>(), b = v[(*edge)[i]].head<2>();
        sample(a, b);
        along += (b - a).norm();
      }
    }
  }
  for (std::size_t t = first; t < mesh.mesh.triangles.size(); ++t) {
    const auto& tri = mesh.mesh.triangles[t];
    const Vec2 a = v[tri[0]].head<2>(), b = v[tri[1]].head<2>(), c = v[tri[2]].head<2>();
    for (const Vec2& p : probes) {
      // Signed distances to the three sides (counter-clockwise: inside is positive).
      const auto side = [&](const Vec2& s0, const Vec2& s1) {
        const Vec2 d = s1 - s0;
        const double length = d.norm();
        return length > 0.0 ? (d.x() * (p.y() - s0.y()) - d.y() * (p.x() - s0.x())) / length : -1.0;
      };
      if (side(a, b) > kKerbCornerGap && side(b, c) > kKerbCornerGap && side(c, a) > kKerbCornerGap)
        return true;
    }
  }
  return false;
}

}  // namespace

std::vector<Vec3> junction_interior(const RoadModel& model, const std::vector<int>& connecting_roads) {
  struct Cluster {
    Vec3 sum = Vec3::Zero();
    int n = 0;
    [[nodiscard]] Vec3 mean() const { return sum / n; }
  };
  std::vector<Cluster> clusters;
  std::unordered_map<std::uint64_t, std::vector<std::size_t>> cells;
  const auto cell_key = [](std::int64_t cx, std::int64_t cy) {
    return (static_cast<std::uint64_t>(cx) << 32) ^ static_cast<std::uint64_t>(cy & 0xffffffff);
  };
  const auto add = [&](const Vec3& p) {
    const auto cx = static_cast<std::int64_t>(std::floor(p.x() / kInteriorMerge));
    const auto cy = static_cast<std::int64_t>(std::floor(p.y() / kInteriorMerge));
    for (std::int64_t dx = -1; dx <= 1; ++dx) {
      for (std::int64_t dy = -1; dy <= 1; ++dy) {
        const auto it = cells.find(cell_key(cx + dx, cy + dy));
        if (it == cells.end()) continue;
        for (const std::size_t c : it->second) {
          if ((clusters[c].mean().head<2>() - p.head<2>()).norm() >= kInteriorMerge) continue;
          clusters[c].sum += p;
          ++clusters[c].n;
          return;
        }
      }
    }
    cells[cell_key(cx, cy)].push_back(clusters.size());
    clusters.push_back({p, 1});
  };
  for (const int r : connecting_roads) {
    const ModelRoad& road = model.roads[static_cast<std::size_t>(r)];
    const double length = road.length();
    if (road.sections.empty() || !(length > 2.0 * kInteriorEndGap)) continue;
    const int steps =
        std::max(1, static_cast<int>(std::ceil((length - 2.0 * kInteriorEndGap) / kInteriorSpacing)));
    for (int i = 0; i <= steps; ++i) {
      const double s = kInteriorEndGap + (length - 2.0 * kInteriorEndGap) * i / steps;
      const LaneSection& section = section_at(road, s);
      for (std::size_t k = 0; k < section.left.size(); ++k)
        add(surface_point(road, s, lane_centre_t(road, s, static_cast<int>(k) + 1)));
      for (std::size_t k = 0; k < section.right.size(); ++k)
        add(surface_point(road, s, lane_centre_t(road, s, -static_cast<int>(k) - 1)));
    }
  }
  std::vector<Vec3> out;
  out.reserve(clusters.size());
  for (const Cluster& c : clusters) out.push_back(c.mean());
  return out;
}

std::vector<Vec3> surface_grid(const std::vector<Vec2>& outline, const std::vector<Vec3>& lane_points,
                               const JunctionHeight& surface) {
  if (outline.empty()) return {};
  Vec2 lo = outline.front(), hi = outline.front();
  for (const Vec2& p : outline) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const Vec2 size = hi - lo;
  const double spacing = std::max(kSurfaceSpacing, std::sqrt(size.x() * size.y() / kMaxSurfacePoints));
  // The lane points by 1 m cell, to skip the grid points near one, with their departure from
  // the surface (a connecting road leaves it where it is too steep along the road).
  const auto key = [](std::int64_t cx, std::int64_t cy) {
    return (static_cast<std::uint64_t>(cx) << 32) ^ static_cast<std::uint64_t>(cy & 0xffffffff);
  };
  const auto cell = [&](double v) { return static_cast<std::int64_t>(std::floor(v / kInteriorMerge)); };
  std::unordered_map<std::uint64_t, std::vector<Vec3>> lanes;
  for (const Vec3& p : lane_points)
    lanes[key(cell(p.x()), cell(p.y()))].emplace_back(p.x(), p.y(), p.z() - surface.at(p.head<2>()).first);
  const auto reach = static_cast<std::int64_t>(std::ceil(kDepartureReach / kInteriorMerge));
  // Whether p lies within 1 m of a lane point, and else the lane points' departure there: a
  // blend of theirs by w = (1 / d^2) (1 - d / R)^2 within R = kDepartureReach, beside the
  // surface's own weight 1 / R^2 (so it fades to none at R: about 90 % of a lane point's at 1 m,
  // half at 2 m, a tenth at 3 m).
  const auto departure = [&](const Vec2& p, bool& near) {
    double num = 0.0, den = 1.0 / (kDepartureReach * kDepartureReach);
    near = false;
    for (std::int64_t dx = -reach; dx <= reach; ++dx)
      for (std::int64_t dy = -reach; dy <= reach; ++dy) {
        const auto it = lanes.find(key(cell(p.x()) + dx, cell(p.y()) + dy));
        if (it == lanes.end()) continue;
        for (const Vec3& q : it->second) {
          const double d = (q.head<2>() - p).norm();
          if (d < kInteriorMerge) near = true;
          if (near || d >= kDepartureReach || q.z() == 0.0) continue;
          const double fade = 1.0 - d / kDepartureReach;
          const double w = fade * fade / (d * d);
          num += w * q.z();
          den += w;
        }
      }
    return num / den;
  };
  std::vector<Vec3> points;
  const auto nx = static_cast<int>(std::floor(size.x() / spacing));
  const auto ny = static_cast<int>(std::floor(size.y() / spacing));
  // Centred in the box, so that a symmetric junction gets a symmetric grid.
  const Vec2 origin = lo + 0.5 * (size - spacing * Vec2(nx, ny));
  for (int i = 0; i <= nx; ++i)
    for (int j = 0; j <= ny; ++j) {
      const Vec2 p = origin + spacing * Vec2(i, j);
      bool near = false;
      const double d = departure(p, near);
      if (!near) points.emplace_back(p.x(), p.y(), surface.at(p).first + d);
    }
  return points;
}

JunctionSurfaceResult build_junction_surface(const RoadModel& model, const JunctionModel& junction,
                                             std::vector<JunctionEnd> ends,
                                             const std::vector<int>& connecting_roads,
                                             const RoadMeshOptions& options, MeshBuilder& mesh) {
  std::erase_if(ends, [](const JunctionEnd& e) { return e.vertices.size() < 2; });
  if (ends.empty()) return {"no road ends", {}};
  const auto& vertices = mesh.mesh.vertices;
  const auto midpoint = [&](const JunctionEnd& e) -> Vec3 {
    return 0.5 * (vertices[e.vertices.front()] + vertices[e.vertices.back()]);
  };
  Vec2 centre = Vec2::Zero();
  for (const JunctionEnd& e : ends) centre += midpoint(e).head<2>();
  centre /= static_cast<double>(ends.size());
  // The same order as the node outlines given to netconvert (junction_end_order).
  std::vector<PlanEnd> plan_ends;
  for (const JunctionEnd& e : ends) {
    const ModelRoad& road = model.roads[static_cast<std::size_t>(e.road_index)];
    const double h = heading_at(road, e.at_start ? 0.0 : road.length());
    const Vec2 along(std::cos(h), std::sin(h));
    plan_ends.push_back({vertices[e.vertices.front()].head<2>(), vertices[e.vertices.back()].head<2>(),
                         e.at_start ? along : Vec2(-along)});
  }
  std::vector<JunctionEnd> sorted;
  sorted.reserve(ends.size());
  for (const std::size_t k : junction_end_order(plan_ends)) sorted.push_back(std::move(ends[k]));

  const auto end_width = [&](const JunctionEnd& e) {
    return (vertices[e.vertices.back()] - vertices[e.vertices.front()]).head<2>().norm();
  };
  // How far p lies behind an end's edge (outside the junction), across from the edge itself
  // (more than -kKerbCornerGap where it does); NaN where p is beside the edge.
  const auto behind_edge = [&](const JunctionEnd& e, const Vec3& p) {
    const Vec2 right = vertices[e.vertices.front()].head<2>(), left = vertices[e.vertices.back()].head<2>();
    const Vec2 edge = left - right, q = p.head<2>() - right;
    const double length = edge.norm();
    const double along = edge.dot(q) / length;
    if (!(length > 0.0) || !(along > -kKerbCornerGap && along < length + kKerbCornerGap))
      return std::numeric_limits<double>::quiet_NaN();
    return -(edge.x() * q.y() - edge.y() * q.x()) / length;
  };
  const auto over_end = [&](const JunctionEnd& e, const Vec3& p) {
    return behind_edge(e, p) > -kKerbCornerGap;
  };
  // Whether p lies on the road of end e: behind its edge by at most its width or kOnRoadDepth.
  const auto on_road_of = [&](const JunctionEnd& e, const Vec3& p) {
    const double behind = behind_edge(e, p);
    return behind > -kKerbCornerGap && behind <= std::max(end_width(e), kOnRoadDepth);
  };
  // The kerb lines between consecutive ends of `order`.
  const auto kerb_gaps = [&](const std::vector<JunctionEnd>& order) {
    std::vector<OutlineGap> gaps(order.size());
    for (std::size_t k = 0; k < order.size(); ++k) {
      const JunctionEnd& a = order[k];
      const JunctionEnd& b = order[(k + 1) % order.size()];
      gaps[k].points = kerb_between(model, connecting_roads, end_key(a.road_index, a.at_start),
                                    end_key(b.road_index, b.at_start), centre, vertices[a.vertices.back()],
                                    vertices[b.vertices.front()], options);
      // A kerb point behind the edge of either end (a tight turn's border bulging back over the
      // road it leaves) lies over that road's mesh: the two surfaces would cross there.
      std::erase_if(gaps[k].points, [&](const Vec3& p) { return over_end(a, p) || over_end(b, p); });
      if (gaps[k].points.empty()) gaps[k] = along_road_edges(a, b, vertices);
    }
    return gaps;
  };
  const std::vector<OutlineGap> gaps = kerb_gaps(sorted);
  // The junction's height surface (relief/roads/junction_height.h): the one its connecting roads
  // take their heights from.
  std::vector<EndPlane> planes;
  planes.reserve(sorted.size());
  for (const JunctionEnd& e : sorted)
    planes.push_back(end_plane(model.roads[static_cast<std::size_t>(e.road_index)], e.at_start));
  const JunctionHeight surface(std::move(planes));
  std::vector<Vec3> interior = junction_interior(model, connecting_roads);
  std::vector<Vec2> extent;
  for (const JunctionEnd& e : sorted)
    for (const std::uint32_t v : e.vertices) extent.emplace_back(vertices[v].head<2>());
  for (const OutlineGap& gap : gaps)
    for (const Vec3& p : gap.points) extent.emplace_back(p.head<2>());
  const std::vector<Vec3> grid = surface_grid(extent, interior, surface);
  interior.insert(interior.end(), grid.begin(), grid.end());
  // Straight sides (along the roads' edges where a road runs along one; if even that is not a
  // simple outline, plain) for the ends in `order`.
  const auto straight = [&](const std::vector<JunctionEnd>& order, bool follow_edges) {
    std::vector<OutlineGap> sides(order.size());
    if (follow_edges)
      for (std::size_t k = 0; k < order.size(); ++k)
        sides[k] = along_road_edges(order[k], order[(k + 1) % order.size()], vertices);
    return triangulate_junction(order, sides, junction.id, mesh, interior, &surface).empty() ||
           (follow_edges && triangulate_junction(order, std::vector<OutlineGap>(order.size()), junction.id,
                                                 mesh, interior, &surface)
                                .empty());
  };
  // A kerb line that cuts across a neighbouring road end (a sharp fork): straight gaps instead;
  // where even that is not simple (ends reaching past one another: a joined junction, a road end
  // across a neighbour's), the ends in another order around the junction, one whose outline is.
  const auto straight_or_reordered = [&](const std::vector<JunctionEnd>& set) {
    if (straight(set, true)) return true;
    std::vector<Polyline2> chains;
    for (const JunctionEnd& e : set) {
      Polyline2& chain = chains.emplace_back();
      for (const std::uint32_t v : e.vertices) chain.push_back(vertices[v].head<2>());
    }
    const std::optional<std::vector<std::size_t>> simple = simple_outline_order(chains);
    if (!simple) return false;
    std::vector<JunctionEnd> reordered;
    for (const std::size_t k : *simple) reordered.push_back(set[k]);
    return straight(reordered, true);
  };
  // Ends lying on another end's road are left out (on_road_of) where the rest make a
  // simple outline: reaching round to them, the outline ran over that road's pavement and into
  // the neighbouring junction's (Liechtenstein's footways along a main road, 27 pairs crossing).
  // Narrowest first: of two ends lying on each other's roads (crossing), the narrower goes.
  std::vector<bool> on_another(sorted.size(), false);
  std::vector<std::size_t> by_width(sorted.size());
  std::iota(by_width.begin(), by_width.end(), std::size_t{0});
  std::stable_sort(by_width.begin(), by_width.end(),
                   [&](std::size_t a, std::size_t b) { return end_width(sorted[a]) < end_width(sorted[b]); });
  for (const std::size_t k : by_width)
    for (std::size_t i = 0; i < sorted.size() && !on_another[k]; ++i)
      on_another[k] = i != k && !on_another[i] && on_road_of(sorted[i], midpoint(sorted[k]));
  if (std::find(on_another.begin(), on_another.end(), true) != on_another.end()) {
    std::vector<JunctionEnd> own, others;
    std::vector<std::pair<int, bool>> left_out;
    for (std::size_t k = 0; k < sorted.size(); ++k) {
      if (on_another[k]) {
        left_out.emplace_back(sorted[k].road_index, sorted[k].at_start);
        others.push_back(sorted[k]);
      } else {
        own.push_back(sorted[k]);
      }
    }
    const std::size_t vertices_before = mesh.mesh.vertices.size(),
                      triangles_before = mesh.mesh.triangles.size();
    if (own.size() >= 2 &&
        (triangulate_junction(own, kerb_gaps(own), junction.id, mesh, interior, &surface).empty() ||
         straight_or_reordered(own))) {
      if (!patch_covers(mesh, triangles_before, others)) return {{}, left_out};
      // A left-out road running through the junction to its end: the patch would pave over it.
      mesh.mesh.vertices.resize(vertices_before);
      mesh.mesh.uvs.resize(vertices_before);
      mesh.mesh.triangles.resize(triangles_before);
      mesh.owner.resize(triangles_before);
    }
  }
  std::string failed = triangulate_junction(sorted, gaps, junction.id, mesh, interior, &surface);
  if (failed.empty()) return {};
  // One kerb line crossing another or an end (at a hairpin's tip the inner kerb reaches round
  // to the outer one): that gap straight, the other kerbs kept.
  for (std::size_t k = 0; k < sorted.size(); ++k) {
    if (gaps[k].points.empty() || !gaps[k].vertices.empty()) continue;  // not a kerb line
    std::vector<OutlineGap> one = gaps;
    one[k] = along_road_edges(sorted[k], sorted[(k + 1) % sorted.size()], vertices);
    if (triangulate_junction(sorted, one, junction.id, mesh, interior, &surface).empty()) return {};
  }
  if (straight_or_reordered(sorted)) return {};
  // No order makes one simple outline of all the ends: one end lies across the others (on a
  // neighbouring road's pavement, where bad data put two roads' ends on each other). The
  // junction is built without one end, so that its area is paved and the rest of its ends
  // joined; tried first are the ends whose edge's midpoint lies behind another end's edge (over
  // that road), then the narrowest.
  if (sorted.size() < 3) return {failed, {}};
  std::vector<std::pair<std::pair<bool, double>, std::size_t>> candidates;
  for (std::size_t k = 0; k < sorted.size(); ++k) {
    bool behind = false;
    for (std::size_t i = 0; i < sorted.size() && !behind; ++i)
      behind = i != k && over_end(sorted[i], midpoint(sorted[k]));
    candidates.push_back({{!behind, end_width(sorted[k])}, k});
  }
  std::sort(candidates.begin(), candidates.end());
  for (const auto& [order, k] : candidates) {
    std::vector<JunctionEnd> rest;
    for (std::size_t i = 0; i < sorted.size(); ++i)
      if (i != k) rest.push_back(sorted[i]);
    // Its kerb lines first: straight sides across a joined junction's notches would pave
    // over the roads that lie in them.
    if (triangulate_junction(rest, kerb_gaps(rest), junction.id, mesh, interior, &surface).empty() ||
        straight_or_reordered(rest))
      return {{}, {{sorted[k].road_index, sorted[k].at_start}}};
  }
  return {failed, {}};
}

OutlineGap along_road_edges(const JunctionEnd& a, const JunctionEnd& b, const std::vector<Vec3>& vertices) {
  OutlineGap gap;
  if (a.vertices.empty() || b.vertices.empty()) return gap;
  const Vec2 p = vertices[a.vertices.back()].head<2>();
  const Vec2 side = vertices[b.vertices.front()].head<2>() - p;
  const double length = side.norm();
  if (!(length > 0.0)) return gap;
  const Vec2 dir = side / length;
  std::vector<std::pair<double, std::uint32_t>> inside;  // (distance along the side, vertex)
  for (const std::vector<std::uint32_t>* edge : {&a.left_edge, &b.right_edge}) {
    for (std::size_t i = 1; i < edge->size(); ++i) {
      const Vec2 x = vertices[(*edge)[i]].head<2>() - p;
      const double along = dir.dot(x);
      const double across = dir.x() * x.y() - dir.y() * x.x();  // > 0: inside the junction
      if (along <= 0.0 || along >= length || across < -kEdgeTurnedAway) break;
      if (across > kKerbCornerGap) inside.emplace_back(along, (*edge)[i]);
    }
  }
  std::sort(inside.begin(), inside.end());
  for (const auto& [along, v] : inside) {
    if (!gap.vertices.empty() && v == gap.vertices.back()) continue;
    gap.points.push_back(vertices[v]);
    gap.vertices.push_back(v);
  }
  return gap;
}

std::string triangulate_junction(const std::vector<JunctionEnd>& ends, const std::vector<OutlineGap>& gaps,
                                 int junction_id, MeshBuilder& mesh, const std::vector<Vec3>& interior,
                                 const JunctionHeight* surface) {
  // Outline: each end from its right to its left corner, then the gap to the next end.
  // On the surface, a straight side (no points), or a piece of a side with a new point at either
  // end, gets points every kSurfaceSpacing: a piece between two mesh vertices may be a road's
  // edge, which must stay whole.
  std::vector<OutlineVertex> outline;
  const auto side_to = [&](const OutlineVertex& to, bool straight) {
    const OutlineVertex& from = outline.back();
    if (surface != nullptr && (straight || from.mesh_index == kNoVertex || to.mesh_index == kNoVertex)) {
      const Vec2 a = from.p.head<2>(), b = to.p.head<2>();
      const int pieces = static_cast<int>(std::ceil((b - a).norm() / kSurfaceSpacing));
      for (int i = 1; i < pieces; ++i) {
        const Vec2 xy = a + (b - a) * (static_cast<double>(i) / pieces);
        outline.push_back({Vec3(xy.x(), xy.y(), surface->at(xy).first), kNoVertex});
      }
    }
    outline.push_back(to);
  };
  for (std::size_t k = 0; k < ends.size(); ++k) {
    for (const std::uint32_t v : ends[k].vertices) {
      if (outline.empty() || outline.back().mesh_index != v) outline.push_back({mesh.mesh.vertices[v], v});
    }
    if (k < gaps.size()) {
      const OutlineGap& gap = gaps[k];
      for (std::size_t i = 0; i < gap.points.size(); ++i)
        side_to({gap.points[i], i < gap.vertices.size() ? gap.vertices[i] : kNoVertex}, false);
      // To the next end's first corner (which that end then does not repeat; the first end's
      // comes twice, and is popped below).
      const std::uint32_t next = ends[(k + 1) % ends.size()].vertices.front();
      side_to({mesh.mesh.vertices[next], next}, gap.points.empty());
    }
  }
  while (outline.size() > 1 && outline.front().mesh_index != kNoVertex &&
         outline.front().mesh_index == outline.back().mesh_index) {
    outline.pop_back();
  }
  const std::size_t n = outline.size();
  if (n < 3) return "outline has fewer than three vertices";
  std::unordered_set<std::uint32_t> seen;
  for (const OutlineVertex& v : outline) {
    if (v.mesh_index != kNoVertex && !seen.insert(v.mesh_index).second) {
      return "outline passes twice through vertex " + std::to_string(v.mesh_index);
    }
  }
  const double area = signed_area(outline);
  if (!(area > 1e-9)) return "outline is not counter-clockwise (signed area " + std::to_string(area) + " m2)";

  Cdt cdt;
  std::vector<Cdt::Vertex_handle> handles;
  handles.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Cdt::Vertex_handle h = cdt.insert(Cdt::Point(outline[i].p.x(), outline[i].p.y()));
    if (h->info().index >= 0) return "two outline vertices at the same position";
    h->info().index = static_cast<int>(i);
    handles.push_back(h);
  }
  for (std::size_t i = 0; i < n; ++i) cdt.insert_constraint(handles[i], handles[(i + 1) % n]);
  std::size_t crossings = 0;
  for (const auto v : cdt.finite_vertex_handles()) {
    if (v->info().index < 0) ++crossings;
  }
  if (crossings > 0) {
    return "outline is not simple: CGAL split its constraints at " + std::to_string(crossings) +
           " crossing(s)";
  }
  mark_nesting(cdt);
  std::vector<std::array<int, 3>> inside;
  double inside_area = 0.0;
  std::vector<Vec3> steiner;  // interior points, vertex index n + k
  const auto point_of = [&](int index) -> const Vec3& {
    const auto i = static_cast<std::size_t>(index);
    return i < n ? outline[i].p : steiner[i - n];
  };
  const auto collect = [&] {
    inside.clear();
    inside_area = 0.0;
    for (const auto f : cdt.finite_face_handles()) {
      if (f->info().nesting % 2 != 1) continue;
      std::array<int, 3> t{};
      for (int i = 0; i < 3; ++i) t[static_cast<std::size_t>(i)] = f->vertex(i)->info().index;
      const Vec3& a = point_of(t[0]);
      const Vec3& b = point_of(t[1]);
      const Vec3& c = point_of(t[2]);
      inside_area += 0.5 * ((b.x() - a.x()) * (c.y() - a.y()) - (c.x() - a.x()) * (b.y() - a.y()));
      inside.push_back(t);
    }
  };
  collect();
  // A simple polygon of n vertices without Steiner points has exactly n - 2 triangles
  // covering its area; anything else means the outline touches itself.
  if (inside.size() != n - 2 || std::abs(inside_area - area) > 1e-6 * std::max(1.0, area)) {
    return "outline is not a simple polygon (" + std::to_string(inside.size()) + " triangles for " +
           std::to_string(n) + " vertices)";
  }
  // Which points lie inside is read off the outline's own faces, before any is inserted: the
  // faces an insertion creates carry no nesting yet (reading them dropped every later point
  // that fell in one, half of a large junction's).
  std::vector<Vec3> inserted;
  for (const Vec3& p : interior) {
    const Cdt::Face_handle f = cdt.locate(Cdt::Point(p.x(), p.y()));
    if (f == nullptr || cdt.is_infinite(f) || f->info().nesting % 2 != 1) continue;
    if (distance_to_outline(outline, p.head<2>()) < kInteriorClearance) continue;
    inserted.push_back(p);
  }
  for (const Vec3& p : inserted) {
    const Cdt::Vertex_handle h = cdt.insert(Cdt::Point(p.x(), p.y()));
    if (h->info().index >= 0) continue;  // at a vertex already there
    h->info().index = static_cast<int>(n + steiner.size());
    steiner.push_back(p);
  }

  if (!steiner.empty()) {
    mark_nesting(cdt);
    collect();
    if (std::abs(inside_area - area) > 1e-6 * std::max(1.0, area))
      return "interior points changed the junction's area (" + std::to_string(inside_area) + " m2)";
  }
  for (OutlineVertex& v : outline) {
    if (v.mesh_index == kNoVertex) v.mesh_index = mesh.add_vertex(v.p, v.p.head<2>());
  }
  std::vector<std::uint32_t> steiner_index;
  steiner_index.reserve(steiner.size());
  for (const Vec3& p : steiner) steiner_index.push_back(mesh.add_vertex(p, p.head<2>()));
  const auto index_of = [&](int index) {
    const auto i = static_cast<std::size_t>(index);
    return i < n ? outline[i].mesh_index : steiner_index[i - n];
  };
  for (const auto& t : inside)
    mesh.add_triangle(index_of(t[0]), index_of(t[1]), index_of(t[2]), -1 - junction_id);
  return {};
}

}  // namespace relief::detail
