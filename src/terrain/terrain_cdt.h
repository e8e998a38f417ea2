#pragma once
// CGAL types of the terrain TIN (private to src/terrain): a constrained Delaunay triangulation
// of 3D points projected on xy, exact predicates, constraint crossings split by CGAL
// (Constrained_triangulation_plus_2 keeps which input constraint covers which edge), and the
// grid samples the TIN approximates.

#include <cmath>
#include <cstdint>
#include <vector>

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wconversion"
#pragma GCC diagnostic ignored "-Wshadow"
#pragma GCC diagnostic ignored "-Wpedantic"
#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Constrained_triangulation_plus_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Projection_traits_xy_3.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#pragma GCC diagnostic pop

#include "relief/geometry/types.h"

namespace relief::terrain_detail {

inline constexpr std::uint32_t kNoIndex = ~std::uint32_t{0};

struct VertexData {
  std::uint32_t grid = kNoIndex;  ///< grid sample index, for a vertex taken from the DEM grid
  bool outline = false;           ///< an outline point, inserted as given
};

struct FaceData {
  std::vector<std::uint32_t> points;  ///< grid samples inside the face, not yet vertices (greedy phase)
  std::uint32_t best = kNoIndex;      ///< the sample of largest error above the tolerance
  double best_error = 0.0;
  bool paved = false;     ///< inside an odd number of outline loops
  bool visited = false;   ///< flood fill
  std::int8_t side = -1;  ///< region tiles: 1 on a core line's high side, 0 low, -1 not told yet
  std::int8_t core = 0;   ///< region tiles: 1 in the tile's core
};

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Traits = CGAL::Projection_traits_xy_3<Kernel>;
using VertexBase = CGAL::Triangulation_vertex_base_with_info_2<VertexData, Traits>;
using FaceBase =
    CGAL::Constrained_triangulation_face_base_2<Traits,
                                                CGAL::Triangulation_face_base_with_info_2<FaceData, Traits>>;
using Tds = CGAL::Triangulation_data_structure_2<VertexBase, FaceBase>;
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<Traits, Tds, CGAL::Exact_intersections_tag>;
using Tin = CGAL::Constrained_triangulation_plus_2<Cdt>;
using Point = Traits::Point_2;  // a Kernel::Point_3
using FaceHandle = Tin::Face_handle;
using VertexHandle = Tin::Vertex_handle;

/// Sample flags (bits).
enum SampleFlag : std::uint8_t {
  kValid = 1,      ///< the DEM has a height here
  kPaved = 2,      ///< inside the paved area
  kNear = 4,       ///< closer than the clearance to the outline: never a vertex
  kBoundary = 8,   ///< on the convex hull of the valid samples (simplified separately)
  kInserted = 16,  ///< a TIN vertex
  kBand = 32,      ///< within max_slope_width_m of the outline
};

/// The regular grid of DEM samples over the terrain area, row by row (k = j * nx + i).
struct GridSamples {
  Vec2 origin = Vec2::Zero();
  double step_m = 1.0;
  long nx = 0;
  long ny = 0;
  std::vector<double> z_dem;     ///< DEM height (meaningful only where kValid is set)
  std::vector<double> z_target;  ///< z_dem moved onto the cut/fill batter near the outline
  std::vector<std::uint8_t> flags;

  [[nodiscard]] std::size_t size() const { return flags.size(); }
  [[nodiscard]] Vec2 xy(std::size_t k) const {
    const auto n = static_cast<long>(k);
    const long row = n / nx;
    return origin + step_m * Vec2(static_cast<double>(n % nx), static_cast<double>(row));
  }
  [[nodiscard]] Point point(std::size_t k) const {
    const Vec2 p = xy(k);
    return Point(p.x(), p.y(), z_target[k]);
  }
  [[nodiscard]] bool has(std::size_t k, std::uint8_t flag) const { return (flags[k] & flag) != 0; }
};

/// Height of the plane through finite face f at (x, y).
[[nodiscard]] inline double interpolate(const FaceHandle& f, double x, double y) {
  const Point& a = f->vertex(0)->point();
  const Point& b = f->vertex(1)->point();
  const Point& c = f->vertex(2)->point();
  const double bx = b.x() - a.x(), by = b.y() - a.y(), cx = c.x() - a.x(), cy = c.y() - a.y();
  const double det = bx * cy - cx * by;
  const double px = x - a.x(), py = y - a.y();
  const double u = (px * cy - cx * py) / det;
  const double v = (bx * py - px * by) / det;
  return a.z() + u * (b.z() - a.z()) + v * (c.z() - a.z());
}

}  // namespace relief::terrain_detail
