#include "relief/geometry/mesh_quality.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <numeric>
#include <optional>
#include <unordered_map>
#include <utility>

#include <Eigen/Geometry>  // cross()

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wconversion"
#pragma GCC diagnostic ignored "-Wshadow"
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wunused-parameter"
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/box_intersection_d.h>
#include <boost/iterator/function_output_iterator.hpp>
#pragma GCC diagnostic pop

#include "geometry/edge_order.h"
#include "relief/core/errors.h"
#include "relief/geometry/plane.h"

namespace relief {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point3 = Kernel::Point_3;
using Triangle = std::array<std::uint32_t, 3>;

constexpr std::uint32_t kNone = ~std::uint32_t{0};

// Union-find with path halving; unions by index keep it deterministic.
class DisjointSets {
 public:
  explicit DisjointSets(std::size_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), 0u); }
  std::uint32_t find(std::uint32_t x) {
    while (parent_[x] != x) {
      parent_[x] = parent_[parent_[x]];
      x = parent_[x];
    }
    return x;
  }
  void unite(std::uint32_t a, std::uint32_t b) {
    a = find(a);
    b = find(b);
    if (a != b) parent_[std::max(a, b)] = std::min(a, b);
  }

 private:
  std::vector<std::uint32_t> parent_;
};

// One use of an edge by a triangle: the edge from t[k] to t[(k+1)%3] of triangle `tri`.
struct EdgeUse {
  std::uint64_t key;  // (min index << 32) | max index
  std::uint32_t tri;
  std::uint32_t k;
};

std::uint64_t edge_key(std::uint32_t a, std::uint32_t b) {
  return (std::uint64_t{std::min(a, b)} << 32) | std::max(a, b);
}

bool repeats_index(const Triangle& t) {
  return t[0] == t[1] || t[1] == t[2] || t[2] == t[0];
}

void check_indices(const TriangleMesh& mesh, const char* what) {
  const std::size_t n = mesh.vertices.size();
  for (const Triangle& t : mesh.triangles) {
    if (t[0] >= n || t[1] >= n || t[2] >= n) {
      throw InvalidInput(std::string(what) + ": mesh '" + mesh.name + "' has a vertex index out of range");
    }
  }
}

// Every edge use, sorted by edge so that the uses of one edge are adjacent.
std::vector<EdgeUse> sorted_edge_uses(const TriangleMesh& mesh) {
  std::vector<EdgeUse> uses;
  uses.reserve(3 * mesh.triangles.size());
  for (std::uint32_t i = 0; i < mesh.triangles.size(); ++i) {
    const Triangle& t = mesh.triangles[i];
    for (std::uint32_t k = 0; k < 3; ++k) {
      const std::uint32_t a = t[k], b = t[(k + 1) % 3];
      if (a != b) uses.push_back({edge_key(a, b), i, k});
    }
  }
  // By key, then triangle (the uses were made in triangle order and the sort is stable).
  detail::sort_by_vertex_pair(
      uses, mesh.vertices.size(), [](const EdgeUse& u) { return static_cast<std::uint32_t>(u.key >> 32); },
      [](const EdgeUse& u) { return static_cast<std::uint32_t>(u.key); });
  return uses;
}

// Calls f(first, last) for each run of uses of one edge.
template <class F>
void for_each_edge(const std::vector<EdgeUse>& uses, F&& f) {
  for (std::size_t i = 0; i < uses.size();) {
    std::size_t j = i + 1;
    while (j < uses.size() && uses[j].key == uses[i].key) ++j;
    f(i, j);
    i = j;
  }
}

// --- Self-intersections ---------------------------------------------------------------------

std::vector<Point3> cgal_points(const TriangleMesh& mesh) {
  std::vector<Point3> p;
  p.reserve(mesh.vertices.size());
  for (const Vec3& v : mesh.vertices) p.emplace_back(v.x(), v.y(), v.z());
  return p;
}

// Whether two non-degenerate triangles intersect other than in the vertices/edge they share
// (by index). Same criteria as CGAL PMP's test on a halfedge mesh, on a triangle soup:
// sharing an edge, they overlap only if coplanar with the far corners on the same side;
// sharing a vertex, one's opposite edge must meet the other triangle.
bool triangles_intersect(const std::vector<Point3>& p, const Triangle& s, const Triangle& t) {
  int shared = 0;
  std::array<int, 3> in_t{-1, -1, -1};  // for each corner of s: its position in t, or -1
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      if (s[static_cast<std::size_t>(i)] == t[static_cast<std::size_t>(j)]) {
        in_t[static_cast<std::size_t>(i)] = j;
        ++shared;
      }
    }
  }
  const auto tri = [&](const Triangle& u) { return Kernel::Triangle_3(p[u[0]], p[u[1]], p[u[2]]); };
  if (shared == 0) return CGAL::do_intersect(tri(s), tri(t));
  if (shared == 3) return true;  // the same triangle twice
  if (shared == 2) {
    // s = (a, b, r) with a-b shared; the far corner of t is the one not in s.
    std::size_t r = 0;
    while (in_t[r] >= 0) ++r;
    std::size_t q = 0;
    while (t[q] == s[(r + 1) % 3] || t[q] == s[(r + 2) % 3]) ++q;
    const Point3& a = p[s[(r + 1) % 3]];
    const Point3& b = p[s[(r + 2) % 3]];
    const Point3& far_s = p[s[r]];
    const Point3& far_t = p[t[q]];
    return CGAL::coplanar(a, b, far_s, far_t) &&
           CGAL::coplanar_orientation(a, b, far_s, far_t) == CGAL::POSITIVE;
  }
  // One shared vertex: s's edge opposite it against t, and t's opposite edge against s.
  std::size_t i = 0;
  while (in_t[i] < 0) ++i;
  const auto j = static_cast<std::size_t>(in_t[i]);
  const Point3& v = p[s[i]];
  const Point3& a = p[s[(i + 1) % 3]];
  const Point3& b = p[s[(i + 2) % 3]];
  const Point3& c = p[t[(j + 1) % 3]];
  const Point3& d = p[t[(j + 2) % 3]];
  // Quick exits (most neighbour pairs of a mesh): one triangle strictly on one side of the
  // other's plane but for v; or, coplanar, a line through v and a corner strictly separating them.
  const auto oc = CGAL::orientation(v, a, b, c), od = CGAL::orientation(v, a, b, d);
  if (oc == od && oc != CGAL::COPLANAR) return false;
  const auto oa = CGAL::orientation(v, c, d, a), ob = CGAL::orientation(v, c, d, b);
  if (oa == ob && oa != CGAL::COPLANAR) return false;
  if (oa == CGAL::COPLANAR && ob == CGAL::COPLANAR && oc == CGAL::COPLANAR && od == CGAL::COPLANAR) {
    const auto separates = [](const Point3& o, const Point3& e, const Point3& f, const Point3& g,
                              const Point3& h) {
      return CGAL::coplanar_orientation(o, e, f, g) == CGAL::NEGATIVE &&
             CGAL::coplanar_orientation(o, e, f, h) == CGAL::NEGATIVE;
    };
    if (separates(v, a, b, c, d) || separates(v, b, a, c, d) || separates(v, c, d, a, b) ||
        separates(v, d, c, a, b)) {
      return false;
    }
  }
  return CGAL::do_intersect(tri(t), Kernel::Segment_3(a, b)) ||
         CGAL::do_intersect(tri(s), Kernel::Segment_3(c, d));
}

// Where a pair of triangles intersects: the midpoint of their centroids.
Vec3 pair_site(const TriangleMesh& mesh, std::size_t s, std::size_t t) {
  Vec3 c = Vec3::Zero();
  for (const std::size_t f : {s, t}) {
    for (const std::uint32_t v : mesh.triangles[f]) c += mesh.vertices[v];
  }
  return c / 6.0;
}

struct PairCount {
  std::size_t pairs = 0;
  std::vector<Vec3> sites;                                 // the first kMaxSites pairs'
  std::vector<std::array<std::size_t, 2>> triangle_pairs;  // the same pairs' triangles

  void add(const TriangleMesh& mesh, std::size_t s, std::size_t t) {
    ++pairs;
    if (sites.size() < kMaxSelfIntersectionSites) {
      sites.push_back(pair_site(mesh, s, t));
      triangle_pairs.push_back({std::min(s, t), std::max(s, t)});
    }
  }
};

// Triangle soup: boxes around the non-degenerate triangles, box_intersection_d for candidate
// pairs, then the exact test above; all pairs, or with `across` (a flag per triangle) only the
// pairs of a flagged and an unflagged triangle. The boxes are sorted through pointers: their ids
// are their addresses, which must not move.
PairCount soup_intersections(const TriangleMesh& mesh, const std::vector<std::uint8_t>* across = nullptr) {
  using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 3, std::uint32_t,
                                                        CGAL::Box_intersection_d::ID_FROM_BOX_ADDRESS>;
  const std::vector<Point3> p = cgal_points(mesh);
  std::vector<Box> boxes;
  boxes.reserve(mesh.triangles.size());
  for (std::uint32_t i = 0; i < mesh.triangles.size(); ++i) {
    const Triangle& t = mesh.triangles[i];
    if (repeats_index(t) || CGAL::collinear(p[t[0]], p[t[1]], p[t[2]])) continue;
    boxes.emplace_back(p[t[0]].bbox() + p[t[1]].bbox() + p[t[2]].bbox(), i);
  }
  std::array<std::vector<const Box*>, 2> sets;  // unflagged, flagged
  for (const Box& b : boxes) sets[across != nullptr && (*across)[b.info()] ? 1 : 0].push_back(&b);
  PairCount pairs;
  const auto on_overlap = [&](const Box* x, const Box* y) {
    if (triangles_intersect(p, mesh.triangles[x->info()], mesh.triangles[y->info()])) {
      pairs.add(mesh, x->info(), y->info());
    }
  };
  // A cutoff of 2000 boxes (scan below it, as PMP does) is several times faster than the default 10.
  constexpr std::ptrdiff_t kCutoff = 2000;
  if (across == nullptr) {
    CGAL::box_self_intersection_d<CGAL::Sequential_tag>(sets[0].begin(), sets[0].end(), on_overlap, kCutoff);
  } else {
    CGAL::box_intersection_d<CGAL::Sequential_tag>(sets[0].begin(), sets[0].end(), sets[1].begin(),
                                                   sets[1].end(), on_overlap, kCutoff);
  }
  return pairs;
}

// Manifold, consistently oriented mesh: CGAL::Surface_mesh and PMP::self_intersections.
// Returns nothing if CGAL refuses a face (then the soup test is used).
std::optional<PairCount> pmp_self_intersections(const TriangleMesh& mesh) {
  using SurfaceMesh = CGAL::Surface_mesh<Point3>;
  SurfaceMesh sm;
  sm.reserve(static_cast<SurfaceMesh::size_type>(mesh.vertices.size()),
             static_cast<SurfaceMesh::size_type>(3 * mesh.triangles.size()),
             static_cast<SurfaceMesh::size_type>(mesh.triangles.size()));
  for (const Vec3& v : mesh.vertices) sm.add_vertex(Point3(v.x(), v.y(), v.z()));
  for (const Triangle& t : mesh.triangles) {
    const auto f = sm.add_face(SurfaceMesh::Vertex_index(t[0]), SurfaceMesh::Vertex_index(t[1]),
                               SurfaceMesh::Vertex_index(t[2]));
    if (f == SurfaceMesh::null_face()) return std::nullopt;
  }
  PairCount pairs;
  // PMP reports a degenerate face f as the pair (f, f): those are counted as degenerate instead.
  // Faces were added in triangle order, so a face index is the triangle's.
  const auto count = [&](const std::pair<SurfaceMesh::Face_index, SurfaceMesh::Face_index>& fg) {
    if (fg.first != fg.second) pairs.add(mesh, std::size_t(fg.first), std::size_t(fg.second));
  };
  CGAL::Polygon_mesh_processing::self_intersections(sm, boost::make_function_output_iterator(count));
  return pairs;
}

}  // namespace

std::vector<std::pair<std::uint32_t, std::uint32_t>> boundary_edges(const TriangleMesh& mesh) {
  const std::vector<EdgeUse> uses = sorted_edge_uses(mesh);
  std::vector<std::pair<std::uint32_t, std::uint32_t>> out;
  for_each_edge(uses, [&](std::size_t i, std::size_t j) {
    if (j != i + 1) return;
    const Triangle& t = mesh.triangles[uses[i].tri];
    out.emplace_back(t[uses[i].k], t[(uses[i].k + 1) % 3]);
  });
  return out;
}

MeshQuality analyse_mesh(const TriangleMesh& mesh, const MeshQualityOptions& options) {
  check_indices(mesh, "analyse_mesh");
  if (mesh.triangles.size() >= std::numeric_limits<std::uint32_t>::max() / 3) {
    throw InvalidInput("analyse_mesh: mesh '" + mesh.name + "' has too many triangles");
  }
  MeshQuality q;
  q.name = mesh.name;
  q.vertices = mesh.vertices.size();
  q.triangles = mesh.triangles.size();
  const auto n_tri = static_cast<std::uint32_t>(mesh.triangles.size());

  // Vertex use, bounds and heights.
  std::vector<std::uint8_t> used(mesh.vertices.size(), 0);
  for (const Triangle& t : mesh.triangles) used[t[0]] = used[t[1]] = used[t[2]] = 1;
  double min_z = std::numeric_limits<double>::infinity(), max_z = -min_z;
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
    if (!used[v]) {
      ++q.unused_vertices;
      continue;
    }
    q.bounds.extend(Vec2(mesh.vertices[v].head<2>()));
    min_z = std::min(min_z, mesh.vertices[v].z());
    max_z = std::max(max_z, mesh.vertices[v].z());
  }
  if (min_z <= max_z) {
    q.min_z = min_z;
    q.max_z = max_z;
  }

  // Edges: boundary, manifold (orientation), non-manifold. Triangles sharing any edge join one
  // component; corners (triangle, vertex) joined across two-triangle edges form the fans.
  // A corner is named by the first position of its vertex in the triangle.
  const auto corner = [&](std::uint32_t tri, std::uint32_t k) {
    const Triangle& t = mesh.triangles[tri];
    std::uint32_t first = 0;
    while (t[first] != t[k]) ++first;
    return 3 * tri + first;
  };
  const std::vector<EdgeUse> uses = sorted_edge_uses(mesh);
  DisjointSets components(n_tri), fans(3 * std::size_t{n_tri});
  for_each_edge(uses, [&](std::size_t i, std::size_t j) {
    const std::size_t count = j - i;
    if (count == 1) ++q.boundary_edges;
    if (count >= 3) ++q.non_manifold_edges;
    for (std::size_t k = i + 1; k < j; ++k) components.unite(uses[i].tri, uses[k].tri);
    if (count != 2) return;
    const EdgeUse& x = uses[i];
    const EdgeUse& y = uses[i + 1];
    const Triangle& tx = mesh.triangles[x.tri];
    const Triangle& ty = mesh.triangles[y.tri];
    const bool same_way = tx[x.k] == ty[y.k];
    if (same_way) ++q.inconsistent_orientation_edges;
    const std::uint32_t x_end = (x.k + 1) % 3, y_end = (y.k + 1) % 3;
    // Join the corners at each end of the edge.
    fans.unite(corner(x.tri, x.k), corner(y.tri, same_way ? y.k : y_end));
    fans.unite(corner(x.tri, x_end), corner(y.tri, same_way ? y_end : y.k));
  });
  std::vector<std::uint32_t> component_of(n_tri);
  for (std::uint32_t t = 0; t < n_tri; ++t) {
    component_of[t] = components.find(t);
    if (component_of[t] == t) ++q.components;
  }
  std::vector<std::uint8_t> fan_count(mesh.vertices.size(), 0);
  for (std::uint32_t t = 0; t < n_tri; ++t) {
    for (std::uint32_t k = 0; k < 3; ++k) {
      const std::uint32_t c = corner(t, k);
      if (c != 3 * t + k || fans.find(c) != c) continue;
      std::uint8_t& n = fan_count[mesh.triangles[t][k]];
      if (n < 2) ++n;
    }
  }
  q.non_manifold_vertices = static_cast<std::size_t>(std::count(fan_count.begin(), fan_count.end(), 2));

  // Boundary loops and holes: per component, every loop but the one of largest vector area.
  const auto loops = boundary_loops(mesh);
  q.boundary_loops = loops.size();
  std::unordered_map<std::uint32_t, std::pair<double, double>> outer;  // component -> (area, length)
  outer.reserve(loops.size());
  struct LoopFigures {
    std::uint32_t component;
    std::pair<double, double> score;  // (area, length)
    Vec3 centre;
  };
  std::vector<LoopFigures> figures;
  figures.reserve(loops.size());
  for (const auto& loop : loops) {
    const Vec3& o = mesh.vertices[loop[0]];
    Vec3 twice_area = Vec3::Zero();
    double length = 0.0;
    for (std::size_t i = 0; i < loop.size(); ++i) {
      const Vec3& a = mesh.vertices[loop[i]];
      const Vec3& b = mesh.vertices[loop[(i + 1) % loop.size()]];
      twice_area += (a - o).cross(b - o);
      length += (b - a).norm();
    }
    const std::uint64_t key = edge_key(loop[0], loop[1]);
    const auto use = std::lower_bound(uses.begin(), uses.end(), key,
                                      [](const EdgeUse& e, std::uint64_t k) { return e.key < k; });
    const std::uint32_t component = component_of[use->tri];
    const std::pair<double, double> score{0.5 * twice_area.norm(), length};
    const auto [it, inserted] = outer.try_emplace(component, score);
    if (!inserted) {
      ++q.holes;
      it->second = std::max(it->second, score);
    }
    Vec3 centre = Vec3::Zero();
    for (const std::uint32_t v : loop) centre += mesh.vertices[v];
    figures.push_back({component, score, centre / static_cast<double>(loop.size())});
  }
  for (const LoopFigures& f : figures) {
    if (q.hole_sites.size() == kMaxSelfIntersectionSites) break;
    if (f.score == outer.at(f.component)) continue;  // the component's outer loop
    q.hole_sites.push_back(f.centre);
    q.hole_lengths_m.push_back(f.score.second);
  }

  // Per-triangle shape: area, orientation, angles, aspect ratio.
  q.min_angle_deg = 180.0;
  bool any_shape = false;
  const double rad_to_deg = 180.0 / std::numbers::pi;
  for (const Triangle& t : mesh.triangles) {
    const Vec3& a = mesh.vertices[t[0]];
    const Vec3& b = mesh.vertices[t[1]];
    const Vec3& c = mesh.vertices[t[2]];
    const Vec3 cross = (b - a).cross(c - a);
    const double twice_area = cross.norm();
    q.area_m2 += 0.5 * twice_area;
    if (repeats_index(t) || !(0.5 * twice_area > options.degenerate_area_m2)) {
      ++q.degenerate_triangles;
      continue;
    }
    if (cross.z() < 0.0) ++q.upside_down_triangles;
    // Angle at each corner: atan2(|u x v|, u . v), with |u x v| = twice the area.
    const double angle_a = std::atan2(twice_area, (b - a).dot(c - a));
    const double angle_b = std::atan2(twice_area, (a - b).dot(c - b));
    const double angle_c = std::atan2(twice_area, (a - c).dot(b - c));
    const double min_angle = std::min({angle_a, angle_b, angle_c}) * rad_to_deg;
    // Longest edge / shortest altitude = longest^2 / (2 area).
    const double longest2 = std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
    const double aspect = longest2 / twice_area;
    any_shape = true;
    q.min_angle_deg = std::min(q.min_angle_deg, min_angle);
    q.max_aspect_ratio = std::max(q.max_aspect_ratio, aspect);
    if (min_angle < options.sliver_min_angle_deg || aspect > options.sliver_max_aspect_ratio) {
      ++q.sliver_triangles;
    }
  }
  if (!any_shape) q.min_angle_deg = 0.0;

  // Self-intersections: PMP on a halfedge mesh where one can be built, else the soup test.
  if (options.self_intersections) {
    q.self_intersections_checked = true;
    const bool manifold = q.non_manifold_edges == 0 && q.non_manifold_vertices == 0 &&
                          q.inconsistent_orientation_edges == 0 &&
                          std::none_of(mesh.triangles.begin(), mesh.triangles.end(), repeats_index);
    std::optional<PairCount> pairs;
    if (!options.intersections_across.empty()) {
      if (options.intersections_across.size() != mesh.triangles.size())
        throw InvalidInput("analyse_mesh: intersections_across needs one flag per triangle");
      pairs = soup_intersections(mesh, &options.intersections_across);
    }
    if (!pairs && manifold) pairs = pmp_self_intersections(mesh);
    if (!pairs) pairs = soup_intersections(mesh);
    q.self_intersecting_pairs = pairs->pairs;
    q.self_intersection_sites = std::move(pairs->sites);
    q.self_intersection_triangles = std::move(pairs->triangle_pairs);
  }
  return q;
}

SeamGap seam_gap(const TriangleMesh& a, const TriangleMesh& b, double reach_m) {
  if (!(reach_m >= 0.0) || !std::isfinite(reach_m)) {
    throw InvalidInput("seam_gap: reach must be a finite distance >= 0, not " + std::to_string(reach_m));
  }
  check_indices(a, "seam_gap");
  check_indices(b, "seam_gap");
  SeamGap gap;
  const auto edges_b = boundary_edges(b);
  if (edges_b.empty()) return gap;

  // Uniform grid in the plane over b's boundary edges; the cell is at least the reach and the
  // mean edge length, and long edges are cut into cell-sized pieces before they are binned.
  double mean_length = 0.0;
  for (const auto& [u, v] : edges_b) mean_length += (b.vertices[v] - b.vertices[u]).head<2>().norm();
  mean_length /= static_cast<double>(edges_b.size());
  const double cell = std::max({reach_m, mean_length, 1e-6});
  const auto cell_of = [cell](double x) { return static_cast<std::int64_t>(std::floor(x / cell)); };
  const auto cell_key = [](std::int64_t ix, std::int64_t iy) {
    return (static_cast<std::uint64_t>(ix) << 32) ^ static_cast<std::uint64_t>(iy & 0xffffffff);
  };
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> grid;
  for (std::uint32_t e = 0; e < edges_b.size(); ++e) {
    const Vec2 p = b.vertices[edges_b[e].first].head<2>();
    const Vec2 r = b.vertices[edges_b[e].second].head<2>();
    const auto pieces = static_cast<std::size_t>(std::ceil((r - p).norm() / cell)) + 1;
    for (std::size_t i = 0; i < pieces; ++i) {
      const Vec2 s = p + (r - p) * (static_cast<double>(i) / static_cast<double>(pieces));
      const Vec2 t = p + (r - p) * (static_cast<double>(i + 1) / static_cast<double>(pieces));
      for (std::int64_t ix = cell_of(std::min(s.x(), t.x())); ix <= cell_of(std::max(s.x(), t.x())); ++ix) {
        for (std::int64_t iy = cell_of(std::min(s.y(), t.y())); iy <= cell_of(std::max(s.y(), t.y())); ++iy) {
          auto& bin = grid[cell_key(ix, iy)];
          if (bin.empty() || bin.back() != e) bin.push_back(e);  // pieces of one edge share cells
        }
      }
    }
  }

  // Nearest of b's edges in the cells within `radius` of p (xy): (3D distance, any within reach).
  std::vector<std::uint32_t> seen(edges_b.size(), kNone);
  std::uint32_t stamp = 0;
  const auto nearest = [&](const Vec3& p, double radius) {
    ++stamp;
    double best = std::numeric_limits<double>::infinity();
    bool in_reach = false;
    for (std::int64_t ix = cell_of(p.x() - radius); ix <= cell_of(p.x() + radius); ++ix) {
      for (std::int64_t iy = cell_of(p.y() - radius); iy <= cell_of(p.y() + radius); ++iy) {
        const auto bin = grid.find(cell_key(ix, iy));
        if (bin == grid.end()) continue;
        for (const std::uint32_t e : bin->second) {
          if (seen[e] == stamp) continue;
          seen[e] = stamp;
          const Vec3& u = b.vertices[edges_b[e].first];
          const Vec3& v = b.vertices[edges_b[e].second];
          const double d = point_segment_distance(p, u, v);
          in_reach = in_reach || d <= reach_m;
          best = std::min(best, d);
        }
      }
    }
    return std::pair{best, in_reach};
  };

  std::vector<std::uint8_t> done(a.vertices.size(), 0);
  for (const auto& [u, v] : boundary_edges(a)) {
    for (const std::uint32_t w : {u, v}) {
      if (done[w]) continue;
      done[w] = 1;
      const Vec3& p = a.vertices[w];
      const auto [distance, in_reach] = nearest(p, reach_m);
      if (!in_reach) continue;
      ++gap.vertices_checked;
      gap.max_gap_m = std::max(gap.max_gap_m, distance);
    }
  }
  return gap;
}

}  // namespace relief
