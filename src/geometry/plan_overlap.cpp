#include "relief/geometry/plan_overlap.h"

#include <array>
#include <cmath>
#include <string>

#include <Eigen/Geometry>  // cross()

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/box_intersection_d.h>

#include "relief/core/errors.h"

namespace relief {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point2 = Kernel::Point_2;
using Corners = std::array<Point2, 3>;
using Triangle = std::array<std::uint32_t, 3>;

// Interiors of two triangles (non-degenerate in plan) are disjoint exactly when one of the six
// edge lines has the other triangle wholly on its outer closed side (separating axis; exact).
bool separated_by_an_edge_of(const Corners& a, const Corners& b) {
  const CGAL::Orientation turn = CGAL::orientation(a[0], a[1], a[2]);
  for (int i = 0; i < 3; ++i) {
    const Point2& p = a[static_cast<std::size_t>(i)];
    const Point2& q = a[static_cast<std::size_t>((i + 1) % 3)];
    bool outside = true;
    for (const Point2& r : b) {
      // A shared corner lies on the line: settled here, where the filtered predicate would fall
      // back to exact arithmetic to prove a zero (most pairs are neighbours sharing corners).
      if (r == p || r == q) continue;
      outside = outside && CGAL::orientation(p, q, r) != turn;
    }
    if (outside) return true;
  }
  return false;
}

bool interiors_overlap(const Corners& a, const Corners& b) {
  return !separated_by_an_edge_of(a, b) && !separated_by_an_edge_of(b, a);
}

Vec3 centroid(const TriangleMesh& mesh, const Triangle& t) {
  return (mesh.vertices[t[0]] + mesh.vertices[t[1]] + mesh.vertices[t[2]]) / 3.0;
}

}  // namespace

std::optional<double> plane_height(const TriangleMesh& mesh, const Triangle& t, const Vec2& xy) {
  const Vec3& a = mesh.vertices[t[0]];
  const Vec3 n = (mesh.vertices[t[1]] - a).cross(mesh.vertices[t[2]] - a);
  if (!(std::abs(n.z()) > 1e-12)) return std::nullopt;
  return a.z() - (n.x() * (xy.x() - a.x()) + n.y() * (xy.y() - a.y())) / n.z();
}

PlanOverlaps plan_overlaps(const TriangleMesh& mesh, const std::vector<std::uint8_t>& candidates) {
  if (!candidates.empty() && candidates.size() != mesh.triangles.size()) {
    throw InvalidInput("plan_overlaps: " + std::to_string(candidates.size()) + " flags for " +
                       std::to_string(mesh.triangles.size()) + " triangles");
  }
  for (const Triangle& t : mesh.triangles) {
    for (const std::uint32_t v : t) {
      if (v >= mesh.vertices.size())
        throw InvalidInput("plan_overlaps: a triangle refers to a missing vertex");
    }
  }
  using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 2, std::uint32_t,
                                                        CGAL::Box_intersection_d::ID_FROM_BOX_ADDRESS>;
  std::vector<Corners> corners(mesh.triangles.size());
  std::vector<Box> boxes;
  for (std::uint32_t i = 0; i < mesh.triangles.size(); ++i) {
    if (!candidates.empty() && !candidates[i]) continue;
    const Triangle& t = mesh.triangles[i];
    Corners& c = corners[i];
    for (std::size_t k = 0; k < 3; ++k) c[k] = Point2(mesh.vertices[t[k]].x(), mesh.vertices[t[k]].y());
    if (CGAL::collinear(c[0], c[1], c[2])) continue;
    boxes.emplace_back(c[0].bbox() + c[1].bbox() + c[2].bbox(), i);
  }
  // Boxes are passed by pointer: their ids are their addresses, which a copy would change.
  std::vector<const Box*> pointers;
  pointers.reserve(boxes.size());
  for (const Box& b : boxes) pointers.push_back(&b);

  PlanOverlaps out;
  out.under.assign(mesh.triangles.size(), 0);
  const auto on_overlap = [&](const Box* x, const Box* y) {
    const std::uint32_t i = x->info();
    const std::uint32_t j = y->info();
    if (!interiors_overlap(corners[i], corners[j])) return;
    const Triangle& ti = mesh.triangles[i];
    const Triangle& tj = mesh.triangles[j];
    const Vec3 mid = (centroid(mesh, ti) + centroid(mesh, tj)) / 2.0;
    // Both are non-degenerate in plan (collinear ones have no box), so both planes exist.
    const double zi = *plane_height(mesh, ti, mid.head<2>());
    const double zj = *plane_height(mesh, tj, mid.head<2>());
    const std::uint32_t lower = zi < zj ? i : zj < zi ? j : std::max(i, j);
    ++out.pairs;
    out.lower_upper.emplace_back(lower, lower == i ? j : i);
    if (out.under[lower]) return;
    out.under[lower] = 1;
    if (out.sites.size() < kMaxPlanOverlapSites) out.sites.push_back(centroid(mesh, mesh.triangles[lower]));
  };
  constexpr std::ptrdiff_t kCutoff = 2000;  // as in the soup intersection test
  CGAL::box_self_intersection_d<CGAL::Sequential_tag>(pointers.begin(), pointers.end(), on_overlap, kCutoff);
  return out;
}

}  // namespace relief
