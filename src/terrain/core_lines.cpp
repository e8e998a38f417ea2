#include "terrain/core_lines.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <deque>
#include <limits>
#include <optional>
#include <utility>

#include "terrain/outline_index.h"

namespace relief::terrain_detail {
namespace {

// How far from a point of a core line, at most, the DEM's height is looked for where it has none
// at the point (the tiles' windows reach a halo beyond the line, 500 m by default).
constexpr double kFallbackReachM = 200.0;

using Point2 = Kernel::Point_2;
using Segment2 = Kernel::Segment_2;

// A line of the core: x = c (axis 0, running along y) or y = c (axis 1, running along x).
struct Line {
  int index;  // 0, 1: x = core.min.x, core.max.x; 2, 3: y = core.min.y, core.max.y
  int axis;
  double c;
  [[nodiscard]] Vec2 at(double along) const { return axis == 0 ? Vec2(c, along) : Vec2(along, c); }
  [[nodiscard]] double across(const Vec3& p) const { return p[axis]; }
  [[nodiscard]] double along(const Vec3& p) const { return p[1 - axis]; }
};

// An outline edge crossing a line: `lo` on the low side (across < c), `hi` on the other.
struct Crossing {
  double along;
  Vec3 lo, hi;
};

bool lex_less(const Vec3& a, const Vec3& b) {
  return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
}

Point2 plan(const Vec3& p) {
  return {p.x(), p.y()};
}
Point2 plan(const Vec2& p) {
  return {p.x(), p.y()};
}

// A node of a chain: a point of the line (inserted) or an outline vertex (there already).
struct Node {
  Vec3 p;
  double along;          // the line's coordinate it stands for (a crossing's, for an outline vertex)
  bool outline = false;  // an end of a road edge the line crosses
};

class LineCutter {
 public:
  LineCutter(Tin& tin, GridSamples& grid, const DemSampler& dem, const Aabb2& core, double step,
             const std::vector<Polyline3>& outline, const TerrainOptions& o, CoreLines& out)
      : tin_(tin),
        grid_(grid),
        dem_(dem),
        core_(core),
        step_(step),
        outline_(outline),
        options_(o),
        index_(outline, std::max(o.max_slope_width_m, o.constraint_clearance_m)),
        out_(out) {}

  void cut(const Line& line, const std::array<double, 2>& crossing_lines) {
    // Where the line enters and leaves the triangulation (its convex hull: the samples' and the
    // outline's, which may reach beyond the DEM); the chain runs from one to the other.
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    auto hull = tin_.incident_faces(tin_.infinite_vertex());
    const auto first = hull;
    do {
      const int i = hull->index(tin_.infinite_vertex());
      const Point& u = hull->vertex(Tin::ccw(i))->point();
      const Point& w = hull->vertex(Tin::cw(i))->point();
      const double du = u[line.axis] - line.c, dw = w[line.axis] - line.c;
      if ((du < 0.0 && dw < 0.0) || (du > 0.0 && dw > 0.0)) continue;
      const double t = du == dw ? 0.0 : du / (du - dw);
      for (const double a :
           {u[1 - line.axis] + t * (w[1 - line.axis] - u[1 - line.axis]),
            du == dw ? w[1 - line.axis] : u[1 - line.axis] + t * (w[1 - line.axis] - u[1 - line.axis])}) {
        lo = std::min(lo, a);
        hi = std::max(hi, a);
      }
    } while (++hull != first);
    if (!(lo < hi)) return;
    // The ends beyond the hull, at the first whole multiples of the step a centimetre or more
    // out: a point computed on a hull edge may round to its inside, where a sliver between it and
    // the edge would join the two sides; outside, it is a vertex of the hull. On the step's
    // lattice, where a neighbour whose terrain reaches further has a point of its own line.
    const double first_j = std::floor((lo - 0.01) / step_), last_j = std::ceil((hi + 0.01) / step_);
    lo = first_j * step_;
    hi = last_j * step_;

    // The points: whole multiples of the step, the crossing lines, the two ends.
    std::vector<double> along;
    for (double j = first_j + 1.0; j < last_j; ++j) along.push_back(j * step_);
    for (const double v : crossing_lines)
      if (v > lo && v < hi) along.push_back(v);
    std::sort(along.begin(), along.end());
    along.erase(std::unique(along.begin(), along.end()), along.end());
    std::vector<Node> points;
    if (const std::optional<double> z = end_height(line.at(lo)))
      points.push_back({Vec3(line.at(lo).x(), line.at(lo).y(), *z), lo});
    for (const double a : along) {
      if (const std::optional<double> z = terrain_height(line.at(a)))
        points.push_back({Vec3(line.at(a).x(), line.at(a).y(), *z), a});
    }
    if (const std::optional<double> z = end_height(line.at(hi)))
      points.push_back({Vec3(line.at(hi).x(), line.at(hi).y(), *z), hi});

    // The outline edges crossing the line, in order along it.
    std::vector<Crossing> crossings;
    near_.clear();
    for (const Polyline3& loop : outline_) {
      for (std::size_t k = 0; k < loop.size(); ++k) {
        Vec3 a = loop[k], b = loop[(k + 1) % loop.size()];
        if ((line.across(a) < line.c) == (line.across(b) < line.c)) continue;
        if (line.across(a) >= line.c) std::swap(a, b);
        const double t = (line.c - line.across(a)) / (line.across(b) - line.across(a));
        crossings.push_back({line.along(a) + t * (line.along(b) - line.along(a)), a, b});
      }
    }
    std::sort(crossings.begin(), crossings.end(), [](const Crossing& x, const Crossing& y) {
      if (x.along != y.along) return x.along < y.along;
      if (x.lo != y.lo) return lex_less(x.lo, y.lo);
      return lex_less(x.hi, y.hi);
    });
    // The outline edges a detour may meet: those within the slab the crossing edges span.
    double reach = 0.0;
    for (const Crossing& x : crossings)
      reach = std::max({reach, line.c - line.across(x.lo), line.across(x.hi) - line.c});
    for (const Polyline3& loop : outline_) {
      for (std::size_t k = 0; k < loop.size(); ++k) {
        const Vec3& a = loop[k];
        const Vec3& b = loop[(k + 1) % loop.size()];
        if (std::max(line.across(a), line.across(b)) < line.c - reach ||
            std::min(line.across(a), line.across(b)) > line.c + reach)
          continue;
        near_.emplace_back(plan(a), plan(b));
      }
    }

    // Interval by interval between crossings: the points in it, joined to the crossing edges.
    std::size_t p = 0;
    open_end_.reset();
    for (std::size_t k = 0; k <= crossings.size(); ++k) {
      const Crossing* start = k > 0 ? &crossings[k - 1] : nullptr;
      const Crossing* end = k < crossings.size() ? &crossings[k] : nullptr;
      std::vector<Node> chain;
      while (p < points.size() && (end == nullptr || points[p].along < end->along)) {
        if (start == nullptr || points[p].along > start->along) chain.push_back(points[p]);
        ++p;
      }
      // A point of the line close to each crossing (the first of 0.5, 1, 2... m from it that
      // keeps clear of the road edges), so that the detour to the edge's end is short and seldom
      // meets another road edge (the DEM step may be 30 m).
      if (start != nullptr) {
        const double limit = chain.empty() ? (end != nullptr ? end->along : hi) : chain.front().along;
        if (const std::optional<Node> n = near_crossing(line, start->along, limit, 1.0))
          chain.insert(chain.begin(), *n);
      }
      if (end != nullptr) {
        const double limit = chain.empty() ? (start != nullptr ? start->along : lo) : chain.back().along;
        if (const std::optional<Node> n = near_crossing(line, end->along, limit, -1.0)) chain.push_back(*n);
      }
      if (chain.empty()) {
        // No point between two crossings: a narrow strip of terrain (or paved area) is left open
        // unless one edge of the outline reaches the next.
        if (start != nullptr && end != nullptr && start->along < end->along &&
            !paved(line.at(0.5 * (start->along + end->along))))
          bridge(line, *start, *end);
        continue;
      }
      if (start != nullptr) {
        const std::optional<Node> n = detour(*start, chain.front().p);
        if (n) chain.insert(chain.begin(), *n);
      }
      if (end != nullptr) {
        const std::optional<Node> n = detour(*end, chain.back().p);
        if (n) chain.push_back(*n);
      }
      if (chain.front().outline) {
        link_across_paved(line, chain.front());
      }
      insert_chain(line, chain);
      open_end_ = chain.back().outline ? std::optional<Node>(chain.back()) : std::nullopt;
    }
  }

  // Inserts the pieces across the paved area, and marks the faces they make paved.
  void insert_across_paved() {
    for (auto f = tin_.finite_faces_begin(); f != tin_.finite_faces_end(); ++f) f->info().visited = true;
    for (const auto& [index, ends] : across_paved_) {
      const VertexHandle a = vertex(ends.first), b = vertex(ends.second);
      const Tin::Constraint_id id = tin_.insert_constraint(a, b);
      hint_ = b->face();
      out_.separators.push_back({id, ends.first.p.head<2>(), ends.second.p.head<2>(), index});
    }
    for (auto f = tin_.finite_faces_begin(); f != tin_.finite_faces_end(); ++f) {
      if (f->info().visited) continue;
      f->info().visited = true;
      f->info().paved = true;  // made in the paved area
    }
  }

 private:
  // The terrain's height at a point of a line (the DEM on the batter), or nullopt where the point
  // is paved, outside the terrain, without a DEM height or closer than the clearance to a road
  // edge.
  std::optional<double> terrain_height(const Vec2& p) {
    Tin::Locate_type type{};
    int li = 0;
    const FaceHandle f = tin_.locate(Point(p.x(), p.y(), 0.0), type, li, hint_);
    if (type == Tin::OUTSIDE_CONVEX_HULL || type == Tin::OUTSIDE_AFFINE_HULL) return std::nullopt;
    hint_ = f;
    if (type == Tin::VERTEX && f->vertex(li)->info().outline) return std::nullopt;
    if (type == Tin::FACE && f->info().paved) return std::nullopt;
    if (type == Tin::EDGE && f->info().paved && f->neighbor(li)->info().paved) return std::nullopt;
    const std::optional<OutlineHit> hit = index_.nearest(p);
    if (hit && hit->distance_m < options_.constraint_clearance_m) return std::nullopt;
    const std::optional<double> z = line_dem_height(p);
    if (!z) return std::nullopt;
    if (!hit || hit->distance_m >= options_.max_slope_width_m) return *z;
    const double reach = hit->distance_m / options_.slope_run_per_rise;
    return std::clamp(*z, hit->z - reach, hit->z + reach);
  }

  // The DEM's height at a point of a line, or where it has none there (a void, or beyond the
  // DEM's edge while the terrain still reaches the line over the roads' outline), the mean of the
  // nearest valid probes around it: at 1, 2, 4... DEM steps, up to kFallbackReachM, along the
  // axes and the diagonals. A function of the DEM and the point alone, so that two tiles whose
  // terrain both reach the line cut it at the same vertices; without it the line had no point
  // there, and the flood telling the core's side crossed the gap (Portland's 10 m DEM ends 42 to
  // 73 m short of a tile line).
  [[nodiscard]] std::optional<double> line_dem_height(const Vec2& p) const {
    if (const std::optional<double> z = dem_.height_at(p)) return z;
    // The axes, then the diagonals.
    static constexpr std::array<double, 8> kU{1.0, 0.0, -1.0, 0.0, 1.0, -1.0, -1.0, 1.0};
    static constexpr std::array<double, 8> kV{0.0, 1.0, 0.0, -1.0, 1.0, 1.0, -1.0, -1.0};
    for (double d = step_; d <= std::max(step_, kFallbackReachM); d *= 2.0) {
      double sum = 0.0;
      int n = 0;
      for (std::size_t k = 0; k < kU.size(); ++k) {
        const double s = k < 4 ? d : d / std::sqrt(2.0);
        if (const std::optional<double> z = dem_.height_at(p + Vec2(kU[k] * s, kV[k] * s))) {
          sum += *z;
          ++n;
        }
      }
      if (n > 0) return sum / n;
    }
    return std::nullopt;
  }

  // The first point of the line 0.5, 1, 2... m from a crossing at `from` towards `limit`
  // (`direction` +1 or -1), short of it, where the terrain has a height.
  std::optional<Node> near_crossing(const Line& line, double from, double limit, double direction) {
    for (double d = 0.5; d <= 16.0; d *= 2.0) {
      const double a = from + direction * d;
      if (direction * (limit - a) <= 0.0) break;
      if (const std::optional<double> z = terrain_height(line.at(a)))
        return Node{Vec3(line.at(a).x(), line.at(a).y(), *z), a};
    }
    return std::nullopt;
  }

  // An end of a line, on the triangulation's hull (a tile's own: the terrain ends there): the
  // DEM's height, or the hull's where the DEM has none; nullopt on a road.
  std::optional<double> end_height(const Vec2& p) {
    Tin::Locate_type type{};
    int li = 0;
    const FaceHandle f = tin_.locate(Point(p.x(), p.y(), 0.0), type, li, hint_);
    if (type == Tin::OUTSIDE_AFFINE_HULL) return std::nullopt;
    if (type == Tin::VERTEX) return f->vertex(li)->point().z();
    FaceHandle g = f;
    if (tin_.is_infinite(g)) g = g->neighbor(g->index(tin_.infinite_vertex()));
    if (tin_.is_infinite(g) || g->info().paved) return std::nullopt;
    if (const std::optional<double> z = line_dem_height(p)) return *z;
    if (!tin_.is_infinite(f)) return interpolate(g, p.x(), p.y());
    // Beyond the hull and the DEM: the height of the hull edge's nearest point (a plane
    // extrapolated a step out may be hundreds of metres off).
    const int i = f->index(tin_.infinite_vertex());
    const Point& u = f->vertex(Tin::ccw(i))->point();
    const Point& w = f->vertex(Tin::cw(i))->point();
    const Vec2 d(w.x() - u.x(), w.y() - u.y());
    const double t = std::clamp((p - Vec2(u.x(), u.y())).dot(d) / d.squaredNorm(), 0.0, 1.0);
    return u.z() + t * (w.z() - u.z());
  }

  bool paved(const Vec2& p) {
    Tin::Locate_type type{};
    int li = 0;
    const FaceHandle f = tin_.locate(Point(p.x(), p.y(), 0.0), type, li, hint_);
    if (type == Tin::OUTSIDE_CONVEX_HULL || type == Tin::OUTSIDE_AFFINE_HULL) return true;
    hint_ = f;
    if (type == Tin::FACE) return f->info().paved;
    return type != Tin::EDGE || (f->info().paved && f->neighbor(li)->info().paved);
  }

  // Closes a line's chain across the paved area between the last piece's end (a road edge's
  // vertex) and `next` (another): straight, where that stays in the paved area and meets no road
  // edge but at its ends. Inserted last: constraints in the paved area make faces the paved
  // marking has not seen.
  void link_across_paved(const Line& line, const Node& next) {
    if (!open_end_ || open_end_->p == next.p) return;
    const Point2 p = plan(open_end_->p), q = plan(next.p);
    const Segment2 s(p, q);
    for (const Segment2& e : near_) {
      if (!CGAL::do_intersect(s, e)) continue;
      const bool shares = e.source() == p || e.target() == p || e.source() == q || e.target() == q;
      if (!shares || (e.source() == p && e.target() == q) || (e.source() == q && e.target() == p)) {
        ++out_.blocked;
        return;
      }
      const Point2& other = (e.source() == p || e.source() == q) ? e.target() : e.source();
      if (CGAL::collinear(p, q, other) && CGAL::collinear_are_ordered_along_line(p, other, q)) {
        ++out_.blocked;
        return;
      }
    }
    if (!paved_toward(open_end_->p, next.p) || !paved_toward(next.p, open_end_->p)) {
      ++out_.blocked;
      return;
    }
    across_paved_.push_back({line.index, {*open_end_, next}});
  }

  // Whether the segment from the vertex at `from` towards `to` starts into a paved face (false
  // when it runs along an edge there). Exact, where a midpoint test is not: a chord of a road
  // edge bent by a hair has its midpoint on the edge.
  bool paved_toward(const Vec3& from, const Vec3& to) {
    Tin::Locate_type type{};
    int li = 0;
    const FaceHandle at = tin_.locate(Point(from.x(), from.y(), 0.0), type, li, hint_);
    if (type != Tin::VERTEX) return false;
    const VertexHandle v = at->vertex(li);
    const Point2 a = plan(from), c = plan(to);
    auto f = tin_.incident_faces(v);
    const auto first = f;
    do {
      if (tin_.is_infinite(f)) continue;
      const int i = f->index(v);
      const Point2 u(f->vertex(Tin::ccw(i))->point().x(), f->vertex(Tin::ccw(i))->point().y());
      const Point2 w(f->vertex(Tin::cw(i))->point().x(), f->vertex(Tin::cw(i))->point().y());
      const CGAL::Orientation from_u = CGAL::orientation(a, u, c), to_w = CGAL::orientation(a, c, w);
      if (from_u == CGAL::COLLINEAR && (u - a) * (c - a) > 0.0) {
        // Along the edge to u: paved when it is no road edge and both its faces are paved (the
        // paved area's own triangulation often joins a road's two edges' vertices already).
        const int k = Tin::cw(i);  // the edge v-u is opposite f's vertex cw of v
        const FaceHandle g = f->neighbor(k);
        return !f->is_constrained(k) && f->info().paved && !tin_.is_infinite(g) && g->info().paved;
      }
      if (to_w == CGAL::COLLINEAR && (w - a) * (c - a) > 0.0)
        continue;  // along the edge to w: seen from its other face
      if (from_u == CGAL::LEFT_TURN && to_w == CGAL::LEFT_TURN) return f->info().paved;
    } while (++f != first);
    return false;
  }

  // Whether the segment pq meets an outline edge anywhere but at q, when q is one of its ends.
  [[nodiscard]] bool blocked(const Vec3& p3, const Vec3& q3) const {
    const Point2 p = plan(p3), q = plan(q3);
    if (p == q) return true;
    const Segment2 s(p, q);
    for (const Segment2& e : near_) {
      if (!CGAL::do_intersect(s, e)) continue;
      const bool shares_q = e.source() == q || e.target() == q;
      if (!shares_q) return true;
      const Point2& other = e.source() == q ? e.target() : e.source();
      if (CGAL::collinear(p, q, other) && other != p && CGAL::collinear_are_ordered_along_line(q, other, p))
        return true;                                        // runs along the edge
      if (e.source() == p || e.target() == p) return true;  // pq is an outline edge
    }
    return false;
  }

  // The end of the crossing edge a chain goes to from `from`: the nearer to the crossing first,
  // the one whose segment from `from` meets no road edge.
  std::optional<Node> detour(const Crossing& x, const Vec3& from) {
    std::array<const Vec3*, 2> ends{&x.lo, &x.hi};
    const auto distance = [&](const Vec3& e) { return std::abs(e[0] - from[0]) + std::abs(e[1] - from[1]); };
    if (distance(x.hi) < distance(x.lo)) std::swap(ends[0], ends[1]);
    for (const Vec3* e : ends) {
      if (!blocked(from, *e)) {
        ++out_.detours;
        return Node{*e, x.along, true};
      }
    }
    ++out_.blocked;
    return std::nullopt;
  }

  // Two crossings with no point between: an end of the one joined to an end of the other.
  void bridge(const Line& line, const Crossing& a, const Crossing& b) {
    for (const Vec3* p : {&a.lo, &a.hi}) {
      for (const Vec3* q : {&b.lo, &b.hi}) {
        if (*p == *q) {  // the edges meet: the strip is closed there
          link_across_paved(line, Node{*p, a.along, true});
          open_end_ = Node{*p, b.along, true};
          return;
        }
      }
    }
    for (const Vec3* p : {&a.lo, &a.hi}) {
      for (const Vec3* q : {&b.lo, &b.hi}) {
        const Vec2 mid = 0.5 * (p->head<2>() + q->head<2>());
        if (blocked(*p, *q) || blocked(*q, *p) || paved(mid)) continue;
        ++out_.detours;
        const std::vector<Node> chain{Node{*p, a.along, true}, Node{*q, b.along, true}};
        link_across_paved(line, chain.front());
        insert_chain(line, chain);
        open_end_ = chain.back();
        return;
      }
    }
    ++out_.blocked;
    open_end_.reset();
  }

  VertexHandle vertex(const Node& n) {
    Tin::Locate_type type{};
    int li = 0;
    const FaceHandle f = tin_.locate(Point(n.p.x(), n.p.y(), 0.0), type, li, hint_);
    if (type == Tin::VERTEX) return f->vertex(li);
    const VertexHandle v = tin_.insert(Point(n.p.x(), n.p.y(), n.p.z()), f);
    ++out_.line_vertices;
    return v;
  }

  void insert_chain(const Line& line, const std::vector<Node>& chain) {
    if (chain.size() < 2) return;
    std::vector<VertexHandle> v;
    v.reserve(chain.size());
    for (const Node& n : chain) {
      v.push_back(vertex(n));
      hint_ = v.back()->face();
    }
    for (std::size_t i = 0; i + 1 < chain.size(); ++i) {
      if (v[i] == v[i + 1]) continue;
      const Tin::Constraint_id id = tin_.insert_constraint(v[i], v[i + 1]);
      hint_ = v[i + 1]->face();
      flag_near(chain[i].p, chain[i + 1].p);
      const CoreSeparator s{id, chain[i].p.head<2>(), chain[i + 1].p.head<2>(), line.index};
      out_.separators.push_back(s);
    }
  }

  // Samples within the clearance of segment ab never become vertices.
  void flag_near(const Vec3& a, const Vec3& b) {
    const double r = options_.constraint_clearance_m;
    const Vec2 pa = a.head<2>(), pb = b.head<2>(), d = pb - pa;
    const double len2 = d.squaredNorm();
    const auto index = [&](double v, int axis, long n) {
      return std::clamp(static_cast<long>(std::floor((v - grid_.origin[axis]) / grid_.step_m)), 0L, n - 1);
    };
    const long i0 = index(std::min(pa.x(), pb.x()) - r, 0, grid_.nx);
    const long i1 = index(std::max(pa.x(), pb.x()) + r, 0, grid_.nx) + 1;
    const long j0 = index(std::min(pa.y(), pb.y()) - r, 1, grid_.ny);
    const long j1 = index(std::max(pa.y(), pb.y()) + r, 1, grid_.ny) + 1;
    for (long j = j0; j <= std::min(j1, grid_.ny - 1); ++j) {
      for (long i = i0; i <= std::min(i1, grid_.nx - 1); ++i) {
        const auto k = static_cast<std::size_t>(j * grid_.nx + i);
        const Vec2 q = grid_.xy(k);
        const double t = len2 > 0.0 ? std::clamp((q - pa).dot(d) / len2, 0.0, 1.0) : 0.0;
        if ((q - (pa + t * d)).norm() < r) grid_.flags[k] |= kNear;
      }
    }
  }

  Tin& tin_;
  GridSamples& grid_;
  const DemSampler& dem_;
  Aabb2 core_;
  double step_;
  const std::vector<Polyline3>& outline_;
  const TerrainOptions& options_;
  OutlineIndex index_;
  CoreLines& out_;
  FaceHandle hint_;
  std::vector<Segment2> near_;
  std::optional<Node> open_end_;  // the last piece's end, when it is a road edge's vertex
  std::vector<std::pair<int, std::pair<Node, Node>>> across_paved_;  // line, ends: inserted last
};

using Key = std::pair<const void*, const void*>;
Key edge_key(const VertexHandle& a, const VertexHandle& b) {
  const void* pa = &*a;
  const void* pb = &*b;
  return pa < pb ? Key{pa, pb} : Key{pb, pa};
}

}  // namespace

CoreLines insert_core_lines(Tin& tin, GridSamples& grid, const DemSampler& dem, const Aabb2& core,
                            double step, const std::vector<Polyline3>& outline, const TerrainOptions& o) {
  CoreLines out;
  LineCutter cutter(tin, grid, dem, core, step, outline, o, out);
  const std::array<double, 2> xs{core.min.x(), core.max.x()}, ys{core.min.y(), core.max.y()};
  for (int i = 0; i < 2; ++i) cutter.cut(Line{i, 0, xs[static_cast<std::size_t>(i)]}, ys);
  for (int i = 0; i < 2; ++i) cutter.cut(Line{2 + i, 1, ys[static_cast<std::size_t>(i)]}, xs);
  cutter.insert_across_paved();
  return out;
}

std::size_t mark_core_faces(Tin& tin, const CoreLines& lines, const Aabb2& core) {
  // Line by line, every face is told the side of the line's chain it lies on: the faces beside
  // the chain's constrained sub-edges (a later constraint may have split a piece) by the side
  // of the piece they lie on, the faces wholly beyond the band the chain keeps within by their
  // side of the line, the others breadth first from those across every edge but the chain's (a
  // face takes the side of its nearest: a gap in a chain, where no end of a road edge could be
  // reached, mislabels only faces in the band, nearer to it), the faces no chain reaches (an
  // island of terrain in the paved area, a line outside the terrain) by their centroid. A line's high side is
  // +x (+y); the core is high of lines 0 and 2, low of 1 and 3.
  const std::array<double, 4> c{core.min.x(), core.max.x(), core.min.y(), core.max.y()};
  std::vector<Key> cut;
  std::deque<FaceHandle> queue;
  std::size_t leaks = 0;
  const auto label = [&](const FaceHandle& f, std::int8_t high) {
    if (tin.is_infinite(f) || f->info().paved) return;
    if (f->info().side < 0) {
      f->info().side = high;
      queue.push_back(f);
    } else if (f->info().side != high) {
      ++leaks;
    }
  };
  for (auto f = tin.finite_faces_begin(); f != tin.finite_faces_end(); ++f) f->info().core = 0b0101;
  for (int line = 0; line < 4; ++line) {
    const int axis = line / 2;
    for (auto f = tin.finite_faces_begin(); f != tin.finite_faces_end(); ++f) f->info().side = -1;
    cut.clear();
    // The chain keeps within `band` of its line: a face wholly beyond lies on that side.
    double band = 0.0;
    for (const CoreSeparator& s : lines.separators) {
      if (s.line != line) continue;
      band = std::max({band, std::abs(s.a[axis] - c[static_cast<std::size_t>(line)]),
                       std::abs(s.b[axis] - c[static_cast<std::size_t>(line)])});
    }
    for (const CoreSeparator& s : lines.separators) {
      if (s.line != line || s.id == Tin::Constraint_id()) continue;
      const Point2 a = plan(s.a), b = plan(s.b);
      const std::vector<VertexHandle> chain(tin.vertices_in_constraint_begin(s.id),
                                            tin.vertices_in_constraint_end(s.id));
      for (std::size_t k = 0; k + 1 < chain.size(); ++k) {
        FaceHandle f;
        int i = 0;
        if (!tin.is_edge(chain[k], chain[k + 1], f, i)) continue;
        cut.push_back(edge_key(chain[k], chain[k + 1]));
        for (const FaceHandle& g : {f, f->neighbor(i)}) {
          if (tin.is_infinite(g)) continue;
          const VertexHandle r = g->vertex(3 - g->index(chain[k]) - g->index(chain[k + 1]));
          const CGAL::Orientation turn = CGAL::orientation(a, b, Point2(r->point().x(), r->point().y()));
          if (turn == CGAL::COLLINEAR) continue;
          // Directed along increasing coordinate: +x is right of an x line, +y left of a y line.
          label(g, static_cast<std::int8_t>(turn == (axis == 0 ? CGAL::RIGHT_TURN : CGAL::LEFT_TURN)));
        }
      }
    }
    for (auto f = tin.finite_faces_begin(); f != tin.finite_faces_end(); ++f) {
      int beyond = 0;
      for (int i = 0; i < 3; ++i) {
        const double d = f->vertex(i)->point()[axis] - c[static_cast<std::size_t>(line)];
        beyond += d > band ? 1 : d < -band ? -1 : 0;
      }
      if (beyond == 3 || beyond == -3) label(f, static_cast<std::int8_t>(beyond == 3));
    }
    std::sort(cut.begin(), cut.end());
    while (!queue.empty()) {
      const FaceHandle f = queue.front();
      queue.pop_front();
      for (int i = 0; i < 3; ++i) {
        if (std::binary_search(cut.begin(), cut.end(),
                               edge_key(f->vertex(Tin::cw(i)), f->vertex(Tin::ccw(i)))))
          continue;
        label(f->neighbor(i), f->info().side);
      }
    }
    for (auto f = tin.finite_faces_begin(); f != tin.finite_faces_end(); ++f) {
      bool high = f->info().side == 1;
      if (f->info().side < 0) {
        double centroid = 0.0;
        for (int i = 0; i < 3; ++i) centroid += f->vertex(i)->point()[axis];
        high = centroid / 3.0 >= c[static_cast<std::size_t>(line)];
      }
      if (high) f->info().core ^= static_cast<std::int8_t>(1 << line);
    }
  }
  // In the core: high of lines 0 and 2, low of 1 and 3: every bit clear.
  for (auto f = tin.finite_faces_begin(); f != tin.finite_faces_end(); ++f)
    f->info().core = static_cast<std::int8_t>(f->info().core == 0);
  return leaks;
}

}  // namespace relief::terrain_detail
