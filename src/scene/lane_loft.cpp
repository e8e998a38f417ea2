#include "scene/lane_loft.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include <Eigen/Geometry>

#include "relief/core/errors.h"
#include "relief/roads/road_surface.h"

namespace relief::detail {

namespace {

constexpr double kSameBorderT = 1e-7;     // borders of one station closer than this share a vertex (m)
constexpr double kSectionSeamT = 1e-6;    // borders on both sides of a section start that coincide (m)
constexpr double kMinStep = 1e-3;         // no bisection below this step (m)
constexpr int kMaxDepth = 24;             // nor deeper than this
constexpr double kMinBreakGap = 0.05;     // plan-view record boundaries closer than this are one break (m)
constexpr double kMaxSkippedTurn = 1e-3;  // ... where the plan turns less than this between them (rad)
constexpr double kDashOn = 3.0;           // broken marks: 3 m painted ...
constexpr double kDashPeriod = 9.0;       // ... then 6 m gap, from the lane section's start

/// Cross-section of a road at one station: t and surface point of each border, by decreasing t.
struct Station {
  double s = 0.0;
  std::vector<double> t;
  std::vector<Vec3> p;
};

/// Borders of one lane section, evaluated with the section's own lanes (so that the end of a
/// section is evaluated with its lanes even at the next section's start). Border j, by
/// decreasing t: the outer borders of the left lanes from the outermost in, the centre lane,
/// the outer borders of the right lanes from the innermost out.
class SectionSampler {
 public:
  SectionSampler(const ModelRoad& road, const LaneSection& section, int only_border = -1)
      : road_(road), section_(section), only_border_(only_border) {}

  [[nodiscard]] std::size_t left_count() const { return section_.left.size(); }
  [[nodiscard]] std::size_t border_count() const { return section_.left.size() + section_.right.size() + 1; }

  /// Lane between border j and border j + 1.
  [[nodiscard]] const LaneModel& gap_lane(std::size_t j) const {
    const std::size_t nl = section_.left.size();
    return j < nl ? section_.left[nl - 1 - j] : section_.right[j - nl];
  }

  /// Road mark on border j.
  [[nodiscard]] const RoadMark& border_mark(std::size_t j) const {
    const std::size_t nl = section_.left.size();
    if (j < nl) return section_.left[nl - 1 - j].mark;
    if (j == nl) return section_.centre_mark;
    return section_.right[j - nl - 1].mark;
  }

  /// Index of the border of lane `lane_id` (lanes listed innermost first), or -1.
  [[nodiscard]] int border_of(int lane_id) const {
    const std::size_t nl = section_.left.size();
    if (lane_id == 0) return static_cast<int>(nl);
    for (std::size_t k = 0; k < section_.left.size(); ++k) {
      if (section_.left[k].id == lane_id) return static_cast<int>(nl - 1 - k);
    }
    for (std::size_t k = 0; k < section_.right.size(); ++k) {
      if (section_.right[k].id == lane_id) return static_cast<int>(nl + 1 + k);
    }
    return -1;
  }

  [[nodiscard]] std::vector<double> border_t(double s) const {
    const double ds = s - section_.s;
    const double offset = road_.lane_offset.value(s);
    const std::size_t nl = section_.left.size();
    std::vector<double> t(border_count());
    t[nl] = offset;
    double sum = offset;
    for (std::size_t k = 0; k < nl; ++k) {
      sum += section_.left[k].width.value(ds);
      t[nl - 1 - k] = sum;
    }
    sum = offset;
    for (std::size_t k = 0; k < section_.right.size(); ++k) {
      sum -= section_.right[k].width.value(ds);
      t[nl + 1 + k] = sum;
    }
    return t;
  }

  [[nodiscard]] Station at(double s) const {
    Station station;
    station.s = s;
    station.t = border_t(s);
    if (only_border_ >= 0) station.t = {station.t[static_cast<std::size_t>(only_border_)]};
    station.p.reserve(station.t.size());
    const Pose2 pose = road_.plan.at(s);  // once for every border of the station
    for (const double t : station.t) station.p.push_back(surface_point(road_, pose, s, t));
    return station;
  }

  [[nodiscard]] Vec3 point(double s, double t) const { return surface_point(road_, s, t); }

  /// Chord error of the step a -> b: every border at 1/4, 1/2 and 3/4 of the step, and the twist
  /// of every quad (how far its diagonals' midpoints leave the quad's plane). `mid` receives the
  /// station at 1/2, `mid_error` the part of the error measured there.
  double step_error(const Station& a, const Station& b, Station& mid, double& mid_error) const {
    double error = 0.0;
    mid_error = 0.0;
    for (const double f : {0.25, 0.5, 0.75}) {
      Station m = at(a.s + f * (b.s - a.s));
      for (std::size_t j = 0; j < m.p.size(); ++j) {
        const double e = (m.p[j] - ((1.0 - f) * a.p[j] + f * b.p[j])).norm();
        error = std::max(error, e);
        if (f == 0.5) mid_error = std::max(mid_error, e);
      }
      if (f == 0.5) mid = std::move(m);
    }
    // Twist: the two triangles of a non-planar quad leave the surface by a quarter of
    // (A_r + B_l - A_l - B_r) along the quad's normal (zero for a planar quad).
    for (std::size_t j = 0; j + 1 < a.p.size(); ++j) {
      const Vec3 normal = (b.p[j] - a.p[j + 1]).cross(a.p[j] - b.p[j + 1]);
      if (!(normal.norm() > 0.0)) continue;
      const double e = std::abs(normal.normalized().dot(a.p[j + 1] + b.p[j] - a.p[j] - b.p[j + 1])) / 4.0;
      error = std::max(error, e);
      mid_error = std::max(mid_error, e);
    }
    return error;
  }

 private:
  const ModelRoad& road_;
  const LaneSection& section_;
  int only_border_;
};

/// Appends the stations after `a` up to and including `b`, bisecting until the chord error is
/// within tolerance; `max_error` collects the error measured at the accepted steps' middles.
void refine(const SectionSampler& sampler, const Station& a, const Station& b, double tolerance, int depth,
            std::vector<Station>& out, double& max_error) {
  Station mid;
  double mid_error = 0.0;
  const double error = sampler.step_error(a, b, mid, mid_error);
  if (error <= tolerance || depth >= kMaxDepth || b.s - a.s <= kMinStep) {
    max_error = std::max(max_error, mid_error);
    out.push_back(b);
    return;
  }
  refine(sampler, a, mid, tolerance, depth + 1, out, max_error);
  refine(sampler, mid, b, tolerance, depth + 1, out, max_error);
}

/// Stations of one section over [s0, s1]: the breaks, at most max_spacing apart, refined.
std::vector<Station> sample_section(const SectionSampler& sampler, const std::vector<double>& breaks,
                                    const RoadMeshOptions& options, double& max_error) {
  std::vector<Station> stations{sampler.at(breaks.front())};
  for (std::size_t k = 0; k + 1 < breaks.size(); ++k) {
    const double u0 = breaks[k];
    const double u1 = breaks[k + 1];
    const auto steps = static_cast<int>(std::max(1.0, std::ceil((u1 - u0) / options.max_spacing_m - 1e-9)));
    for (int i = 1; i <= steps; ++i) {
      const Station a = stations.back();
      const double s = i == steps ? u1 : u0 + (u1 - u0) * i / steps;
      refine(sampler, a, sampler.at(s), options.tolerance_m, 0, stations, max_error);
    }
  }
  return stations;
}

/// Section start, plan-view record boundaries inside it, section end. A boundary within
/// kMinBreakGap of the last break, or of the end, with a nearly straight piece between them
/// (turning less than kMaxSkippedTurn) is none: the plan view joins two arcs by a line of a
/// millimetre or a few where their tangents all but meet (1 032 of 3 403 records of a generated
/// mountain tile are under 1 cm), and a station at each of its ends made triangles that thin,
/// slivers that fold over when a file rounds them to its float grid. Across such a piece the
/// chord refinement bounds the error as anywhere else. A short piece that turns (Liechtenstein's
/// road 10532 ends in a 2.7 cm arc of 0.3 m radius, 5 degrees) keeps its station: without it the
/// road's last cross-section turned against the one before and its loft folded.
std::vector<double> section_breaks(const ModelRoad& road, double s0, double s1) {
  std::vector<double> breaks{s0};
  const auto straight = [&](double a, double b) { return road.plan.total_turn(a, b) < kMaxSkippedTurn; };
  for (const PlanGeometry& record : road.plan.records()) {
    if (record.s <= s0 + 1e-9 || record.s >= s1 - 1e-9) continue;
    if (record.s - breaks.back() < kMinBreakGap && straight(breaks.back(), record.s)) continue;
    if (s1 - record.s < kMinBreakGap && straight(record.s, s1)) continue;
    breaks.push_back(record.s);
  }
  breaks.push_back(s1);
  return breaks;
}

/// One vertex of the loft, shared by the lanes (and sections) that meet there.
struct Node {
  Vec3 p;
  Vec2 uv;
  std::uint32_t index[2] = {kNoVertex, kNoVertex};  // in the road mesh, in the sidewalk mesh
};

class Loft {
 public:
  Loft(const ModelRoad& road, MeshBuilder& road_mesh, MeshBuilder& sidewalk)
      : road_(road), meshes_{&road_mesh, &sidewalk} {}

  std::size_t add_node(const Vec3& p, double s, double t) {
    nodes_.push_back(Node{p, Vec2(t, s)});
    return nodes_.size() - 1;
  }

  std::uint32_t vertex(std::size_t node, int mesh) {
    Node& n = nodes_[node];
    std::uint32_t& index = n.index[mesh];
    if (index == kNoVertex) index = meshes_[mesh]->add_vertex(n.p, n.uv);
    return index;
  }

  void quad(std::size_t al, std::size_t ar, std::size_t bl, std::size_t br, int mesh) {
    // Counter-clockwise from above: s forward and t to the left form a right-handed frame.
    const std::uint32_t a_l = vertex(al, mesh), a_r = vertex(ar, mesh);
    const std::uint32_t b_l = vertex(bl, mesh), b_r = vertex(br, mesh);
    meshes_[mesh]->add_triangle(a_r, b_r, b_l, road_.id);
    meshes_[mesh]->add_triangle(a_r, b_l, a_l, road_.id);
  }

  /// Vertices of a station over the contiguous range of lanes that go to `mesh`.
  std::vector<std::uint32_t> end_vertices(const SectionSampler& sampler, const std::vector<std::size_t>& ids,
                                          int mesh) {
    int first = -1, last = -1;
    for (std::size_t j = 0; j + 1 < ids.size(); ++j) {
      if (mesh_of(sampler.gap_lane(j)) != mesh) continue;
      if (first < 0) first = static_cast<int>(j);
      last = static_cast<int>(j);
    }
    std::vector<std::uint32_t> out;
    if (first < 0) return out;
    for (auto j = static_cast<std::size_t>(first); j <= static_cast<std::size_t>(last) + 1; ++j) {
      const std::uint32_t v = vertex(ids[j], mesh);
      if (out.empty() || out.back() != v) out.push_back(v);
    }
    return out;
  }

  static int mesh_of(const LaneModel& lane) { return lane.type == "sidewalk" ? 1 : 0; }

 private:
  const ModelRoad& road_;
  MeshBuilder* meshes_[2];
  std::vector<Node> nodes_;
};

/// Mark strips of one section: each painted interval is sampled at its ends and at the loft
/// stations inside it; double lines are two strips one width apart. The vertices of strips that
/// reach the road's start (s = 0) or end go to `start` / `end`, to be welded to the linked road's.
void emit_marks(const ModelRoad& road, const SectionSampler& sampler, const std::vector<Station>& stations,
                const RoadMeshOptions& options, MeshBuilder& marking, RoadEnd& start, RoadEnd& end) {
  const double s0 = stations.front().s;
  const double s1 = stations.back().s;
  const double length = road.length();
  struct Line {
    double offset;
    bool broken;
  };
  for (std::size_t j = 0; j < sampler.border_count(); ++j) {
    const RoadMark& mark = sampler.border_mark(j);
    const double w = mark.width_m;
    if (mark.type == RoadMark::Type::none || !(w > 0.0)) continue;
    std::vector<Line> lines;
    switch (mark.type) {
      case RoadMark::Type::solid:
        lines = {{0.0, false}};
        break;
      case RoadMark::Type::broken:
        lines = {{0.0, true}};
        break;
      case RoadMark::Type::solid_solid:
        lines = {{w, false}, {-w, false}};
        break;
      case RoadMark::Type::solid_broken:
        lines = {{w, false}, {-w, true}};
        break;
      case RoadMark::Type::broken_solid:
        lines = {{w, true}, {-w, false}};
        break;
      case RoadMark::Type::none:
        break;
    }
    for (const Line& line : lines) {
      std::vector<std::pair<double, double>> painted;
      if (!line.broken) {
        painted.emplace_back(s0, s1);
      } else {
        for (double u = s0; u < s1 - 1e-6; u += kDashPeriod)
          painted.emplace_back(u, std::min(u + kDashOn, s1));
      }
      for (const auto& [u0, u1] : painted) {
        if (u1 - u0 < 1e-6) continue;
        std::vector<double> ss{u0};
        auto it = std::upper_bound(stations.begin(), stations.end(), u0 + 1e-9,
                                   [](double value, const Station& st) { return value < st.s; });
        for (; it != stations.end() && it->s < u1 - 1e-9; ++it) ss.push_back(it->s);
        ss.push_back(u1);
        std::uint32_t prev_l = kNoVertex, prev_r = kNoVertex;
        for (const double s : ss) {
          const double t = sampler.border_t(s)[j] + line.offset;
          const Vec3 lift(0.0, 0.0, options.marking_lift_m);
          const std::uint32_t l = marking.add_vertex(sampler.point(s, t + 0.5 * w) + lift, Vec2(0.5 * w, s));
          const std::uint32_t r = marking.add_vertex(sampler.point(s, t - 0.5 * w) + lift, Vec2(-0.5 * w, s));
          if (prev_l != kNoVertex) {
            marking.add_triangle(prev_r, r, l, road.id);
            marking.add_triangle(prev_r, l, prev_l, road.id);
          }
          if (s <= 1e-9) start.marking_vertices.insert(start.marking_vertices.end(), {l, r});
          if (s >= length - 1e-9) end.marking_vertices.insert(end.marking_vertices.end(), {l, r});
          prev_l = l;
          prev_r = r;
        }
      }
    }
  }
}

}  // namespace

LoftedRoad loft_road(const ModelRoad& road, const RoadMeshOptions& options, MeshBuilder& road_mesh,
                     MeshBuilder& sidewalk, MeshBuilder* marking) {
  if (road.plan.records().empty())
    throw InvalidInput("road " + std::to_string(road.id) + " has no plan view");
  if (road.sections.empty()) throw InvalidInput("road " + std::to_string(road.id) + " has no lane sections");
  const double length = road.length();
  Loft loft(road, road_mesh, sidewalk);
  LoftedRoad result;
  bool first = true;
  Station previous;
  std::vector<std::size_t> previous_ids;
  for (std::size_t k = 0; k < road.sections.size(); ++k) {
    const LaneSection& section = road.sections[k];
    const double s0 = std::clamp(section.s, 0.0, length);
    const double s1 = k + 1 < road.sections.size() ? std::clamp(road.sections[k + 1].s, 0.0, length) : length;
    if (s1 - s0 <= 1e-9) continue;
    const SectionSampler sampler(road, section);
    const std::vector<Station> stations =
        sample_section(sampler, section_breaks(road, s0, s1), options, result.max_deviation_m);

    // One node per border and station; coincident borders share one, and the first station
    // reuses the previous section's last nodes where the borders coincide.
    std::vector<std::vector<std::size_t>> ids(stations.size());
    for (std::size_t i = 0; i < stations.size(); ++i) {
      const Station& st = stations[i];
      std::size_t q = 0;
      for (std::size_t j = 0; j < st.t.size(); ++j) {
        if (j > 0 && std::abs(st.t[j] - st.t[j - 1]) < kSameBorderT) {
          ids[i].push_back(ids[i].back());
          continue;
        }
        if (i == 0 && !first) {
          while (q < previous.t.size() && previous.t[q] > st.t[j] + kSectionSeamT) ++q;
          if (q < previous.t.size() && std::abs(previous.t[q] - st.t[j]) <= kSectionSeamT) {
            ids[i].push_back(previous_ids[q]);
            continue;
          }
        }
        ids[i].push_back(loft.add_node(st.p[j], st.s, st.t[j]));
      }
    }
    for (std::size_t i = 0; i + 1 < stations.size(); ++i) {
      for (std::size_t j = 0; j + 1 < ids[i].size(); ++j) {
        loft.quad(ids[i][j], ids[i][j + 1], ids[i + 1][j], ids[i + 1][j + 1],
                  Loft::mesh_of(sampler.gap_lane(j)));
      }
    }
    for (const std::vector<std::size_t>& station : ids) {
      const std::vector<std::uint32_t> across = loft.end_vertices(sampler, station, 0);
      if (across.size() < 2) continue;
      if (result.left_edge.empty() || result.left_edge.back() != across.front())
        result.left_edge.push_back(across.front());
      if (result.right_edge.empty() || result.right_edge.back() != across.back())
        result.right_edge.push_back(across.back());
    }
    if (first) {
      result.start.road_vertices = loft.end_vertices(sampler, ids.front(), 0);
      result.start.sidewalk_vertices = loft.end_vertices(sampler, ids.front(), 1);
    }
    result.end.road_vertices = loft.end_vertices(sampler, ids.back(), 0);
    result.end.sidewalk_vertices = loft.end_vertices(sampler, ids.back(), 1);
    if (marking != nullptr) emit_marks(road, sampler, stations, options, *marking, result.start, result.end);
    result.stations += stations.size();
    previous = stations.back();
    previous_ids = ids.back();
    first = false;
  }
  return result;
}

std::vector<Vec3> sample_lane_border(const ModelRoad& road, int lane_id, const RoadMeshOptions& options) {
  if (road.plan.records().empty())
    throw InvalidInput("road " + std::to_string(road.id) + " has no plan view");
  const double length = road.length();
  std::vector<Vec3> points;
  double ignored = 0.0;
  for (std::size_t k = 0; k < road.sections.size(); ++k) {
    const LaneSection& section = road.sections[k];
    const double s0 = std::clamp(section.s, 0.0, length);
    const double s1 = k + 1 < road.sections.size() ? std::clamp(road.sections[k + 1].s, 0.0, length) : length;
    if (s1 - s0 <= 1e-9) continue;
    const int border = SectionSampler(road, section).border_of(lane_id);
    if (border < 0) {
      throw InvalidInput("road " + std::to_string(road.id) + ": no lane " + std::to_string(lane_id) +
                         " in the lane section at s=" + std::to_string(section.s));
    }
    const SectionSampler sampler(road, section, border);
    for (const Station& st : sample_section(sampler, section_breaks(road, s0, s1), options, ignored)) {
      if (points.empty() || (points.back() - st.p.front()).norm() > 1e-9) points.push_back(st.p.front());
    }
  }
  return points;
}

}  // namespace relief::detail
