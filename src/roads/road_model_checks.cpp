#include "relief/roads/road_model_checks.h"

#include "relief/core/errors.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <vector>

#include "relief/geometry/plane.h"
#include "relief/roads/road_surface.h"

namespace relief {
namespace {

// Inner and outer border points of a lane at s.
std::pair<Vec3, Vec3> lane_borders(const ModelRoad& road, double s, int lane) {
  const int inner = lane < 0 ? lane + 1 : lane - 1;
  return {surface_point(road, s, lane_border_t(road, s, inner)),
          surface_point(road, s, lane_border_t(road, s, lane))};
}

bool has_lane(const ModelRoad& road, double s, int lane) {
  const LaneSection& sec = section_at(road, s);
  for (const auto* side : {&sec.left, &sec.right})
    for (const LaneModel& l : *side)
      if (l.id == lane) return true;
  return false;
}

}  // namespace

ConnectingRoadCrossings check_connecting_road_crossings(const RoadModel& model, double tolerance_m,
                                                        double step_m, double near_m) {
  ConnectingRoadCrossings out;
  // The lane centres of each junction's connecting roads as sampled 3-D polylines.
  std::map<int, std::vector<Polyline3>> centres;
  for (const ModelRoad& road : model.roads) {
    if (road.junction < 0 || road.sections.empty()) continue;
    const double length = road.length();
    const int n = std::max(1, static_cast<int>(std::ceil(length / step_m)));
    const LaneSection& first = road.sections.front();
    for (const auto* side : {&first.left, &first.right}) {
      for (const LaneModel& lane : *side) {
        if (lane.type != "driving") continue;
        Polyline3& line = centres[road.junction].emplace_back();
        for (int i = 0; i <= n; ++i) {
          const double s = length * i / n;
          line.push_back(surface_point(road, s, lane_centre_t(road, s, lane.id)));
        }
      }
    }
  }
  for (const auto& [junction, lines] : centres) {
    // The segments of every line in a plan grid of 1 m cells (each segment in the cells its box
    // touches, grown by near_m), so that a point meets only the segments beside it.
    constexpr double kCell = 1.0;
    const auto key = [](double x, double y) {
      return std::pair<long, long>{static_cast<long>(std::floor(x / kCell)),
                                   static_cast<long>(std::floor(y / kCell))};
    };
    std::map<std::pair<long, long>, std::vector<std::pair<std::size_t, std::size_t>>> grid;
    for (std::size_t b = 0; b < lines.size(); ++b) {
      for (std::size_t k = 0; k + 1 < lines[b].size(); ++k) {
        const Vec2 u = lines[b][k].head<2>(), v = lines[b][k + 1].head<2>();
        const auto lo = key(std::min(u.x(), v.x()) - near_m, std::min(u.y(), v.y()) - near_m);
        const auto hi = key(std::max(u.x(), v.x()) + near_m, std::max(u.y(), v.y()) + near_m);
        for (long i = lo.first; i <= hi.first; ++i)
          for (long j = lo.second; j <= hi.second; ++j) grid[{i, j}].emplace_back(b, k);
      }
    }
    double worst = 0.0;
    Vec2 worst_xy = Vec2::Zero();
    for (std::size_t a = 0; a < lines.size(); ++a) {
      for (const Vec3& p : lines[a]) {
        const Vec2 q = p.head<2>();
        const auto cell = grid.find(key(q.x(), q.y()));
        if (cell == grid.end()) continue;
        std::size_t last_line = lines.size();
        for (const auto& [b, k] : cell->second) {
          if (b == a || b == last_line) continue;
          const Vec2 u = lines[b][k].head<2>(), v = lines[b][k + 1].head<2>();
          const double f = segment_parameter(q, u, v);
          if ((u + f * (v - u) - q).norm() > near_m) continue;
          last_line = b;  // one measurement per other line
          ++out.crossings;
          const double step =
              std::abs(p.z() - (lines[b][k].z() + f * (lines[b][k + 1].z() - lines[b][k].z())));
          if (step > worst) {
            worst = step;
            worst_xy = q;
          }
        }
      }
    }
    if (worst > tolerance_m) ++out.junctions_over;
    if (worst > out.max_step_m) {
      out.max_step_m = worst;
      out.worst_junction = junction;
      out.worst_xy = worst_xy;
    }
  }
  return out;
}

ConnectingRoadsOverRoads check_connecting_roads_over_roads(const RoadModel& model, double tolerance_m,
                                                           double step_m, double reach_m, double inset_m) {
  ConnectingRoadsOverRoads out;
  // The pavement of each road within reach_m of each junction it ends at, as triangles with
  // their distance behind the end line at each corner.
  struct Triangle {
    std::array<Vec3, 3> p;
    std::array<double, 3> behind;
    int road = -1;
  };
  constexpr double kAlong = 0.5;  // m between the pavement's cross-sections
  std::map<int, std::vector<Triangle>> pavement;
  for (const ModelRoad& road : model.roads) {
    if (road.junction >= 0 || road.sections.empty()) continue;
    const double length = road.length();
    for (const auto& [link, at_start] :
         {std::pair{&road.predecessor, true}, std::pair{&road.successor, false}}) {
      if (!*link || (*link)->element != RoadLink::Element::junction) continue;
      const double reach = std::min(reach_m, length);
      const int n = std::max(1, static_cast<int>(std::ceil(reach / kAlong)));
      std::array<Vec3, 2> prev{Vec3::Zero(), Vec3::Zero()};
      double prev_behind = 0.0;
      for (int i = 0; i <= n; ++i) {
        const double behind = reach * i / n;
        const double s = at_start ? behind : length - behind;
        const LaneSection& sec = section_at(road, s);
        const int left = sec.left.empty() ? 0 : sec.left.back().id;
        const int right = sec.right.empty() ? 0 : sec.right.back().id;
        const std::array<Vec3, 2> cut{surface_point(road, s, lane_border_t(road, s, right)),
                                      surface_point(road, s, lane_border_t(road, s, left))};
        if (i > 0) {
          std::vector<Triangle>& tris = pavement[(*link)->id];
          tris.push_back({{prev[0], prev[1], cut[0]}, {prev_behind, prev_behind, behind}, road.id});
          tris.push_back({{prev[1], cut[1], cut[0]}, {prev_behind, behind, behind}, road.id});
        }
        prev = cut;
        prev_behind = behind;
      }
    }
  }
  // Each junction's triangles in a plan grid of 1 m cells, and its connecting roads' lane
  // centres sampled against them.
  std::map<int, std::vector<const ModelRoad*>> connecting;
  for (const ModelRoad& road : model.roads) {
    if (road.junction >= 0 && !road.sections.empty()) connecting[road.junction].push_back(&road);
  }
  constexpr double kCell = 1.0;
  const auto key = [](double x, double y) {
    return std::pair<long, long>{static_cast<long>(std::floor(x / kCell)),
                                 static_cast<long>(std::floor(y / kCell))};
  };
  for (const auto& [junction, tris] : pavement) {
    const auto roads = connecting.find(junction);
    if (roads == connecting.end()) continue;
    std::map<std::pair<long, long>, std::vector<std::size_t>> grid;
    for (std::size_t k = 0; k < tris.size(); ++k) {
      const auto& p = tris[k].p;
      const auto lo = key(std::min({p[0].x(), p[1].x(), p[2].x()}), std::min({p[0].y(), p[1].y(), p[2].y()}));
      const auto hi = key(std::max({p[0].x(), p[1].x(), p[2].x()}), std::max({p[0].y(), p[1].y(), p[2].y()}));
      for (long i = lo.first; i <= hi.first; ++i)
        for (long j = lo.second; j <= hi.second; ++j) grid[{i, j}].push_back(k);
    }
    double worst = 0.0;
    for (const ModelRoad* c : roads->second) {
      const double length = c->length();
      const int n = std::max(1, static_cast<int>(std::ceil(length / step_m)));
      const LaneSection& first = c->sections.front();
      for (const auto* side : {&first.left, &first.right}) {
        for (const LaneModel& lane : *side) {
          if (lane.type != "driving") continue;
          for (int i = 0; i <= n; ++i) {
            const double s = length * i / n;
            const Vec3 q = surface_point(*c, s, lane_centre_t(*c, s, lane.id));
            const auto cell = grid.find(key(q.x(), q.y()));
            if (cell == grid.end()) continue;
            for (const std::size_t k : cell->second) {
              const Triangle& t = tris[k];
              const Vec2 a = t.p[0].head<2>(), b = t.p[1].head<2>(), d = t.p[2].head<2>();
              const double area = cross(b - a, d - a);
              if (std::abs(area) < 1e-12) continue;
              const double wb = cross(q.head<2>() - a, d - a) / area;  // q = a + wb (b - a) + wd (d - a)
              const double wd = cross(b - a, q.head<2>() - a) / area;
              const double wa = 1.0 - wb - wd;
              if (wa < 0.0 || wb < 0.0 || wd < 0.0) continue;
              if (wa * t.behind[0] + wb * t.behind[1] + wd * t.behind[2] < inset_m) continue;
              ++out.samples;
              const double step = std::abs(q.z() - (wa * t.p[0].z() + wb * t.p[1].z() + wd * t.p[2].z()));
              if (step > worst) worst = step;
              if (step > out.max_step_m) {
                out.max_step_m = step;
                out.worst_junction = junction;
                out.worst_road = t.road;
                out.worst_xy = q.head<2>();
              }
              break;
            }
          }
        }
      }
    }
    if (worst > tolerance_m) ++out.junctions_over;
  }
  return out;
}

LinkContinuity check_link_continuity(const RoadModel& model, double tolerance_m) {
  LinkContinuity c;
  const auto compare = [&](const ModelRoad& a, double sa, int la, const ModelRoad& b, double sb, int lb) {
    if (!has_lane(a, sa, la) || !has_lane(b, sb, lb)) return;
    const auto [ai, ao] = lane_borders(a, sa, la);
    const auto [bi, bo] = lane_borders(b, sb, lb);
    for (const auto& [p, q] : {std::pair{ai, bi}, std::pair{ao, bo}}) {
      const double h = (p.head<2>() - q.head<2>()).norm();
      const double v = std::abs(p.z() - q.z());
      ++c.borders_checked;
      if (h > tolerance_m || v > tolerance_m) ++c.over_tolerance;
      if (h > c.max_horizontal_m || v > c.max_vertical_m) {
        c.worst_road = a.id;
        c.worst_other_road = b.id;
        c.worst_at = p;
      }
      c.max_horizontal_m = std::max(c.max_horizontal_m, h);
      c.max_vertical_m = std::max(c.max_vertical_m, v);
    }
  };
  for (const ModelRoad& road : model.roads) {
    for (const bool at_start : {true, false}) {
      const auto& link = at_start ? road.predecessor : road.successor;
      if (!link || link->element != RoadLink::Element::road) continue;
      const int other_index = model.road_index(link->id);
      if (other_index < 0) continue;
      const ModelRoad& other = model.roads[other_index];
      const double s = at_start ? 0.0 : road.length();
      const double so = link->contact == RoadLink::Contact::start ? 0.0 : other.length();
      const LaneSection& sec = section_at(road, s);
      for (const auto* side : {&sec.left, &sec.right}) {
        for (const LaneModel& lane : *side) {
          const auto& linked = at_start ? lane.predecessor : lane.successor;
          if (linked) compare(road, s, lane.id, other, so, *linked);
        }
      }
    }
  }
  return c;
}

ModelDeviation compare_models(const RoadModel& a, const RoadModel& b, double step_m) {
  ModelDeviation d;
  for (const ModelRoad& ra : a.roads) {
    const int ib = b.road_index(ra.id);
    if (ib < 0) {
      d.max_xy_m = std::numeric_limits<double>::infinity();
      d.worst_road = ra.id;
      continue;
    }
    const ModelRoad& rb = b.roads[ib];
    const double length = ra.length();
    const auto n = static_cast<long>(std::ceil(length / step_m));
    for (long k = 0; k <= n; ++k) {
      const double s = std::min(length, static_cast<double>(k) * step_m);
      std::vector<double> ts{0.0};
      const LaneSection& sec = section_at(ra, s);
      for (const auto* side : {&sec.left, &sec.right})
        for (const LaneModel& l : *side) ts.push_back(lane_border_t(ra, s, l.id));
      const Pose2 pose_a = ra.plan.at(s), pose_b = rb.plan.at(s);  // once per station, not per border
      for (double t : ts) {
        const Vec3 p = surface_point(ra, pose_a, s, t), q = surface_point(rb, pose_b, s, t);
        const double xy = (p.head<2>() - q.head<2>()).norm(), z = std::abs(p.z() - q.z());
        ++d.points;
        if (xy > d.max_xy_m || z > d.max_z_m) d.worst_road = ra.id;
        d.max_xy_m = std::max(d.max_xy_m, xy);
        d.max_z_m = std::max(d.max_z_m, z);
      }
    }
  }
  return d;
}

double linked_grade_cap(const RoadModel& model, const std::vector<double>& cap, std::size_t index) {
  const auto given = [&](std::size_t i) { return i < cap.size() && cap[i] >= 0.0; };
  if (given(index)) return cap[index];
  double c = 0.0;
  for (const auto& link : {model.roads[index].predecessor, model.roads[index].successor}) {
    if (!link || link->element != RoadLink::Element::road) continue;
    const int k = model.road_index(link->id);
    if (k >= 0 && given(static_cast<std::size_t>(k))) c = std::max(c, cap[static_cast<std::size_t>(k)]);
  }
  return c;
}

ModelGrades check_grades(const RoadModel& model, const std::vector<double>& cap, double tolerance,
                         double step_m, double cross_slope_over) {
  if (cap.size() != model.roads.size()) throw InvalidInput("check_grades: one cap per road is required");
  if (!(step_m > 0.0)) throw InvalidInput("check_grades: the step must be > 0 m");
  const auto cap_of = [&](std::size_t i) { return linked_grade_cap(model, cap, i); };
  ModelGrades out;
  for (std::size_t i = 0; i < model.roads.size(); ++i) {
    const ModelRoad& road = model.roads[i];
    GradeCheck& g = road.junction >= 0 ? out.connecting_roads : out.roads;
    const double limit = cap_of(i);
    const double length = road.length();
    const int steps = std::max(1, static_cast<int>(std::ceil(length / step_m)));
    double road_worst = 0.0;
    bool rolled_over = false;
    for (int k = 0; k < steps; ++k) {
      const double s0 = length * k / steps, s1 = length * (k + 1) / steps;
      if (road.junction < 0) {
        CrossSlopeCheck& c = out.cross_slopes;
        const double mid = 0.5 * (s0 + s1);
        const double cross = std::abs(std::tan(road.superelevation.value(mid)));
        c.length_m += s1 - s0;
        if (cross > cross_slope_over) {
          c.length_over_m += s1 - s0;
          rolled_over = true;
        }
        if (100.0 * cross > c.max_percent) {
          c.max_percent = 100.0 * cross;
          c.worst_road = road.id;
          c.worst_s = mid;
          c.worst_xy = road.plan.at(mid).position;
        }
      }
      const double grade =
          std::abs(road.elevation.value(s1) - road.elevation.value(s0)) / std::max(s1 - s0, 1e-9);
      road_worst = std::max(road_worst, grade);
      g.max_grade_percent = std::max(g.max_grade_percent, 100.0 * grade);
      const double excess = 100.0 * (grade - limit);
      if (excess > g.max_excess_percent) {
        g.max_excess_percent = excess;
        g.worst_road = road.id;
        g.worst_s = 0.5 * (s0 + s1);
        g.worst_xy = road.plan.at(g.worst_s).position;
      }
    }
    if (road_worst > limit + tolerance) ++g.roads_over;
    if (rolled_over) ++out.cross_slopes.roads_over;
  }
  return out;
}

}  // namespace relief
