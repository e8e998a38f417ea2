#include "relief/terrain/dem_sampler.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>
#include <utility>

#include "relief/core/diagnostic_codes.h"
#include "relief/core/errors.h"
#include "relief/geometry/crs_transform.h"
#include "terrain/dem_ground_filter.h"
#include "terrain/dem_sanity.h"
#include "terrain/gdal_dataset.h"

namespace relief {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Maps raster CRS coordinates to fractional cell-centre indices: u = column, v = row, with the
// centre of cell (c, r) at (u, v) = (c, r), i.e. at x = gt0 + (c + 0.5) * gt1,
// y = gt3 + (r + 0.5) * gt5. Works for south-up rasters (gt5 > 0) as for north-up ones.
struct PixelGrid {
  double x0 = 0.0;   // gt[0]
  double dx = 1.0;   // gt[1]
  double y0 = 0.0;   // gt[3]
  double dy = -1.0;  // gt[5]
  int width = 0;
  int height = 0;

  [[nodiscard]] Vec2 index_of(const Vec2& xy) const {
    return {(xy.x() - x0) / dx - 0.5, (xy.y() - y0) / dy - 0.5};
  }
  /// Inside the raster's extent (cell edges, not centres).
  [[nodiscard]] bool inside(const Vec2& uv) const {
    return uv.x() >= -0.5 && uv.x() <= width - 0.5 && uv.y() >= -0.5 && uv.y() <= height - 0.5;
  }
};

// Heights in metres of a window of band 1; NaN marks nodata (and cells outside the window).
struct HeightWindow {
  gdal::PixelWindow window;
  std::vector<double> z;  // row-major, window.cols x window.rows

  [[nodiscard]] double at(int col, int row) const {
    const int c = col - window.col0;
    const int r = row - window.row0;
    if (c < 0 || r < 0 || c >= window.cols || r >= window.rows) return kNaN;
    return z[static_cast<std::size_t>(r) * window.cols + c];
  }
};

// The two cells bracketing index u along an axis of n cells, and the fraction t from the first
// to the second. u is clamped to the border cell centres (within half a pixel of the border).
struct AxisCells {
  int i0 = 0;
  int i1 = 0;
  double t = 0.0;
};

AxisCells axis_cells(double u, int n) {
  const double c = std::clamp(u, 0.0, static_cast<double>(n - 1));
  const int i0 = std::min(static_cast<int>(std::floor(c)), std::max(n - 2, 0));
  return {i0, std::min(i0 + 1, n - 1), c - i0};
}

// Frame CRS -> raster CRS through a lattice of nodes transformed exactly by PROJ and
// interpolated bilinearly in between (the idea of GDAL's approximate transformer): PROJ costs
// ~1 us a point for a datum shift, the lattice ~10 ns. The nodes lie at multiples of a step h
// (a power of two metres) of the frame CRS, and h is chosen from the raster's whole extent, not
// from the area read: a point gets the same four nodes, hence the same bits, in every build that
// reads it (region tiles agree with each other and with a whole build).
class GridTransform {
 public:
  // The coarsest step (1024 m .. 16 m) whose interpolation error, checked against PROJ at the
  // centres of 24 x 24 lattice cells spread over `extent` (the raster's extent in the frame
  // CRS), is <= tolerance_px pixels of `pixel_size` (raster CRS units) on both axes; nullopt
  // when none is, or PROJ fails there.
  static std::optional<double> step_for(const CrsTransform& exact, const Aabb2& extent,
                                        const Vec2& pixel_size, double tolerance_px) {
    const Vec2 size = extent.max - extent.min;
    if (!(size.x() > 0.0) || !(size.y() > 0.0) || !size.allFinite()) return std::nullopt;
    constexpr int kProbes = 24;
    for (double h = 1024.0; h >= 16.0; h /= 2.0) {
      // Corners and centre of each probe cell, in one PROJ batch.
      std::vector<Vec2> points;
      points.reserve(kProbes * kProbes * 5);
      for (int j = 0; j < kProbes; ++j) {
        for (int i = 0; i < kProbes; ++i) {
          const Vec2 at = extent.min + Vec2((i + 0.5) * size.x() / kProbes, (j + 0.5) * size.y() / kProbes);
          const Vec2 lo(std::floor(at.x() / h) * h, std::floor(at.y() / h) * h);
          for (const Vec2& d : {Vec2(0, 0), Vec2(h, 0), Vec2(0, h), Vec2(h, h), Vec2(0.5 * h, 0.5 * h)})
            points.push_back(lo + d);
        }
      }
      exact.apply(std::span<Vec2>(points));
      double worst = 0.0;
      for (std::size_t k = 0; k < points.size(); k += 5) {
        const Vec2 blend = 0.25 * (points[k] + points[k + 1] + points[k + 2] + points[k + 3]);
        const double e = (blend - points[k + 4]).cwiseAbs().cwiseQuotient(pixel_size).maxCoeff();
        worst = std::isfinite(e) ? std::max(worst, e) : std::numeric_limits<double>::infinity();
      }
      if (worst <= tolerance_px) return h;
    }
    return std::nullopt;
  }

  // The lattice of step h over `box` (frame CRS); nullopt when PROJ fails at a node or the box
  // would take more than kMaxNodes nodes.
  static std::optional<GridTransform> build(const CrsTransform& exact, const Aabb2& box, double h) {
    constexpr double kMaxNodes = 4e6;
    if (!(box.max - box.min).allFinite()) return std::nullopt;
    GridTransform grid;
    grid.h_ = h;
    grid.i0_ = static_cast<long long>(std::floor(box.min.x() / h));
    grid.j0_ = static_cast<long long>(std::floor(box.min.y() / h));
    grid.ni_ = static_cast<long long>(std::floor(box.max.x() / h)) - grid.i0_ + 1;
    grid.nj_ = static_cast<long long>(std::floor(box.max.y() / h)) - grid.j0_ + 1;
    if (static_cast<double>(grid.ni_ + 1) * static_cast<double>(grid.nj_ + 1) > kMaxNodes)
      return std::nullopt;
    grid.nodes_.reserve(static_cast<std::size_t>((grid.ni_ + 1) * (grid.nj_ + 1)));
    for (long long j = 0; j <= grid.nj_; ++j) {
      for (long long i = 0; i <= grid.ni_; ++i)
        grid.nodes_.emplace_back(static_cast<double>(grid.i0_ + i) * h,
                                 static_cast<double>(grid.j0_ + j) * h);
    }
    exact.apply(std::span<Vec2>(grid.nodes_));
    if (!std::all_of(grid.nodes_.begin(), grid.nodes_.end(), [](const Vec2& n) { return n.allFinite(); }))
      return std::nullopt;
    return grid;
  }

  [[nodiscard]] bool covers(const Vec2& p) const {
    const double u = std::floor(p.x() / h_) - static_cast<double>(i0_);
    const double v = std::floor(p.y() / h_) - static_cast<double>(j0_);
    return u >= 0.0 && u < static_cast<double>(ni_) && v >= 0.0 && v < static_cast<double>(nj_);
  }

  // Bilinear blend of the four nodes of p's lattice cell (p covered).
  [[nodiscard]] Vec2 apply(const Vec2& p) const {
    const double fu = std::floor(p.x() / h_), fv = std::floor(p.y() / h_);
    const double s = p.x() / h_ - fu;
    const double t = p.y() / h_ - fv;
    const auto i = static_cast<long long>(fu) - i0_;
    const auto j = static_cast<long long>(fv) - j0_;
    return (1 - s) * (1 - t) * node(i, j) + s * (1 - t) * node(i + 1, j) + (1 - s) * t * node(i, j + 1) +
           s * t * node(i + 1, j + 1);
  }

 private:
  GridTransform() = default;

  [[nodiscard]] const Vec2& node(long long i, long long j) const {
    return nodes_[static_cast<std::size_t>(j * (ni_ + 1) + i)];
  }

  double h_ = 1.0;
  long long i0_ = 0, j0_ = 0;  // lattice index of node (0, 0)
  long long ni_ = 0, nj_ = 0;  // cells
  std::vector<Vec2> nodes_;    // (ni_ + 1) x (nj_ + 1), row-major from (i0_, j0_)
};

// Error allowed for the grid transformation: 1e-4 pixel (1 mm on a 10 m DEM).
constexpr double kGridTolerancePx = 1e-4;

// One raster of the mosaic with the part of it the sampler keeps.
struct Raster {
  DemInfo info;
  PixelGrid grid;
  HeightWindow heights;
  CrsTransform to_raster;             // frame CRS -> raster CRS
  std::optional<GridTransform> fast;  // the same over the area read, when accurate enough

  // Frame CRS -> raster CRS in place: through the grid where it covers the points, with one
  // PROJ call for the others. Points PROJ cannot transform become NaN.
  void transform(std::span<Vec2> xy) const {
    std::vector<std::size_t> exact;
    for (std::size_t k = 0; k < xy.size(); ++k) {
      if (fast && fast->covers(xy[k])) {
        xy[k] = fast->apply(xy[k]);
      } else {
        exact.push_back(k);
      }
    }
    if (exact.empty()) return;
    std::vector<Vec2> rest(exact.size());
    for (std::size_t k = 0; k < exact.size(); ++k) rest[k] = xy[exact[k]];
    to_raster.apply(std::span<Vec2>(rest));
    for (std::size_t k = 0; k < exact.size(); ++k) xy[exact[k]] = rest[k];
  }

  // Bilinear between the four surrounding cell centres; nodata corners dropped and the
  // remaining weights renormalised. A point exactly at the centre of a void has no height
  // (all valid corners have weight 0).
  [[nodiscard]] std::optional<double> bilinear(const Vec2& uv, NearVoid near_void) const {
    const AxisCells a = axis_cells(uv.x(), grid.width);
    const AxisCells b = axis_cells(uv.y(), grid.height);
    const std::array<double, 4> z{heights.at(a.i0, b.i0), heights.at(a.i1, b.i0), heights.at(a.i0, b.i1),
                                  heights.at(a.i1, b.i1)};
    const std::array<double, 4> w{(1 - a.t) * (1 - b.t), a.t * (1 - b.t), (1 - a.t) * b.t, a.t * b.t};
    double sum = 0.0;
    double weight = 0.0;
    for (std::size_t k = 0; k < 4; ++k) {
      if (std::isnan(z[k])) {
        if (near_void == NearVoid::no_height && w[k] > 0.0) return std::nullopt;
        continue;
      }
      sum += w[k] * z[k];
      weight += w[k];
    }
    if (!(weight > 0.0)) return std::nullopt;
    return sum / weight;
  }

  // Inverse-distance weighting of the same four cells, weight 1/d^2 with d in the raster's
  // CRS units (degrees for geographic rasters); an exact hit on a valid cell returns it.
  [[nodiscard]] std::optional<double> idw(const Vec2& uv, NearVoid near_void) const {
    const AxisCells a = axis_cells(uv.x(), grid.width);
    const AxisCells b = axis_cells(uv.y(), grid.height);
    const double cu = a.i0 + a.t;  // clamped position, in cell indices
    const double cv = b.i0 + b.t;
    const std::array<std::array<int, 2>, 4> cells{{{a.i0, b.i0}, {a.i1, b.i0}, {a.i0, b.i1}, {a.i1, b.i1}}};
    double sum = 0.0;
    double weight = 0.0;
    bool void_near = false;
    for (const auto& [col, row] : cells) {
      const double z = heights.at(col, row);
      const double ex = (cu - col) * grid.dx;
      const double ey = (cv - row) * grid.dy;
      const double d2 = ex * ex + ey * ey;
      if (std::isnan(z)) {
        void_near = true;
        continue;
      }
      if (d2 == 0.0) return z;
      sum += z / d2;
      weight += 1.0 / d2;
    }
    if (!(weight > 0.0) || (void_near && near_void == NearVoid::no_height)) return std::nullopt;
    return sum / weight;
  }

  // The cell containing the point (border cells within half a pixel of the border).
  [[nodiscard]] std::optional<double> nearest(const Vec2& uv) const {
    const int col = std::clamp(static_cast<int>(std::floor(uv.x() + 0.5)), 0, grid.width - 1);
    const int row = std::clamp(static_cast<int>(std::floor(uv.y() + 0.5)), 0, grid.height - 1);
    const double z = heights.at(col, row);
    if (std::isnan(z)) return std::nullopt;
    return z;
  }

  // Height at a point given in the raster's CRS; nullopt outside the raster or on a void.
  [[nodiscard]] std::optional<double> sample(const Vec2& xy, Interpolation method, NearVoid near_void) const {
    if (std::isnan(xy.x()) || std::isnan(xy.y())) return std::nullopt;
    const Vec2 uv = grid.index_of(xy);
    if (!grid.inside(uv)) return std::nullopt;
    switch (method) {
      case Interpolation::bilinear:
        return bilinear(uv, near_void);
      case Interpolation::idw:
        return idw(uv, near_void);
      case Interpolation::nearest:
        return nearest(uv);
    }
    return std::nullopt;
  }
};

PixelGrid pixel_grid(const gdal::GeoTransform& gt, int width, int height) {
  return {gt[0], gt[1], gt[3], gt[5], width, height};
}

// Pixels of `grid` covering `box` (raster CRS) plus 2 pixels, clamped to the raster; empty
// when the box does not intersect the raster.
gdal::PixelWindow window_over(const PixelGrid& grid, const Aabb2& box) {
  if (box.empty() || !box.min.allFinite() || !box.max.allFinite()) return {};
  // Pixel-edge coordinates of the box (0 = first edge, width = last edge).
  const double ca = (box.min.x() - grid.x0) / grid.dx;
  const double cb = (box.max.x() - grid.x0) / grid.dx;
  const double ra = (box.min.y() - grid.y0) / grid.dy;
  const double rb = (box.max.y() - grid.y0) / grid.dy;
  const double c_lo = std::min(ca, cb);
  const double c_hi = std::max(ca, cb);
  const double r_lo = std::min(ra, rb);
  const double r_hi = std::max(ra, rb);
  if (c_hi < 0.0 || r_hi < 0.0 || c_lo > grid.width || r_lo > grid.height) return {};
  const auto clamp_to = [](double v, int n) {
    return static_cast<int>(std::clamp(v, 0.0, static_cast<double>(n)));
  };
  const int col0 = clamp_to(std::floor(c_lo) - 2.0, grid.width);
  const int col1 = clamp_to(std::ceil(c_hi) + 2.0, grid.width);
  const int row0 = clamp_to(std::floor(r_lo) - 2.0, grid.height);
  const int row1 = clamp_to(std::ceil(r_hi) + 2.0, grid.height);
  return {col0, row0, col1 - col0, row1 - row0};
}

// Raw band values -> metres (scale, offset, then vertical unit); nodata and NaN -> NaN.
std::vector<double> to_metres(std::vector<double> raw, const DemInfo& info) {
  const double to_m = metres_per_unit(info.unit);
  for (double& v : raw) {
    if (std::isnan(v) || (info.nodata && v == *info.nodata)) {
      v = kNaN;
    } else {
      v = (v * info.scale + info.offset) * to_m;
    }
  }
  return raw;
}

std::string format_box(const LonLatBox& b) {
  std::ostringstream out;
  out << std::fixed << std::setprecision(4) << "lon " << b.min_lon << " to " << b.max_lon << ", lat "
      << b.min_lat << " to " << b.max_lat;
  return out.str();
}

LonLatBox lonlat_box(const Aabb2& b) {
  return {b.min.x(), b.min.y(), b.max.x(), b.max.y()};
}

std::string quoted_list(const std::vector<std::string>& paths) {
  std::string out;
  for (const auto& p : paths) out += (out.empty() ? "'" : ", '") + p + "'";
  return out;
}

// Bounding box in the frame CRS of the raster's extent, by transforming its densified edges
// back with the same operation (points PROJ cannot transform are skipped).
Aabb2 extent_in_frame(const DemInfo& info, const CrsTransform& to_raster) {
  constexpr int kSteps = 20;
  const Aabb2& e = info.extent;
  Aabb2 out;
  const auto add = [&](double x, double y) {
    try {
      out.extend(to_raster.apply_inverse(Vec2(x, y)));
    } catch (const ProjectionError&) {
      // Outside the operation's domain: that edge point does not bound anything usable.
    }
  };
  for (int i = 0; i <= kSteps; ++i) {
    const double s = static_cast<double>(i) / kSteps;
    const double x = e.min.x() + s * (e.max.x() - e.min.x());
    const double y = e.min.y() + s * (e.max.y() - e.min.y());
    add(x, e.min.y());
    add(x, e.max.y());
    add(e.min.x(), y);
    add(e.max.x(), y);
  }
  return out;
}

Aabb2 extent_in_frame(const Raster& raster) {
  return extent_in_frame(raster.info, raster.to_raster);
}

void report_missing_grid(const DemInfo& info, const std::string& frame_crs, Diagnostics* diagnostics) {
  if (diagnostics == nullptr) return;
  std::ostringstream message;
  message << "DEM '" << info.path << "': a more accurate transformation from " << frame_crs << " to "
          << info.crs << " needs the grid(s) " << info.missing_grids
          << ", which are not installed (projsync --file <grid> installs them); using '"
          << info.transform_name << "'";
  if (info.transform_accuracy_m) {
    message << " (accuracy " << *info.transform_accuracy_m << " m)";
  } else {
    message << " (accuracy unknown)";
  }
  message << " instead";
  diagnostics->report(Severity::warning, codes::kDemDatumGridMissing, message.str());
}

// Sides (m) of the cell at (col, row), in the frame's metric CRS: the distance from its centre
// to its neighbour's along the row and down the column. Nothing where PROJ cannot measure them
// or they are not finite and > 0.
std::optional<std::pair<double, double>> cell_sides_m(const PixelGrid& grid, const CrsTransform& to_raster,
                                                      double col, double row) {
  const auto centre = [&](double c, double r) {
    return Vec2(grid.x0 + (c + 0.5) * grid.dx, grid.y0 + (r + 0.5) * grid.dy);
  };
  try {
    const Vec2 p = to_raster.apply_inverse(centre(col, row));
    const double along = (to_raster.apply_inverse(centre(col + 1.0, row)) - p).norm();
    const double down = (to_raster.apply_inverse(centre(col, row + 1.0)) - p).norm();
    if (std::isfinite(along) && along > 0.0 && std::isfinite(down) && down > 0.0)
      return std::pair{along, down};
  } catch (const ProjectionError&) {
    // Outside the operation's domain.
  }
  return std::nullopt;
}

// Longer side (m) of the cells of each row of `window`: the larger distance in the frame's
// metric CRS from a cell centre at the window's middle column to its neighbour along the row
// and across it (a geographic raster's cells narrow away from the equator). Measured on one row
// in max(1, rows / 64), the rows between taking the last measured size; rows PROJ cannot
// measure take the nearest measured one. Empty when no row can be measured.
std::vector<double> cell_sizes_m(const PixelGrid& grid, const gdal::PixelWindow& window,
                                 const CrsTransform& to_raster) {
  const int stride = std::max(1, window.rows / 64);
  const int centre_col = window.col0 + window.cols / 2;  // whole column
  std::vector<double> sizes(static_cast<std::size_t>(window.rows), kNaN);
  bool any = false;
  for (int r = 0; r < window.rows; r += stride) {
    // Rows PROJ cannot measure are filled from the nearest measured row.
    const auto sides = cell_sides_m(grid, to_raster, centre_col, window.row0 + r);
    if (!sides) continue;
    std::fill(sizes.begin() + r, sizes.begin() + std::min(r + stride, window.rows),
              std::max(sides->first, sides->second));
    any = true;
  }
  if (!any) return {};
  // Unmeasured rows: the size of the previous measured row, else of the next.
  for (std::size_t r = 1; r < sizes.size(); ++r) {
    if (std::isnan(sizes[r])) sizes[r] = sizes[r - 1];
  }
  for (std::size_t r = sizes.size() - 1; r-- > 0;) {
    if (std::isnan(sizes[r])) sizes[r] = sizes[r + 1];
  }
  return sizes;
}

// Number of the first cells listed in a dem.implausible_height / dem.spike warning.
constexpr std::size_t kCellsListed = 5;

// "1e+30 m at lon -122.401003, lat 37.753312 (pixel 31, line 24)" for each listed cell, and
// how many more there are.
std::string describe_cells(const terrain_detail::VoidedCells& cells, const gdal::PixelWindow& window,
                           const PixelGrid& grid, const DemInfo& info) {
  std::optional<CrsTransform> to_lonlat;
  try {
    to_lonlat.emplace(info.crs_wkt, "EPSG:4326");
  } catch (const ProjectionError&) {
    // A CRS without a path to WGS84: the cells are given in the raster's own CRS.
  }
  std::ostringstream out;
  for (std::size_t k = 0; k < cells.first.size(); ++k) {
    const auto& cell = cells.first[k];
    const int col = window.col0 + cell.col;
    const int row = window.row0 + cell.row;
    const Vec2 xy(grid.x0 + (col + 0.5) * grid.dx, grid.y0 + (row + 0.5) * grid.dy);
    out << (k == 0 ? "" : "; ") << std::setprecision(6) << cell.height_m << " m";
    if (!std::isnan(cell.around_m)) out << " where its neighbours' median is " << cell.around_m << " m,";
    std::optional<Vec2> lonlat;
    if (to_lonlat) {
      try {
        lonlat = to_lonlat->apply(xy);
      } catch (const ProjectionError&) {
        // Given in the raster's CRS below.
      }
    }
    out << std::fixed << std::setprecision(6);
    if (lonlat) {
      out << " at lon " << lonlat->x() << ", lat " << lonlat->y() << " (pixel " << col << ", line " << row
          << ")";
    } else {
      out << " at pixel " << col << ", line " << row << " (" << info.crs << " " << xy.x() << ", " << xy.y()
          << ")";
    }
    out.unsetf(std::ios::floatfield);
  }
  if (cells.count > cells.first.size()) out << "; and " << cells.count - cells.first.size() << " more";
  return out.str();
}

std::string format_number(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

// Makes the implausible heights and the one-cell spikes of a window voids (`z` in metres),
// counts them in `info` and reports one warning per kind.
void void_implausible_cells(std::vector<double>& z, const gdal::PixelWindow& window, const PixelGrid& grid,
                            const CrsTransform& to_raster, const DemOptions& options, DemInfo& info,
                            Diagnostics* diagnostics) {
  const auto implausible = terrain_detail::void_implausible_heights(z, window.cols, options.plausible_min_m,
                                                                    options.plausible_max_m, kCellsListed);
  info.implausible_cells = implausible.count;
  if (implausible.count > 0 && diagnostics != nullptr) {
    diagnostics->report(Severity::warning, codes::kDemImplausibleHeight,
                        "DEM '" + info.path + "': " + std::to_string(implausible.count) +
                            (implausible.count == 1 ? " cell" : " cells") +
                            " outside the plausible heights " + format_number(options.plausible_min_m) +
                            " to " + format_number(options.plausible_max_m) +
                            " m (fill values not flagged as nodata?) treated as " +
                            (implausible.count == 1 ? "a void: " : "voids: ") +
                            describe_cells(implausible, window, grid, info));
  }
  if (!std::isfinite(options.spike_min_step_m)) return;
  const std::vector<double> cell_m = cell_sizes_m(grid, window, to_raster);
  if (cell_m.empty()) return;  // no row PROJ can measure: spikes cannot be told from slopes
  const terrain_detail::SpikeCriteria criteria{options.spike_min_step_m, options.spike_step_per_cell,
                                               options.spike_max_neighbour_spread};
  const auto spikes = terrain_detail::void_spikes(z, window.cols, cell_m, criteria, kCellsListed);
  info.spike_cells = spikes.count;
  if (spikes.count > 0 && diagnostics != nullptr) {
    diagnostics->report(
        Severity::warning, codes::kDemSpike,
        "DEM '" + info.path + "': " + std::to_string(spikes.count) +
            (spikes.count == 1 ? " one-cell spike or pit" : " one-cell spikes or pits") + " (more than max(" +
            format_number(options.spike_min_step_m) + " m, " + format_number(options.spike_step_per_cell) +
            " x the cell size) from the median of 8 neighbours that agree among themselves) treated as " +
            (spikes.count == 1 ? "a void: " : "voids: ") + describe_cells(spikes, window, grid, info));
  }
}

// With DemOptions::ground_filter_m: takes a surface model's buildings, trees and pits down to
// the ground (`z` in metres), counts them in `info` and reports them.
void filter_ground(std::vector<double>& z, const gdal::PixelWindow& window, const PixelGrid& grid,
                   const CrsTransform& to_raster, const DemOptions& options, DemInfo& info,
                   Diagnostics* diagnostics) {
  // The cell sizes at the window's centre (whole cells).
  const int centre_col = window.col0 + window.cols / 2;
  const int centre_row = window.row0 + window.rows / 2;
  const auto axes = cell_sides_m(grid, to_raster, centre_col, centre_row);
  if (!axes) return;
  const auto radius = [&](double cell_m) {
    return std::max(1, static_cast<int>(std::floor(0.5 * options.ground_filter_m / cell_m)));
  };
  const int rc = radius(axes->first), rr = radius(axes->second);
  const auto filtered =
      terrain_detail::filter_off_ground(z, window.cols, rc, rr, options.ground_filter_min_height_m);
  info.off_ground_cells = filtered.lowered + filtered.raised;
  if (diagnostics == nullptr) return;
  std::ostringstream message;
  message << "DEM '" << info.path << "' taken as a surface model (--ground-filter " << options.ground_filter_m
          << " m: an opening and a closing over " << 2 * rc + 1 << " x " << 2 * rr + 1 << " cells, "
          << std::setprecision(3) << (2 * rc + 1) * axes->first << " x " << (2 * rr + 1) * axes->second
          << " m): " << filtered.lowered
          << " cells standing out of the ground (buildings, trees) set down to it, " << filtered.raised
          << " cells in pits raised to it, by more than " << format_number(options.ground_filter_min_height_m)
          << " m";
  if (filtered.largest_col >= 0) {
    terrain_detail::VoidedCells largest;
    largest.count = 1;
    largest.first.push_back({filtered.largest_col, filtered.largest_row, filtered.largest_from_m,
                             std::numeric_limits<double>::quiet_NaN()});
    message << "; the largest change " << std::setprecision(3) << filtered.largest_m << " m, the cell of "
            << describe_cells(largest, window, grid, info);
  }
  diagnostics->report(Severity::info, codes::kDemGroundFiltered, message.str());
}

// Why a raster contributes nothing, for the error message when none contributes.
enum class Unused { none, outside, all_nodata };

struct Opened {
  DemInfo info;
  std::optional<Raster> raster;  // when it has valid heights over the area
  Unused unused = Unused::none;
};

// Opens one raster, builds its transformation and reads the window over `area_crs`.
Opened open_raster(const std::string& path, const GeoFrame& frame, const Aabb2& area_crs,
                   const LonLatBox& area_wgs84, const DemOptions& options, Diagnostics* diagnostics) {
  const auto dataset = gdal::Dataset::open_raster(path);
  DemInfo info = gdal::describe_dem(dataset, options.unit);
  CrsTransform to_raster(frame.crs(), info.crs_wkt, area_wgs84);
  info.transform_name = to_raster.operation_name();
  info.transform_accuracy_m = to_raster.accuracy_m();
  if (to_raster.better_operation_missing_grid()) {
    info.missing_grids = to_raster.missing_grids();
    report_missing_grid(info, frame.crs(), diagnostics);
  }

  const PixelGrid grid = pixel_grid(dataset.geo_transform(), info.width, info.height);
  const gdal::PixelWindow window = window_over(grid, to_raster.transform_bounds(area_crs));
  if (window.empty()) return {info, std::nullopt, Unused::outside};
  std::vector<double> z = to_metres(dataset.read_window(window), info);
  void_implausible_cells(z, window, grid, to_raster, options, info, diagnostics);
  if (options.ground_filter_m > 0.0) filter_ground(z, window, grid, to_raster, options, info, diagnostics);
  if (std::all_of(z.begin(), z.end(), [](double v) { return std::isnan(v); })) {
    return {info, std::nullopt, Unused::all_nodata};
  }
  std::optional<GridTransform> fast;
  if (const std::optional<double> step = GridTransform::step_for(to_raster, extent_in_frame(info, to_raster),
                                                                 info.pixel_size, kGridTolerancePx)) {
    fast = GridTransform::build(to_raster, area_crs, *step);
  }
  return {info, Raster{info, grid, HeightWindow{window, std::move(z)}, std::move(to_raster), std::move(fast)},
          Unused::none};
}

// The exception when no raster has a valid height over the area.
[[noreturn]] void throw_no_height(const std::vector<DemInfo>& sources, const std::vector<Unused>& unused,
                                  const LonLatBox& area) {
  std::vector<std::string> paths;
  bool all_outside = true;
  for (std::size_t i = 0; i < sources.size(); ++i) {
    paths.push_back(sources[i].path);
    all_outside = all_outside && unused[i] == Unused::outside;
  }
  const std::string roads = "the roads' area (" + format_box(area) + ")";
  const std::string dems = (paths.size() == 1 ? "DEM " : "DEMs ") + quoted_list(paths);
  if (all_outside) {
    std::string extents;
    for (const auto& s : sources) {
      extents += "; '" + s.path + "' covers " +
                 (s.extent_wgs84 ? format_box(*s.extent_wgs84) : std::string("an unknown area"));
    }
    throw CoverageError(dems + (paths.size() == 1 ? " does" : " do") + " not cover " + roads + extents,
                        100.0);
  }
  // All nodata because every height was implausible: a raster in the wrong unit or scale.
  const auto implausible = [](const DemInfo& s) {
    return s.implausible_cells == 0
               ? std::string()
               : " (" + std::to_string(s.implausible_cells) +
                     " cells there hold implausible heights: a wrong vertical unit or scale?)";
  };
  if (paths.size() == 1) {
    throw InvalidInput(dems + " is all nodata over " + roads + implausible(sources[0]));
  }
  std::string reasons;
  for (std::size_t i = 0; i < sources.size(); ++i) {
    reasons += "; '" + sources[i].path + "' " +
               (unused[i] == Unused::outside ? "does not reach it"
                                             : "is all nodata there" + implausible(sources[i]));
  }
  throw InvalidInput(dems + " have no valid height over " + roads + reasons);
}

// Throws InvalidInput when DemOptions' plausible range or spike criteria are out of range.
void check_sanity_options(const DemOptions& o) {
  const auto require = [](bool ok, const std::string& message) {
    if (!ok) throw InvalidInput("DEM options: " + message);
  };
  require(o.plausible_min_m < o.plausible_max_m, "the plausible heights " + format_number(o.plausible_min_m) +
                                                     " to " + format_number(o.plausible_max_m) +
                                                     " m are not a range (min < max)");
  require(o.spike_min_step_m >= 0.0,
          "spike_min_step_m must be >= 0 m (got " + format_number(o.spike_min_step_m) + ")");
  require(std::isfinite(o.spike_step_per_cell) && o.spike_step_per_cell >= 0.0,
          "spike_step_per_cell must be finite and >= 0 (got " + format_number(o.spike_step_per_cell) + ")");
  require(o.spike_max_neighbour_spread > 0.0 && o.spike_max_neighbour_spread <= 1.0,
          "spike_max_neighbour_spread must be in (0, 1] (got " + format_number(o.spike_max_neighbour_spread) +
              ")");
  require(std::isfinite(o.ground_filter_m) && o.ground_filter_m >= 0.0,
          "ground_filter_m must be finite and >= 0 (got " + format_number(o.ground_filter_m) + ")");
  require(std::isfinite(o.ground_filter_min_height_m) && o.ground_filter_min_height_m >= 0.0,
          "ground_filter_min_height_m must be finite and >= 0 (got " +
              format_number(o.ground_filter_min_height_m) + ")");
}

}  // namespace

struct DemSampler::Impl {
  Vec2 origin = Vec2::Zero();
  Interpolation interpolation = Interpolation::bilinear;
  std::vector<DemInfo> sources;  // every raster given, in order
  std::vector<Raster> rasters;   // those with valid heights over the area, in order
  Aabb2 coverage;                // local frame
};

DemSampler::DemSampler(const std::vector<std::string>& paths, const GeoFrame& frame, const Aabb2& area,
                       const DemOptions& options, Diagnostics* diagnostics)
    : impl_(std::make_unique<Impl>()) {
  if (paths.empty()) throw InvalidInput("no DEM given");
  if (area.empty()) throw InvalidInput("the area to read from the DEMs is empty");
  if (!(options.margin_m >= 0.0)) {
    throw InvalidInput("the DEM margin must be >= 0 m (got " + std::to_string(options.margin_m) + ")");
  }
  check_sanity_options(options);
  impl_->origin = frame.origin();
  impl_->interpolation = options.interpolation;

  // The area in the frame CRS and in WGS84 (area of interest for PROJ and for messages).
  // A ground filter's result at a cell depends on the cells within twice its window.
  Aabb2 area_crs = area.inflated(options.margin_m + 2.0 * options.ground_filter_m);
  area_crs.min += frame.origin();
  area_crs.max += frame.origin();
  const LonLatBox area_wgs84 = lonlat_box(CrsTransform(frame.crs(), "EPSG:4326").transform_bounds(area_crs));

  std::vector<Unused> unused;
  for (const auto& path : paths) {
    Opened opened = open_raster(path, frame, area_crs, area_wgs84, options, diagnostics);
    impl_->sources.push_back(std::move(opened.info));
    unused.push_back(opened.unused);
    if (opened.raster) impl_->rasters.push_back(std::move(*opened.raster));
  }
  if (impl_->rasters.empty()) throw_no_height(impl_->sources, unused, area_wgs84);

  for (const auto& raster : impl_->rasters) {
    Aabb2 box = extent_in_frame(raster);
    if (box.empty()) continue;
    box.min -= frame.origin();
    box.max -= frame.origin();
    impl_->coverage.extend(box);
  }
}

DemSampler::~DemSampler() = default;
DemSampler::DemSampler(DemSampler&&) noexcept = default;
DemSampler& DemSampler::operator=(DemSampler&&) noexcept = default;

std::optional<double> DemSampler::height_at(const Vec2& local) const {
  std::optional<double> out;
  heights_at(std::span<const Vec2>(&local, 1), std::span<std::optional<double>>(&out, 1));
  return out;
}

void DemSampler::heights_at(std::span<const Vec2> points, std::span<std::optional<double>> out,
                            NearVoid near_void) const {
  if (out.size() != points.size()) {
    throw InvalidInput("heights_at: " + std::to_string(points.size()) + " points but room for " +
                       std::to_string(out.size()) + " heights");
  }
  std::fill(out.begin(), out.end(), std::nullopt);
  // Indices of the points still without a height, tried on each raster in mosaic order.
  std::vector<std::size_t> pending;
  pending.reserve(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (points[i].allFinite()) pending.push_back(i);
  }
  std::vector<Vec2> xy;
  for (const Raster& raster : impl_->rasters) {
    if (pending.empty()) break;
    // Every pending point at once: local -> frame CRS -> raster CRS.
    xy.resize(pending.size());
    for (std::size_t k = 0; k < pending.size(); ++k) xy[k] = points[pending[k]] + impl_->origin;
    raster.transform(std::span<Vec2>(xy));
    std::size_t still = 0;
    for (std::size_t k = 0; k < pending.size(); ++k) {
      if (auto z = raster.sample(xy[k], impl_->interpolation, near_void)) {
        out[pending[k]] = z;
      } else {
        pending[still++] = pending[k];
      }
    }
    pending.resize(still);
  }
}

std::optional<Vec2> DemSampler::gradient_at(const Vec2& local, double step_m) const {
  if (!(step_m > 0.0)) {
    throw InvalidInput("gradient_at: the step must be > 0 m (got " + std::to_string(step_m) + ")");
  }
  // Central differences: dz/dx = (z(x+h) - z(x-h)) / 2h, the same along y.
  const std::array<Vec2, 4> probes{local + Vec2(step_m, 0.0), local - Vec2(step_m, 0.0),
                                   local + Vec2(0.0, step_m), local - Vec2(0.0, step_m)};
  std::array<std::optional<double>, 4> z;
  heights_at(probes, z);
  if (!z[0] || !z[1] || !z[2] || !z[3]) return std::nullopt;
  return Vec2((*z[0] - *z[1]) / (2.0 * step_m), (*z[2] - *z[3]) / (2.0 * step_m));
}

const std::vector<DemInfo>& DemSampler::sources() const {
  return impl_->sources;
}
Interpolation DemSampler::interpolation() const {
  return impl_->interpolation;
}
Aabb2 DemSampler::coverage_bounds() const {
  return impl_->coverage;
}

}  // namespace relief
