#include "terrain/under_decks.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <utility>

#include "relief/geometry/plan_overlap.h"

namespace relief::terrain_detail {
namespace {

using Point2 = Kernel::Point_2;
using Segment2 = Kernel::Segment_2;

constexpr double kCellM = 10.0;  // cell of the bucket grids

// Items bucketed by their boxes in a uniform grid over `bounds`; a query visits the items of the
// cells its box meets (an item may be visited more than once).
class BoxGrid {
 public:
  explicit BoxGrid(const Aabb2& bounds)
      : origin_(bounds.min),
        nx_(std::max(1L, static_cast<long>(std::ceil((bounds.max.x() - bounds.min.x()) / kCellM)) + 1)),
        ny_(std::max(1L, static_cast<long>(std::ceil((bounds.max.y() - bounds.min.y()) / kCellM)) + 1)),
        cells_(static_cast<std::size_t>(nx_ * ny_)) {}

  void add(const Aabb2& box, std::uint32_t item) {
    for_cells(box, [&](std::size_t cell) { cells_[cell].push_back(item); });
  }

  template <class F>
  void visit(const Aabb2& box, F&& f) const {
    for_cells(box, [&](std::size_t cell) {
      for (const std::uint32_t item : cells_[cell]) f(item);
    });
  }

 private:
  // Calls f with the index of every cell the box meets.
  template <class F>
  void for_cells(const Aabb2& box, F&& f) const {
    const auto cell_of = [&](double v, double o, long n) {
      return std::clamp(static_cast<long>(std::floor((v - o) / kCellM)), 0L, n - 1);
    };
    const long x0 = cell_of(box.min.x(), origin_.x(), nx_), x1 = cell_of(box.max.x(), origin_.x(), nx_);
    const long y0 = cell_of(box.min.y(), origin_.y(), ny_), y1 = cell_of(box.max.y(), origin_.y(), ny_);
    for (long y = y0; y <= y1; ++y)
      for (long x = x0; x <= x1; ++x) f(static_cast<std::size_t>(y * nx_ + x));
  }

  Vec2 origin_;
  long nx_, ny_;
  std::vector<std::vector<std::uint32_t>> cells_;
};

Aabb2 box_of(std::initializer_list<Vec2> points) {
  Aabb2 box;
  for (const Vec2& p : points) box.extend(p);
  return box;
}

}  // namespace

UnderDecks keep_under_decks(Tin& tin, const TriangleMesh& decks, const std::vector<Polyline3>& outline,
                            double clearance_m) {
  UnderDecks out;
  if (decks.triangles.empty()) return out;
  const auto loops = boundary_loops(decks);  // first: it rejects an index out of range
  const auto xy = [&](std::uint32_t v) { return Vec2(decks.vertices[v].head<2>()); };
  Aabb2 bounds;
  for (const Vec3& p : decks.vertices) bounds.extend(Vec2(p.head<2>()));
  BoxGrid deck_grid(bounds), outline_grid(bounds);
  for (std::uint32_t i = 0; i < decks.triangles.size(); ++i) {
    const auto& t = decks.triangles[i];
    deck_grid.add(box_of({xy(t[0]), xy(t[1]), xy(t[2])}), i);
  }
  std::vector<Segment2> segments;
  for (const Polyline3& loop : outline) {
    for (std::size_t k = 0; k < loop.size(); ++k) {
      const Vec3& a = loop[k];
      const Vec3& b = loop[(k + 1) % loop.size()];
      outline_grid.add(box_of({a.head<2>(), b.head<2>()}), static_cast<std::uint32_t>(segments.size()));
      segments.emplace_back(Point2(a.x(), a.y()), Point2(b.x(), b.y()));
    }
  }
  // Lowest deck over a point in plan (closed triangles; exact orientation tests).
  const auto deck_z = [&](double x, double y) {
    std::optional<double> z;
    const Point2 q(x, y);
    deck_grid.visit(box_of({Vec2(x, y)}), [&](std::uint32_t i) {
      const auto& t = decks.triangles[i];
      const Point2 a(xy(t[0]).x(), xy(t[0]).y()), b(xy(t[1]).x(), xy(t[1]).y()),
          c(xy(t[2]).x(), xy(t[2]).y());
      const CGAL::Orientation turn = CGAL::orientation(a, b, c);
      if (turn == CGAL::COLLINEAR) return;
      if (CGAL::orientation(a, b, q) == -turn || CGAL::orientation(b, c, q) == -turn ||
          CGAL::orientation(c, a, q) == -turn)
        return;
      const double h = *plane_height(decks, t, Vec2(x, y));  // not vertical: not collinear in plan
      z = z ? std::min(*z, h) : h;
    });
    return z;
  };
  // Whether pq meets the road outline anywhere but at an end it shares with an outline edge
  // (a deck corner on the road edge, at an abutment: the constraint may start there).
  const auto crosses_outline = [&](const Point2& p, const Point2& q) {
    const Segment2 s(p, q);
    bool crosses = false;
    outline_grid.visit(box_of({Vec2(p.x(), p.y()), Vec2(q.x(), q.y())}), [&](std::uint32_t i) {
      if (crosses || !CGAL::do_intersect(s, segments[i])) return;
      const Point2& a = segments[i].source();
      const Point2& b = segments[i].target();
      const bool shares_p = p == a || p == b, shares_q = q == a || q == b;
      const Point2& other = p == a || q == a ? b : a;
      crosses = shares_p == shares_q || CGAL::collinear(p, q, other);
    });
    return crosses;
  };

  FaceHandle hint;
  const auto in_paved = [&](double x, double y) {
    Tin::Locate_type type{};
    int li = 0;
    const FaceHandle f = tin.locate(Point(x, y, 0.0), type, li, hint);
    return type == Tin::FACE ? f->info().paved : type != Tin::EDGE || f->info().paved;
  };

  // 1. The deck outline as constraints, off the paved area and crossing no road edge.
  std::vector<std::pair<Vec3, Vec3>> edges;  // the decks' outline, loop by loop
  for (const auto& loop : loops) {
    for (std::size_t k = 0; k < loop.size(); ++k)
      edges.emplace_back(decks.vertices[loop[k]], decks.vertices[loop[(k + 1) % loop.size()]]);
  }
  for (const auto& [a, b] : edges) {
    const Vec2 mid = 0.5 * (a.head<2>() + b.head<2>());
    if (crosses_outline(Point2(a.x(), a.y()), Point2(b.x(), b.y())) || in_paved(mid.x(), mid.y())) {
      ++out.edges_skipped;
      continue;
    }
    std::array<VertexHandle, 2> ends;
    bool ok = true;
    for (std::size_t e = 0; e < 2 && ok; ++e) {
      const Vec3& p = e == 0 ? a : b;
      Tin::Locate_type type{};
      int li = 0;
      const FaceHandle f = tin.locate(Point(p.x(), p.y(), 0.0), type, li, hint);
      if (type == Tin::VERTEX) {
        ends[e] = f->vertex(li);  // a road-outline vertex stays where it is
      } else if (type == Tin::FACE || type == Tin::EDGE) {
        ok = !f->info().paved && !tin.is_infinite(f);
        if (ok) {
          const double terrain_z = interpolate(f, p.x(), p.y());
          if (terrain_z > p.z() - clearance_m) ++out.vertices_lowered;
          ends[e] = tin.insert(Point(p.x(), p.y(), std::min(terrain_z, p.z() - clearance_m)), f);
        }
      } else {
        ok = false;  // outside the terrain
      }
      if (ok) hint = ends[e]->face();
    }
    if (!ok || ends[0] == ends[1]) {
      ++out.edges_skipped;
      continue;
    }
    tin.insert_constraint(ends[0], ends[1]);
    hint = ends[1]->face();  // the constraint may have replaced the faces the old hint named
    ++out.edges_constrained;
  }

  // 2. Every terrain vertex under a deck down to the clearance (road-outline vertices stay).
  for (auto v = tin.finite_vertices_begin(); v != tin.finite_vertices_end(); ++v) {
    if (v->info().outline) continue;
    const Point& p = v->point();
    const std::optional<double> z = deck_z(p.x(), p.y());
    if (!z || p.z() <= *z - clearance_m) continue;
    v->set_point(Point(p.x(), p.y(), *z - clearance_m));
    ++out.vertices_lowered;
  }
  return out;
}

}  // namespace relief::terrain_detail
