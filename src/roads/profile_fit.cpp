#include "relief/roads/profile_fit.h"

#include <Eigen/OrderingMethods>
#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <iomanip>
#include <limits>
#include <map>
#include <numbers>
#include <numeric>
#include <sstream>
#include <unordered_map>

#include "relief/core/diagnostic_codes.h"
#include "relief/core/errors.h"
#include "relief/geometry/plane.h"
#include "relief/geometry/soft_qp.h"
#include "relief/roads/vertical_curves.h"
#include "roads/junction_planes.h"
#include "roads/transition_roads.h"

namespace relief {
namespace {

using SpMat = Eigen::SparseMatrix<double>;
using Triplet = Eigen::Triplet<double>;
using Vec = Eigen::VectorXd;

constexpr double kMinCurvatureSpacing = 0.5;  // m; closer stations are not used for z'' rows
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kPinnedReach = 30.0;      // m along a road under a crossing
constexpr double kPinnedStiffness = 30.0;  // data weight factor there (a preference, far below any price)
// Two-sided rows on the junction plane's gradient G in this many directions: |G| <= g / cos(pi / 16).
constexpr int kJunctionPlaneDirections = 8;
constexpr double kJunctionRoomMargin_m = 2.0;  // a junction's room: its widest half-width plus this
// The rows between two road ends across a junction hold their height difference to this share of
// the cap over their distance: a connecting road between them also bends from one road's grade
// to the other's, and at the full cap on average it would pass it there (Liechtenstein: 37 %
// under a 35 % cap with the full share; 0.9 leaves 3.5 % at that cap).
constexpr double kPairGradeShare = 0.9;
constexpr double kPlaneLevelWeight = 0.01;  // per (grade)^2, see fit_profiles
constexpr double kSpanWeight = 1e-3;        // per metre of structure, towards its span (fit_profiles)

// Prices of the soft limits per metre of violation, one level per priority (FitLimit order):
// each level is 10x the next, and the lowest is far above any force the data term can exert
// (2 w |z - d| per station, at most ~30 per metre of road within the departure bound, and the
// bending moment of a kilometre of it), so a limit gives way only to a higher one.
constexpr double kPriceScale = 1e7;
double price(FitLimit limit) {
  switch (limit) {
    case FitLimit::ground_departure:
      return kPriceScale * 1e3;
    case FitLimit::grade:
    case FitLimit::junction_grade:
    case FitLimit::cross_slope:
      return kPriceScale * 1e2;
    case FitLimit::clearance:
      return kPriceScale * 1e1;
    case FitLimit::vertical_curve:
      return kPriceScale;
  }
  return kPriceScale;
}

// Index of every sample's height variable: interior samples own one, road ends share their
// junction's variable.
class VariableMap {
 public:
  explicit VariableMap(const RoadNetwork& network, const std::vector<RoadProfile>& profiles)
      : network_(network) {
    road_base_.reserve(profiles.size());
    std::size_t next = 0;
    for (const RoadProfile& p : profiles) {
      road_base_.push_back(next);
      next += p.size() >= 2 ? p.size() - 2 : 0;
    }
    junction_base_ = next;
    next += network.junctions.size();
    gradient_index_.assign(network.junctions.size(), 0);
    for (const Junction& j : network.junctions) {
      if (j.ends.size() < 2) continue;
      gradient_index_[j.id] = next;
      next += 2;
    }
    count_ = next;
  }
  [[nodiscard]] std::size_t of(std::size_t road, std::size_t i, std::size_t n) const {
    if (i == 0) return junction_base_ + network_.roads[road].start_junction;
    if (i + 1 == n) return junction_base_ + network_.roads[road].end_junction;
    return road_base_[road] + i - 1;
  }
  [[nodiscard]] std::size_t junction(int j) const { return junction_base_ + j; }
  /// First of the two variables (dz/dx, dz/dy) of the tangent plane at junction `j`; only for
  /// junctions with two or more road ends.
  [[nodiscard]] std::size_t gradient(int j) const { return gradient_index_[j]; }
  [[nodiscard]] std::size_t count() const { return count_; }
  /// Variables from here on belong to junctions (heights and tangent planes); before, to the
  /// interior stations of the roads, road after road in station order.
  [[nodiscard]] std::size_t junction_base() const { return junction_base_; }

 private:
  const RoadNetwork& network_;
  std::vector<std::size_t> road_base_;
  std::size_t junction_base_ = 0;
  std::vector<std::size_t> gradient_index_;
  std::size_t count_ = 0;
};

// SoftQp::fixed from the holds: every held sample's variable (a road end's is its junction's: the
// first road that holds it sets it) and every held plane. Returns how many variables are held.
std::size_t hold_variables(const RoadNetwork& network, const std::vector<RoadProfile>& raw,
                           const VariableMap& vars, const FitHolds& holds, SoftQp& qp) {
  if (holds.empty()) return 0;
  if ((!holds.road_z.empty() && holds.road_z.size() != raw.size()) ||
      (!holds.junction_gradient.empty() && holds.junction_gradient.size() != network.junctions.size()))
    throw InvalidInput("fit_profiles: holds need one entry per road and per junction");
  qp.fixed.assign(vars.count(), std::numeric_limits<double>::quiet_NaN());
  std::size_t held = 0;
  const auto hold = [&](std::size_t v, double z) {
    if (!std::isfinite(z) || !std::isnan(qp.fixed[v])) return;
    qp.fixed[v] = z;
    ++held;
  };
  for (std::size_t r = 0; r < holds.road_z.size(); ++r) {
    const std::vector<double>& z = holds.road_z[r];
    if (z.empty()) continue;
    if (z.size() != raw[r].size())
      throw InvalidInput("fit_profiles: a held road has another number of samples");
    for (std::size_t i = 0; i < z.size(); ++i) hold(vars.of(r, i, z.size()), z[i]);
  }
  for (std::size_t j = 0; j < holds.junction_gradient.size(); ++j) {
    const std::optional<Vec2>& g = holds.junction_gradient[j];
    if (!g || network.junctions[j].ends.size() < 2) continue;
    hold(vars.gradient(static_cast<int>(j)), g->x());
    hold(vars.gradient(static_cast<int>(j)) + 1, g->y());
  }
  return held;
}

// Second divided difference z'' at the middle of three stations spaced h1, h2.
std::array<double, 3> curvature_row(double h1, double h2) {
  h1 = std::max(h1, kMinCurvatureSpacing);
  h2 = std::max(h2, kMinCurvatureSpacing);
  return {2.0 / (h1 * (h1 + h2)), -2.0 / (h1 * h2), 2.0 / (h2 * (h1 + h2))};
}

// Arc length of station i as driven (RoadProfile::driven_s), where grades and curvatures are
// taken; the OSM polyline's when unknown.
double driven(const RoadProfile& p, std::size_t i) {
  return p.driven_s.empty() ? p.s[i] : p.driven_s[i];
}

bool is_structure(const Road& road) {
  return road.attributes.bridge || road.attributes.tunnel;
}

// lambda = (cutoff / 2 pi)^4: a smoothing spline halves the amplitude at the cutoff wavelength.
double smoothing_weight(double cutoff_wavelength_m) {
  return std::pow(cutoff_wavelength_m / (2.0 * std::numbers::pi), 4.0);
}

// The junction as a smooth surface: every road leaves it tangent to one plane
// z = z_J + G . (p - p_J), with G two extra variables per junction. The residual of each road's
// first station from that plane is penalised like a curvature, lambda * r^2 / h^3, so a plane
// costs nothing and a step or kink between the roads of a junction does.
void add_junction_planes(const RoadNetwork& network, const std::vector<RoadProfile>& profiles,
                         const VariableMap& vars, double lambda, std::vector<Triplet>& p_entries) {
  for (const Junction& j : network.junctions) {
    if (j.ends.size() < 2) continue;
    for (const RoadEnd& e : j.ends) {
      const RoadProfile& p = profiles[e.road];
      const std::size_t n = p.size();
      if (n < 3 || !p.has_height) continue;  // a two-station road has no interior station
      const std::size_t k = e.at_start ? 1 : n - 2;
      const Vec2 d = p.xy[k] - j.position;
      const double h = std::max(d.norm(), kMinCurvatureSpacing);
      const double w = lambda / (h * h * h);
      const std::array<std::size_t, 4> idx{vars.of(e.road, k, n), vars.junction(j.id), vars.gradient(j.id),
                                           vars.gradient(j.id) + 1};
      const std::array<double, 4> a{1.0, -1.0, -d.x(), -d.y()};
      for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c)
          p_entries.emplace_back(static_cast<int>(idx[r]), static_cast<int>(idx[c]), w * a[r] * a[c]);
    }
  }
}

// Two bridges or tunnels of one layer crossing without a node: the data does not say which is
// above; find_grade_separations guessed, and the user should know where.
void report_guessed_orders(const RoadNetwork& network, const std::vector<GradeSeparation>& separations,
                           Diagnostics& diagnostics) {
  for (const GradeSeparation& sep : separations) {
    if (!sep.guessed_order || sep.alongside) continue;
    const Road& up = network.roads[static_cast<std::size_t>(sep.upper_road)];
    const Road& down = network.roads[static_cast<std::size_t>(sep.lower_road)];
    const auto way = [](const Road& r) {
      return r.osm_way_ids.empty() ? std::int64_t{0} : r.osm_way_ids.front();
    };
    std::ostringstream msg;
    msg << std::fixed << std::setprecision(1) << "road " << up.id << " (OSM way " << way(up) << ") and road "
        << down.id << " (OSM way " << way(down) << "), two " << (up.attributes.tunnel ? "tunnels" : "bridges")
        << " of layer " << effective_layer(up.attributes) << ", cross without a shared node at ("
        << sep.xy.x() << ", " << sep.xy.y() << "): built as a grade separation, road " << up.id
        << " above (its ends lie higher there); a layer tag would say which";
    Diagnostic d;
    d.severity = Severity::warning;
    d.code = codes::kOsmStructuresOnOneLevel;
    d.message = msg.str();
    d.osm_way_id = way(up);
    diagnostics.report(std::move(d));
  }
}

// Structures are spans between abutments: a structure takes no data term when it is anchored to
// ground roads at two or more junctions. One cut off by the data's edge (fewer anchors) has
// nothing to span between, so it keeps the DEM as its data like a ground road and is reported.
// Returns, per road, whether its samples carry the data term.
std::vector<std::uint8_t> roads_with_data(const RoadNetwork& network, Diagnostics& diagnostics) {
  const std::size_t nj = network.junctions.size();
  // Union-find over junctions joined by structure roads.
  std::vector<std::size_t> parent(nj);
  std::iota(parent.begin(), parent.end(), 0);
  const std::function<std::size_t(std::size_t)> find = [&](std::size_t a) {
    while (parent[a] != a) a = parent[a] = parent[parent[a]];
    return a;
  };
  std::vector<std::uint8_t> touches_ground(nj, 0);
  for (const Road& road : network.roads) {
    if (is_structure(road)) {
      parent[find(road.start_junction)] = find(road.end_junction);
    } else {
      touches_ground[road.start_junction] = touches_ground[road.end_junction] = 1;
    }
  }
  std::vector<int> anchors(nj, 0);
  for (std::size_t j = 0; j < nj; ++j) anchors[find(j)] += touches_ground[j];
  std::vector<std::uint8_t> data(network.roads.size(), 1);
  std::vector<std::uint8_t> reported(nj, 0);
  for (const Road& road : network.roads) {
    if (!is_structure(road)) continue;
    const std::size_t c = find(road.start_junction);
    if (anchors[c] >= 2) {
      data[road.id] = 0;
    } else if (!reported[c]) {
      reported[c] = 1;
      Diagnostic d;
      d.code = codes::kFitUnanchoredStructure;
      d.road_id = road.id;
      if (!road.osm_way_ids.empty()) d.osm_way_id = road.osm_way_ids.front();
      d.message = "the " + std::string(road.attributes.bridge ? "bridge" : "tunnel") + " of road " +
                  std::to_string(road.id) + " meets ground roads at " + std::to_string(anchors[c]) +
                  " junction(s) (cut off by the data's edge?); it follows the DEM instead of spanning";
      diagnostics.report(std::move(d));
    }
  }
  return data;
}

// A span's own pull. The heights without data (anchored bridges and tunnels) take the tiny
// regularising weight towards the straight line between their abutments, not towards the DEM
// over them: over a 3 km base tunnel 1e-6 per metre towards the ridge above outweighs the
// deck's smoothing and humps the tunnel up to the crest. The line is the harmonic interpolation
// of the anchors' targets over the road graph (linear in distance along a chain; a junction
// inside a span takes the distance-weighted mean of its arms), solved once (sparse LDL^T).
// `free_weight` is the weight of a variable without data; a component without any anchor
// keeps its target (the eps term).
void span_targets(const std::vector<RoadProfile>& raw, const VariableMap& vars, const Vec& weight,
                  double free_weight, Vec& target) {
  constexpr double kEps = 1e-12;
  const auto n = static_cast<Eigen::Index>(target.size());
  std::vector<Eigen::Index> index(static_cast<std::size_t>(n), -1);
  Eigen::Index count = 0;
  for (std::size_t r = 0; r < raw.size(); ++r) {
    const RoadProfile& p = raw[r];
    if (!p.has_height) continue;
    for (std::size_t i = 0; i < p.size(); ++i) {
      const std::size_t v = vars.of(r, i, p.size());
      if (index[v] < 0 && weight[static_cast<Eigen::Index>(v)] <= free_weight) index[v] = count++;
    }
  }
  if (count == 0) return;
  std::vector<Eigen::Triplet<double>> entries;
  Vec rhs = Vec::Zero(count);
  for (std::size_t v = 0; v < index.size(); ++v) {
    if (index[v] < 0) continue;
    entries.emplace_back(index[v], index[v], kEps);
    rhs[index[v]] += kEps * target[static_cast<Eigen::Index>(v)];
  }
  for (std::size_t r = 0; r < raw.size(); ++r) {
    const RoadProfile& p = raw[r];
    if (!p.has_height) continue;
    for (std::size_t i = 0; i + 1 < p.size(); ++i) {
      const std::size_t a = vars.of(r, i, p.size()), b = vars.of(r, i + 1, p.size());
      if (a == b || (index[a] < 0 && index[b] < 0)) continue;
      const double w = 1.0 / std::max(p.s[i + 1] - p.s[i], kMinCurvatureSpacing);
      for (const auto& [x, y] : {std::pair{a, b}, std::pair{b, a}}) {
        if (index[x] < 0) continue;
        entries.emplace_back(index[x], index[x], w);
        if (index[y] >= 0) {
          entries.emplace_back(index[x], index[y], -w);
        } else {
          rhs[index[x]] += w * target[static_cast<Eigen::Index>(y)];
        }
      }
    }
  }
  Eigen::SparseMatrix<double> laplacian(count, count);
  laplacian.setFromTriplets(entries.begin(), entries.end());
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(laplacian);
  if (ldlt.info() != Eigen::Success) return;  // keep the DEM targets (never seen: L + eps I is SPD)
  const Vec z = ldlt.solve(rhs);
  for (std::size_t v = 0; v < index.size(); ++v) {
    if (index[v] >= 0) target[static_cast<Eigen::Index>(v)] = z[index[v]];
  }
}

using Permutation = Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int>;

// Fill-reducing elimination order. The interiors of the roads come first, each road in station
// order: a chain eliminated end to end fills in only its two junctions' variables, so that part
// costs O(samples). Left for the end, ordered by AMD, are the junctions' variables (heights and
// tangent planes) and the interiors of the roads that clearance rows tie to other roads (a
// viaduct over a street: a row every 5 m couples the two, and eliminating either in station
// order would drag every station of the other along). AMD sees their couplings in P + A'A plus,
// for every chain road, the clique of junction variables its elimination leaves behind. Running
// AMD on the whole matrix gives the same fill but takes seconds on millions of stations.
// `block_stations`: per road, interior stations that rows tie across the junction to another
// road's (the rows across junctions in fit_profiles); they go to the block too, and split
// their road's chain in parts, each eliminated in station order.
Permutation elimination_order(const RoadNetwork& network, const std::vector<RoadProfile>& profiles,
                              const VariableMap& vars, const std::vector<GradeSeparation>& separations,
                              const std::vector<std::vector<std::size_t>>& block_stations, const SpMat& P,
                              const Eigen::SparseMatrix<double, Eigen::RowMajor>& A) {
  const auto n = static_cast<int>(vars.count());
  const auto base = static_cast<int>(vars.junction_base());
  std::vector<std::uint8_t> tied(network.roads.size(), 0);
  for (const GradeSeparation& sep : separations) tied[sep.upper_road] = tied[sep.lower_road] = 1;
  // New positions: chain interiors first; the block's variables numbered in `block_of`.
  std::vector<int> block_of(static_cast<std::size_t>(n), -1);
  std::vector<int> order_of(static_cast<std::size_t>(n), -1);
  int next = 0, blocks = 0;
  for (const Road& road : network.roads) {
    const std::size_t np = profiles[road.id].size();
    for (const std::size_t i : block_stations[road.id]) {
      const auto v = static_cast<std::size_t>(vars.of(road.id, i, np));
      if (i >= 1 && i + 1 < np && block_of[v] < 0) block_of[v] = blocks++;
    }
    for (std::size_t i = 1; i + 1 < np; ++i) {
      const auto v = static_cast<std::size_t>(vars.of(road.id, i, np));
      if (block_of[v] >= 0) continue;
      if (tied[road.id]) {
        block_of[v] = blocks++;
      } else {
        order_of[v] = next++;
      }
    }
  }
  for (int v = base; v < n; ++v) block_of[static_cast<std::size_t>(v)] = blocks++;

  std::vector<Triplet> pattern;
  const auto link = [&](int a, int b) {
    const int x = block_of[static_cast<std::size_t>(a)], y = block_of[static_cast<std::size_t>(b)];
    if (x >= 0 && y >= 0) pattern.emplace_back(x, y, 1.0);
  };
  for (int j = 0; j < P.outerSize(); ++j)
    for (SpMat::InnerIterator it(P, j); it; ++it) link(static_cast<int>(it.row()), j);
  for (Eigen::Index r = 0; r < A.rows(); ++r) {
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator i(A, r); i; ++i)
      for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator k(A, r); k; ++k)
        link(static_cast<int>(i.col()), static_cast<int>(k.col()));
  }
  // The clique each part of a chain road leaves among the variables beside it: two stations on
  // each side (curvature rows span three), a junction's height, and its plane where the part
  // holds the road's first or last interior station.
  std::vector<int> clique;
  const auto add_junction = [&](int j) {
    clique.push_back(static_cast<int>(vars.junction(j)));
    if (network.junctions[j].ends.size() >= 2) {
      clique.push_back(static_cast<int>(vars.gradient(j)));
      clique.push_back(static_cast<int>(vars.gradient(j)) + 1);
    }
  };
  for (const Road& road : network.roads) {
    if (tied[road.id]) continue;
    const std::size_t np = profiles[road.id].size();
    if (np < 3) {
      clique.clear();
      add_junction(road.start_junction);
      add_junction(road.end_junction);
      for (const int a : clique)
        for (const int b : clique) link(a, b);
      continue;
    }
    const auto in_chain = [&](std::size_t i) {
      return order_of[static_cast<std::size_t>(vars.of(road.id, i, np))] >= 0;
    };
    std::size_t i = 1;
    while (i + 1 < np) {
      if (!in_chain(i)) {
        ++i;
        continue;
      }
      std::size_t last = i;
      while (last + 2 < np && in_chain(last + 1)) ++last;
      clique.clear();
      if (i == 1) add_junction(road.start_junction);
      if (last + 2 == np) add_junction(road.end_junction);
      for (const std::size_t k : {i - 1, i >= 2 ? i - 2 : 0, last + 1, std::min(last + 2, np - 1)}) {
        const auto v = static_cast<std::size_t>(vars.of(road.id, k, np));
        if (block_of[v] >= 0) clique.push_back(static_cast<int>(v));
      }
      for (const int a : clique)
        for (const int b : clique) link(a, b);
      i = last + 1;
    }
  }
  SpMat block_pattern(blocks, blocks);
  block_pattern.setFromTriplets(pattern.begin(), pattern.end());
  std::vector<Triplet>().swap(pattern);
  Permutation amd_inverse;
  Eigen::AMDOrdering<int>()(block_pattern, amd_inverse);
  const Permutation amd = amd_inverse.inverse();  // old block index -> new
  Permutation order(n);
  for (int v = 0; v < n; ++v) {
    const int b = block_of[static_cast<std::size_t>(v)];
    order.indices()[v] = b >= 0 ? next + amd.indices()[b] : order_of[static_cast<std::size_t>(v)];
  }
  return order;
}

}  // namespace

std::optional<GradePolicy> parse_grade_policy(std::string_view text) {
  if (text == "fidelity") return GradePolicy::fidelity;
  if (text == "design") return GradePolicy::design;
  return std::nullopt;
}

std::string_view to_string(GradePolicy policy) {
  return policy == GradePolicy::fidelity ? "fidelity" : "design";
}

double grade_limit(const ProfileFitOptions& options, HighwayClass cls) {
  if (options.policy == GradePolicy::design) return options.limits.limit_for(cls) / 100.0;
  const bool highway = cls == HighwayClass::motorway || cls == HighwayClass::motorway_link ||
                       cls == HighwayClass::trunk || cls == HighwayClass::trunk_link;
  if (highway) return options.fidelity_highway_max_grade_percent / 100.0;
  return (is_foot_way(cls) ? options.fidelity_foot_max_grade_percent : options.fidelity_max_grade_percent) /
         100.0;
}

double grade_limit(const ProfileFitOptions& options, const WayAttributes& attributes) {
  const double cap = grade_limit(options, attributes.highway);
  if (!attributes.tunnel) return cap;
  // Not below the highways' physical cap: a freeway tunnel on a 9 % ramp is real.
  const double table = options.limits.limit_for(attributes.highway) / 100.0;
  return std::min(cap, std::max(table, options.fidelity_highway_max_grade_percent / 100.0));
}

std::string_view to_string(FitLimit limit) {
  switch (limit) {
    case FitLimit::ground_departure:
      return "ground_departure";
    case FitLimit::grade:
      return "grade";
    case FitLimit::junction_grade:
      return "junction_grade";
    case FitLimit::cross_slope:
      return "cross_slope";
    case FitLimit::clearance:
      return "clearance";
    case FitLimit::vertical_curve:
      return "vertical_curve";
  }
  return "unknown";
}

double design_speed_kmh(const WayAttributes& attributes) {
  return 3.6 * attributes.maxspeed_mps.value_or(default_speed_mps(attributes.highway));
}

namespace {

// The soft rows of the problem, each tagged with its limit and place (road and station, or
// junction) so that a violation can be reported where it is.
class FitRows {
 public:
  struct Tag {
    FitLimit limit;
    int road;               // -1: a junction row
    std::uint32_t station;  // station index on the road; the junction id for junction rows
  };

  /// `price_share`: the share of its limit's price the row costs (a place held by k rows at once
  /// shares it, 1 / k, so that together they weigh like one and the priorities hold).
  void add(std::initializer_list<std::pair<std::size_t, double>> row, double lo, double hi, Tag tag,
           bool always = false, double price_share = 1.0) {
    // Straight into compressed rows (the rows come in order): columns ascending within the row,
    // a repeated column summed, as Eigen's setFromTriplets would, without the triplets and the
    // transposed copy it builds (on a 414 km network 1.1 M rows: about 150 MB at once).
    const std::size_t begin = columns_.size();
    for (const auto& [col, value] : row) {
      const auto c = static_cast<int>(col);
      std::size_t k = begin;
      while (k < columns_.size() && columns_[k] < c) ++k;
      if (k < columns_.size() && columns_[k] == c) {
        values_[k] += value;
      } else {
        columns_.insert(columns_.begin() + static_cast<std::ptrdiff_t>(k), c);
        values_.insert(values_.begin() + static_cast<std::ptrdiff_t>(k), value);
      }
    }
    row_end_.push_back(static_cast<int>(columns_.size()));
    lower_.push_back(lo);
    upper_.push_back(hi);
    tags_.push_back(tag);
    always_.push_back(always ? 1 : 0);
    price_share_.push_back(price_share);
    group_.push_back(tag.road);
  }
  [[nodiscard]] std::size_t size() const { return tags_.size(); }
  [[nodiscard]] const Tag& tag(std::size_t r) const { return tags_[r]; }

  /// Moves the rows into `qp` (A, bounds, prices); only the tags stay.
  void move_into(SoftQp& qp, std::size_t variables) {
    const auto m = static_cast<Eigen::Index>(lower_.size());
    if (columns_.size() >= static_cast<std::size_t>(std::numeric_limits<int>::max()))
      throw Error("profile fit: too many constraint entries");
    row_end_.insert(row_end_.begin(), 0);
    qp.A = Eigen::Map<const Eigen::SparseMatrix<double, Eigen::RowMajor>>(
        m, static_cast<Eigen::Index>(variables), static_cast<Eigen::Index>(columns_.size()), row_end_.data(),
        columns_.data(), values_.data());
    release(columns_);
    release(values_);
    release(row_end_);
    qp.lower = Eigen::Map<const Vec>(lower_.data(), m);
    qp.upper = Eigen::Map<const Vec>(upper_.data(), m);
    release(lower_);
    release(upper_);
    qp.price.resize(m);
    for (Eigen::Index r = 0; r < m; ++r) {
      const auto k = static_cast<std::size_t>(r);
      qp.price[r] = price(tags_[k].limit) * price_share_[k];
    }
    std::vector<double>().swap(price_share_);
    qp.always = std::move(always_);
    qp.group = std::move(group_);
  }

 private:
  template <typename T>
  static void release(std::vector<T>& v) {
    std::vector<T>().swap(v);
  }

  std::vector<int> columns_;    // column of each entry, row after row
  std::vector<double> values_;  // and its value
  std::vector<int> row_end_;    // one past each row's last entry
  std::vector<double> lower_, upper_;
  std::vector<Tag> tags_;
  std::vector<std::uint8_t> always_;
  std::vector<double> price_share_;
  std::vector<int> group_;  // the road, for screening a road's rows together
};

bool has_design_curves(const Road& road, const ProfileFitOptions& options) {
  return options.design_curves && road.attributes.highway <= options.design_curves_through;
}

// The vertical curvature bounds of a road: [-crest, +sag] in 1/m.
std::pair<double, double> curvature_bounds(const Road& road, const ProfileFitOptions& options) {
  double crest = options.max_curvature_per_m > 0.0 ? options.max_curvature_per_m : kInf;
  double sag = crest;
  if (has_design_curves(road, options)) {
    const VerticalCurveBounds k = vertical_curve_bounds(design_speed_kmh(road.attributes));
    crest = std::min(crest, k.crest_curvature_per_m());
    sag = std::min(sag, k.sag_curvature_per_m());
  }
  return {crest, sag};
}

// Station of a row on its road, for reporting.
struct Place {
  double s = 0.0;
  Vec2 xy = Vec2::Zero();
};

}  // namespace

ProfileFitResult fit_profiles(const RoadNetwork& network, const std::vector<RoadProfile>& raw,
                              const ProfileFitOptions& options, Diagnostics& diagnostics,
                              const JunctionCuts& cuts) {
  if (raw.size() != network.roads.size())
    throw InvalidInput("fit_profiles: one profile per road is required");
  if (!(options.max_ground_departure_m >= 0.0) || !(options.clearance_m >= 0.0) ||
      !(options.max_curvature_per_m >= 0.0) || !(options.cutoff_wavelength_m > 0.0) ||
      !(options.structure_cutoff_wavelength_m > 0.0)) {
    throw InvalidInput(
        "fit_profiles: departure, clearance and curvature bounds must be >= 0, wavelengths > 0");
  }
  const VariableMap vars(network, raw);
  const std::size_t n = vars.count();

  // Data term: trapezoidal weights (metres of road per sample), none on structures; a tiny
  // weight everywhere keeps P positive definite where a component has no ground at all.
  constexpr double kFreeWeight = 1e-6;
  Vec weight = Vec::Constant(static_cast<Eigen::Index>(n), kFreeWeight);
  Vec target = Vec::Zero(static_cast<Eigen::Index>(n));
  Vec target_weight = Vec::Zero(static_cast<Eigen::Index>(n));
  Vec initial = Vec::Zero(static_cast<Eigen::Index>(n));
  Vec initial_count = Vec::Zero(static_cast<Eigen::Index>(n));
  // Variables that measured ground (not a void, not a structure): the departure bound's rows.
  std::vector<std::uint8_t> measured(n, 0);
  const std::vector<std::uint8_t> with_data = roads_with_data(network, diagnostics);
  ProfileFitResult result;
  result.separations = find_grade_separations(network, raw);
  report_guessed_orders(network, result.separations, diagnostics);
  std::vector<std::uint8_t> separated(raw.size(), 0);
  for (const GradeSeparation& sep : result.separations)
    separated[sep.upper_road] = separated[sep.lower_road] = 1;
  // The road on the ground level stays on the ground: near a crossing its data term is stiffer
  // than the other road's, so the clearance is won by lifting a bridge deck over it, or by
  // lowering an underpass (layer -1) under it. Of two roads off the ground level the one nearer
  // to it holds; at equal distance the lower road.
  std::vector<std::vector<double>> pinned(raw.size());
  for (const GradeSeparation& sep : result.separations) {
    if (sep.ordering_only) continue;  // a tenth of a metre: no road need hold for it
    const int upper = std::abs(effective_layer(network.roads[sep.upper_road].attributes));
    const int lower = std::abs(effective_layer(network.roads[sep.lower_road].attributes));
    if (upper < lower) {
      pinned[sep.upper_road].push_back(sep.s_upper);
    } else {
      pinned[sep.lower_road].push_back(sep.s_lower);
    }
  }
  const auto stiffness = [&](std::size_t r, double s) {
    for (double at : pinned[r])
      if (std::abs(s - at) <= kPinnedReach) return kPinnedStiffness;
    return 1.0;
  };
  for (std::size_t r = 0; r < raw.size(); ++r) {
    const RoadProfile& p = raw[r];
    const bool ground = with_data[r] && p.has_height;
    const bool on_ground = ground && !is_structure(network.roads[r]);
    if (!p.has_height) {
      // A road with no height anywhere is left out of the outputs: its interior stations are
      // held where they are, apart from the problem, and its ends take no part in it.
      for (std::size_t i = 1; i + 1 < p.size(); ++i) {
        const auto k = static_cast<Eigen::Index>(vars.of(r, i, p.size()));
        weight[k] = 1.0;
        initial[k] = target_weight[k] = 0.0;
        initial_count[k] = 1.0;
      }
      continue;
    }
    for (std::size_t i = 0; i < p.size(); ++i) {
      const std::size_t v = vars.of(r, i, p.size());
      const auto k = static_cast<Eigen::Index>(v);
      const double left = i > 0 ? p.s[i] - p.s[i - 1] : 0.0;
      const double right = i + 1 < p.size() ? p.s[i + 1] - p.s[i] : 0.0;
      const double w = ground ? 0.5 * (left + right) * stiffness(r, p.s[i]) : 0.0;
      weight[k] += w;
      target_weight[k] += w * p.z[i];
      initial[k] += p.z[i];
      initial_count[k] += 1.0;
      if (on_ground && !p.filled[i]) measured[v] = 1;
    }
  }
  for (Eigen::Index v = 0; v < static_cast<Eigen::Index>(n); ++v) {
    initial[v] /= std::max(1.0, initial_count[v]);
    target[v] =
        weight[v] > kFreeWeight ? (target_weight[v] + kFreeWeight * initial[v]) / weight[v] : initial[v];
  }
  span_targets(raw, vars, weight, kFreeWeight, target);
  // The span pulls every station off the ground towards it, kSpanWeight per metre of road: with
  // the smoothing alone a long deck or tunnel has shapes that cost next to nothing (the lowest
  // bending mode of 1.6 km under a 200 m cutoff), which the solver's relative tolerances leave
  // anywhere: a 4 m hump inside a generated 1.6 km tunnel, and two overlapping problems (region
  // tiles) 0.2-0.8 m apart there. The pull fixes those shapes at a price no limit or smoothing
  // notices (a metre off the span over a kilometre costs as much as 1 m of ground misfit over 1 m).
  std::vector<double> span_weight(n, 0.0);
  for (std::size_t r = 0; r < raw.size(); ++r) {
    const RoadProfile& p = raw[r];
    if (!p.has_height) continue;
    for (std::size_t i = 0; i < p.size(); ++i) {
      const std::size_t v = vars.of(r, i, p.size());
      if (weight[static_cast<Eigen::Index>(v)] > kFreeWeight) continue;
      const double left = i > 0 ? p.s[i] - p.s[i - 1] : 0.0;
      const double right = i + 1 < p.size() ? p.s[i + 1] - p.s[i] : 0.0;
      span_weight[v] += kSpanWeight * 0.5 * (left + right);
    }
  }
  for (std::size_t v = 0; v < n; ++v) weight[static_cast<Eigen::Index>(v)] += span_weight[v];

  // Smoothness: lambda * sum (z'')^2 ds, with lambda from the cutoff wavelength; and the rows of
  // the vertical curve bounds on the same triples, scaled to metres (times the mean spacing^2).
  FitRows rows;
  const double lambda = smoothing_weight(options.cutoff_wavelength_m);
  const double lambda_structure = smoothing_weight(options.structure_cutoff_wavelength_m);
  std::vector<Triplet> p_entries;
  p_entries.reserve(n * 10);
  for (std::size_t v = 0; v < n; ++v)
    p_entries.emplace_back(static_cast<int>(v), static_cast<int>(v), weight[static_cast<Eigen::Index>(v)]);
  for (std::size_t r = 0; r < raw.size(); ++r) {
    const RoadProfile& p = raw[r];
    if (!p.has_height) continue;
    const std::size_t np = p.size();
    const double road_lambda = network.roads[r].attributes.bridge ? lambda_structure : lambda;
    const auto [crest, sag] = curvature_bounds(network.roads[r], options);
    // Rows that bind over long stretches are never screened out: a design speed's curves, and
    // the curves of roads that clearances push at single stations (screening by distance would
    // find their kinks one round at a time).
    const bool design = has_design_curves(network.roads[r], options) || separated[r];
    for (std::size_t i = 1; i + 1 < np; ++i) {
      const double h1 = driven(p, i) - driven(p, i - 1), h2 = driven(p, i + 1) - driven(p, i);
      const auto c = curvature_row(h1, h2);
      const double h = 0.5 * (std::max(h1, kMinCurvatureSpacing) + std::max(h2, kMinCurvatureSpacing));
      const double w = road_lambda * h;
      const std::array<std::size_t, 3> idx{vars.of(r, i - 1, np), vars.of(r, i, np), vars.of(r, i + 1, np)};
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b)
          p_entries.emplace_back(static_cast<int>(idx[a]), static_cast<int>(idx[b]), w * c[a] * c[b]);
      if (std::isfinite(crest) && h1 >= kMinCurvatureSpacing && h2 >= kMinCurvatureSpacing) {
        const double h_sq = h * h;
        rows.add({{idx[0], c[0] * h_sq}, {idx[1], c[1] * h_sq}, {idx[2], c[2] * h_sq}}, -crest * h_sq,
                 sag * h_sq, {FitLimit::vertical_curve, static_cast<int>(r), static_cast<std::uint32_t>(i)},
                 design);
      }
    }
  }
  add_junction_planes(network, raw, vars, lambda, p_entries);
  // A weak pull of every junction plane towards level: the cross slope of a plane that its roads
  // do not determine (two roads in line) is level rather than arbitrary, which also keeps the
  // normal equations well conditioned. A 10 % slope costs as much as 1 cm of misfit over 1 m.
  for (const Junction& j : network.junctions) {
    if (j.ends.size() < 2) continue;
    for (int k = 0; k < 2; ++k) {
      const auto g = static_cast<int>(vars.gradient(j.id)) + k;
      p_entries.emplace_back(g, g, kPlaneLevelWeight);
    }
  }
  SoftQp qp;
  qp.P.resize(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(n));
  qp.P.setFromTriplets(p_entries.begin(), p_entries.end());
  std::vector<Triplet>().swap(p_entries);
  qp.q = -weight.cwiseProduct(target);

  // Departure from the DEM, on every measured ground variable.
  if (options.max_ground_departure_m > 0.0) {
    for (std::size_t r = 0; r < raw.size(); ++r) {
      const RoadProfile& p = raw[r];
      for (std::size_t i = 0; i < p.size(); ++i) {
        const std::size_t v = vars.of(r, i, p.size());
        if (!measured[v]) continue;
        measured[v] = 0;  // one row per variable (a junction's is shared)
        const double t = target[static_cast<Eigen::Index>(v)];
        rows.add({{v, 1.0}}, t - options.max_ground_departure_m, t + options.max_ground_departure_m,
                 {FitLimit::ground_departure, static_cast<int>(r), static_cast<std::uint32_t>(i)});
      }
    }
  }

  // Grade rows on every segment.
  std::vector<double> junction_cap(network.junctions.size(), 0.0);
  for (std::size_t r = 0; r < raw.size(); ++r) {
    const RoadProfile& p = raw[r];
    if (!p.has_height) continue;
    const double g = grade_limit(options, network.roads[r].attributes);
    for (const int j : {network.roads[r].start_junction, network.roads[r].end_junction})
      junction_cap[j] = std::max(junction_cap[j], g);
    for (std::size_t i = 0; i + 1 < p.size(); ++i) {
      const std::size_t a = vars.of(r, i, p.size()), b = vars.of(r, i + 1, p.size());
      if (a == b) continue;
      const double ds = driven(p, i + 1) - driven(p, i);
      rows.add({{b, 1.0}, {a, -1.0}}, -g * ds, g * ds,
               {FitLimit::grade, static_cast<int>(r), static_cast<std::uint32_t>(i)});
    }
  }
  // The junction's plane is no steeper than the steepest road it joins, in every direction
  // (16 directions: |G| within 2 % of the cap), so neither are the connecting roads across it.
  for (const Junction& j : network.junctions) {
    if (j.ends.size() < 2) continue;
    const std::size_t gx = vars.gradient(j.id);
    for (int k = 0; k < kJunctionPlaneDirections; ++k) {
      const double a = std::numbers::pi * k / kJunctionPlaneDirections;
      rows.add({{gx, std::cos(a)}, {gx + 1, std::sin(a)}}, -junction_cap[j.id], junction_cap[j.id],
               {FitLimit::junction_grade, -1, static_cast<std::uint32_t>(j.id)});
    }
  }
  // Each road end lies across its junction's plane at tan(roll) = n . S G (junction_planes.h),
  // within its own cap (and max_cross_slope_percent): a plane as steep as the junction's
  // steepest road would roll a motorway link meeting it by that road's grade (Fuzz seed 188: a
  // link bridge rolled 0.33 rad under a 10 % cap).
  std::vector<Eigen::Matrix2d> share(network.junctions.size(), Eigen::Matrix2d::Zero());
  for (const Junction& j : network.junctions) {
    if (j.ends.size() < 2) continue;
    share[j.id] = detail::determined_share(network, j);
    const std::size_t gx = vars.gradient(j.id);
    for (const RoadEnd& e : j.ends) {
      const RoadProfile& p = raw[e.road];
      if (p.size() < 2) continue;
      // The road's direction where the model cuts it, whose heading takes the roll: a road that
      // bends within its trim leaves the node in another direction (NE: 11 % under an 8 % bound
      // with the node's).
      const double cut = cuts.end_trims.empty() ? 0.0 : cuts.end_trims[e.road][e.at_start ? 0 : 1];
      const double at = std::clamp(e.at_start ? cut : p.s.back() - cut, 0.0, p.s.back());
      const auto after = static_cast<std::size_t>(std::upper_bound(p.s.begin(), p.s.end(), at) - p.s.begin());
      const std::size_t a = std::min(std::max<std::size_t>(after, 1) - 1, p.size() - 2);
      const Vec2 d = p.xy[a + 1] - p.xy[a];
      if (!(d.norm() > 0.0)) continue;
      const Vec2 across = share[j.id].transpose() * Vec2(-d.y(), d.x()) / d.norm();
      if (!(across.norm() > 1e-9)) continue;
      double cap = grade_limit(options, network.roads[e.road].attributes);
      if (options.max_cross_slope_percent > 0.0) cap = std::min(cap, options.max_cross_slope_percent / 100.0);
      rows.add({{gx, across.x()}, {gx + 1, across.y()}}, -cap, cap,
               {FitLimit::cross_slope, e.road, static_cast<std::uint32_t>(e.at_start ? 0 : p.size() - 1)});
    }
  }

  // Across a junction the connecting roads run from one road's trimmed end to another's, and
  // those ends can lie much closer together than their paths through the junction's centre (the
  // two legs of a hairpin meeting a side road): between every two road ends, where the model
  // cuts the roads (cuts.end_trims; else the junction's widest half-width plus 2 m), the height
  // difference of their lane centres stays within a share of the steeper road's cap over their
  // plan distance, a lower bound of the connecting road's length. The stations either side of
  // the cuts (and the next, as curvature rows span three) go to the elimination order's block.
  std::unordered_map<std::size_t, std::pair<double, double>> pair_rows;  // row -> distance, cap
  std::vector<std::vector<std::size_t>> block_stations(network.roads.size());
  const auto half_width = [&](int road) {
    const WayAttributes& a = network.roads[road].attributes;
    return 0.5 * a.lane_width_m * (a.lanes_forward + a.lanes_backward);
  };
  // Where a road's end is cut for its junction: the stations a, a + 1 either side of the cut and
  // the cut's share t between them, its height (1 - t) z_a + t z_(a+1); the cut's place and the
  // left normal there.
  struct Cut {
    int road;
    int junction;  // the (member) junction the road ends at
    std::size_t a;
    double t;
    Vec2 xy, normal;
  };
  const auto cut_at = [&](int road, int junction, std::size_t a, double s_cut) {
    const RoadProfile& p = raw[road];
    const Vec2 d = p.xy[a + 1] - p.xy[a];
    const double t = std::clamp((s_cut - p.s[a]) / (p.s[a + 1] - p.s[a]), 0.0, 1.0);
    return Cut{road, junction, a, t, p.xy[a] + t * d, Vec2(-d.y(), d.x()) / std::max(d.norm(), 1e-9)};
  };
  // The offsets of a road's outermost lane centres from its reference line, and its middle.
  const auto lane_offsets = [&](int road) {
    const WayAttributes& a = network.roads[road].attributes;
    const double t = std::max(half_width(road) - 0.5 * a.lane_width_m, 0.0);
    return t > 0.0 ? std::vector<double>{-t, 0.0, t} : std::vector<double>{0.0};
  };
  // The junctions the model builds: a joined junction's connecting roads run between the ends of
  // all its members but the roads inside it (Fuzz seed 18: two junctions 3 m apart, each end
  // within its own junction's rows, and a connecting road from one to the other at 44 % under a
  // 35 % cap).
  std::vector<std::vector<int>> members(network.junctions.size());
  for (const Junction& j : network.junctions)
    members[cuts.joined_into.empty() ? j.id : cuts.joined_into[j.id]].push_back(j.id);
  const auto inside_joined = [&](int road) { return !cuts.absorbed.empty() && cuts.absorbed[road] != 0; };
  // Road ends roll with their junction's plane as the model rolls them; tan(roll) = n . S G, S
  // the share of the plane its roads determine (junction_planes.h). The rows take the rolls at an
  // intersection (three ends or more) and at every member of a joined junction: the model rolls a
  // two-end member's ends too, and Fuzz seed 188's 12 m bridge leaving one rolled 0.33 rad into a
  // connecting road at 44.7 % under a 35 % cap, past rows that took it for level.
  std::vector<std::uint8_t> in_joined(network.junctions.size(), 0);
  for (const std::vector<int>& group : members)
    if (group.size() > 1)
      for (const int m : group) in_joined[m] = 1;
  const auto rolled = [&](int junction) {
    const std::size_t ends = network.junctions[junction].ends.size();
    return ends >= 3 || (ends == 2 && in_joined[junction] != 0);
  };
  for (const std::vector<int>& group : members) {
    if (group.empty()) continue;
    std::vector<std::pair<RoadEnd, int>> ends;  // the end and its member junction
    for (const int m : group)
      for (const RoadEnd& e : network.junctions[m].ends)
        if (!inside_joined(e.road)) ends.emplace_back(e, m);
    // Two ends: where one road continues the other their own grade rows hold; where a transition
    // road bends from one to the other it cuts the corner (a sharp node: at 90 degrees 1.27 times
    // the polyline's grade), and the rows between their cut ends hold it.
    const Junction& first = network.junctions[group.front()];
    if (ends.size() < 2 ||
        (group.size() == 1 && ends.size() == 2 && !detail::needs_transition(network, first)))
      continue;
    double room = 0.0;
    for (const auto& [e, m] : ends) room = std::max(room, half_width(e.road) + kJunctionRoomMargin_m);
    std::vector<Cut> leaving;
    for (const auto& [e, m] : ends) {
      const RoadProfile& p = raw[e.road];
      if (!p.has_height || p.size() < 2) continue;
      // The cut lies between stations a and a + 1; on a short road a + 1 may be its other end.
      // Fuzz seed 92: a dead end trimmed to 1 m had no station past its cut and no rows, and a
      // connecting road from it climbed 46 % under a 35 % cap.
      const double cut = cuts.end_trims.empty() ? room : cuts.end_trims[e.road][e.at_start ? 0 : 1];
      const double other = cuts.end_trims.empty() ? 0.0 : cuts.end_trims[e.road][e.at_start ? 1 : 0];
      if (!(cut > 0.0) || cut + other >= p.s.back()) continue;  // the junctions take the whole road
      std::size_t a = 0;
      if (e.at_start) {
        a = static_cast<std::size_t>(std::lower_bound(p.s.begin(), p.s.end(), cut) - p.s.begin()) - 1;
      } else {
        a = static_cast<std::size_t>(std::upper_bound(p.s.begin(), p.s.end(), p.s.back() - cut) -
                                     p.s.begin()) -
            1;
      }
      a = std::min(a, p.size() - 2);
      leaving.push_back(cut_at(e.road, m, a, e.at_start ? cut : p.s.back() - cut));
      block_stations[e.road].push_back(a);
      block_stations[e.road].push_back(a + 1);
      if (e.at_start || a >= 1) block_stations[e.road].push_back(e.at_start ? a + 2 : a - 1);
    }
    // The rows hold between the lane centres at the cuts. At an intersection the model tilts
    // each road's cross-section there by the roll of its junction's plane, and the connecting
    // roads join those lane centres: every pair of them (outermost either side and the middle)
    // gets a row with its rolls. At the station beyond the cut and on the reference lines alone
    // the rows did not bound the connecting roads: the roads may climb at their cap over that
    // last metre while two ends leaving at an acute angle draw apart by much less, and the rolls
    // lift one lane and lower another (Fuzz seed 350: lane ends 2 m apart in height across a 4 m
    // connecting road, its grade 50 % under a 35 % cap). At a two-road node the transition road
    // checks its own lanes (too steep: a junction), and a row with rolls there lets the fit tilt
    // the plane to meet it, rolling the roads' ends more and their outer lanes past the cap
    // where the roll eases (RoadModelBuilder.ATransitionRoadCuttingASharpCorner: 36.8 % under
    // 35 %): one row on the reference lines, over the nearest lane centres' distance.
    for (std::size_t x = 0; x < leaving.size(); ++x) {
      for (std::size_t y = x + 1; y < leaving.size(); ++y) {
        const Cut& ca = leaving[x];
        const Cut& cb = leaving[y];
        if (ca.road == cb.road) continue;  // a loop's two ends: its own grade rows hold
        const std::size_t na = raw[ca.road].size(), nb = raw[cb.road].size();
        const double g = kPairGradeShare * std::max(grade_limit(options, network.roads[ca.road].attributes),
                                                    grade_limit(options, network.roads[cb.road].attributes));
        const FitRows::Tag tag{FitLimit::junction_grade, ca.road, static_cast<std::uint32_t>(ca.a)};
        const std::size_t a0 = vars.of(ca.road, ca.a, na), a1 = vars.of(ca.road, ca.a + 1, na);
        const std::size_t b0 = vars.of(cb.road, cb.a, nb), b1 = vars.of(cb.road, cb.a + 1, nb);
        const auto lane_point = [](const Cut& c, double t) { return Vec2(c.xy + t * c.normal); };
        if (!rolled(ca.junction) && !rolled(cb.junction)) {
          double d = kInf;
          for (const double ta : lane_offsets(ca.road))
            for (const double tb : lane_offsets(cb.road))
              d = std::min(d, (lane_point(cb, tb) - lane_point(ca, ta)).norm());
          d = std::max(d, kMinCurvatureSpacing);
          pair_rows[rows.size()] = {d, g};
          rows.add({{b0, 1.0 - cb.t}, {b1, cb.t}, {a0, ca.t - 1.0}, {a1, -ca.t}}, -g * d, g * d, tag);
          continue;
        }
        const auto roll = [&](const Cut& c) {
          return rolled(c.junction) ? Vec2(share[c.junction] * c.normal) : Vec2::Zero();
        };
        const Vec2 roll_a = roll(ca), roll_b = roll(cb);
        // The plane's columns (dz/dx, dz/dy); a junction without a plane that rolls its ends
        // has roll 0, its terms put on the end's own columns.
        const auto plane = [&](const Cut& c, std::size_t z0, std::size_t z1) {
          return rolled(c.junction) ? std::pair{vars.gradient(c.junction), vars.gradient(c.junction) + 1}
                                    : std::pair{z0, z1};
        };
        const auto [gax, gay] = plane(ca, a0, a1);
        const auto [gbx, gby] = plane(cb, b0, b1);
        // The pair's rows together weigh like the one row a pair had: 9 rows per pair at a 4-way
        // crossing at the full price outweighed the ground departure above them (a conflict
        // case left a road 2.7 m off the DEM under a 0.5 m bound to spare junction grades).
        const double share_of_pair =
            1.0 / static_cast<double>(lane_offsets(ca.road).size() * lane_offsets(cb.road).size());
        for (const double ta : lane_offsets(ca.road)) {
          for (const double tb : lane_offsets(cb.road)) {
            const double d = std::max((lane_point(cb, tb) - lane_point(ca, ta)).norm(), kMinCurvatureSpacing);
            pair_rows[rows.size()] = {d, g};
            // A junction's plane variables appear once per end; one plane, their terms add.
            rows.add({{b0, 1.0 - cb.t},
                      {b1, cb.t},
                      {a0, ca.t - 1.0},
                      {a1, -ca.t},
                      {gbx, tb * roll_b.x()},
                      {gby, tb * roll_b.y()},
                      {gax, -ta * roll_a.x()},
                      {gay, -ta * roll_a.y()}},
                     -g * d, g * d, tag, false, share_of_pair);
          }
        }
      }
    }
  }

  // Clearance rows where roads on different layers cross.
  const auto at = [&](int road, double s) {
    const RoadProfile& p = raw[road];
    const auto it = std::upper_bound(p.s.begin(), p.s.end(), s);
    std::size_t i = static_cast<std::size_t>(std::max<std::ptrdiff_t>(1, it - p.s.begin())) - 1;
    i = std::min(i, p.size() - 2);
    const double t = std::clamp((s - p.s[i]) / (p.s[i + 1] - p.s[i]), 0.0, 1.0);
    return std::make_pair(i,
                          std::array<std::pair<std::size_t, double>, 2>{
                              {{vars.of(road, i, p.size()), 1.0 - t}, {vars.of(road, i + 1, p.size()), t}}});
  };
  // The deck clears the whole paved width of the road beneath: at a crossing, rows between the
  // two roads at the centrelines' crossing and over each other's paved edges (each road's half
  // width over the sine of the crossing angle along the other, at most 3 widths), 3 x 3 pairs.
  const auto direction = [&](int road, std::size_t i) {
    const RoadProfile& p = raw[road];
    const Vec2 d = p.xy[std::min(i + 1, p.size() - 1)] - p.xy[std::min(i, p.size() - 2)];
    return Vec2(d / std::max(d.norm(), 1e-9));
  };
  for (const GradeSeparation& sep : result.separations) {
    if (!raw[sep.upper_road].has_height || !raw[sep.lower_road].has_height) continue;
    std::vector<double> along_upper{0.0}, along_lower{0.0};
    if (!sep.alongside) {
      const double sine = std::abs(cross(direction(sep.upper_road, at(sep.upper_road, sep.s_upper).first),
                                         direction(sep.lower_road, at(sep.lower_road, sep.s_lower).first)));
      const double ru =
          std::min(half_width(sep.lower_road) / std::max(sine, 1e-3), 3.0 * half_width(sep.lower_road));
      const double rl =
          std::min(half_width(sep.upper_road) / std::max(sine, 1e-3), 3.0 * half_width(sep.upper_road));
      along_upper = {-ru, 0.0, ru};
      along_lower = {-rl, 0.0, rl};
    }
    // One crossing is one place: its rows share the clearance's price, as a junction's pair of
    // ends shares the grade's (at the full price each, a crossing's 9 rows outweighed a junction
    // pair's at a ninth each, one priority level up: Fuzz seeds 58, 64 and 188 left junction
    // grades at 41-46 % under their 31.5 % bound to spare clearances, and their connecting roads
    // climbed past the cap).
    const double crossing_share = 1.0 / static_cast<double>(along_upper.size() * along_lower.size());
    for (const double a : along_upper) {
      for (const double b : along_lower) {
        const auto [iu, u] =
            at(sep.upper_road, std::clamp(sep.s_upper + a, 0.0, raw[sep.upper_road].s.back()));
        const auto [il, d] =
            at(sep.lower_road, std::clamp(sep.s_lower + b, 0.0, raw[sep.lower_road].s.back()));
        (void)il;
        rows.add({{u[0].first, u[0].second},
                  {u[1].first, u[1].second},
                  {d[0].first, -d[0].second},
                  {d[1].first, -d[1].second}},
                 sep.ordering_only ? kOrderingGap_m : options.clearance_m, kInf,
                 {FitLimit::clearance, sep.upper_road, static_cast<std::uint32_t>(iu)}, false,
                 crossing_share);
      }
    }
  }

  result.variables = n;
  result.constraints = rows.size();
  rows.move_into(qp, n);
  result.held_variables = hold_variables(network, raw, vars, options.holds, qp);
  SoftQpOptions solver;
  solver.max_iterations = options.max_iterations;
  solver.gap_tolerance = 1e-12;
  solver.ordering = elimination_order(network, raw, vars, result.separations, block_stations, qp.P, qp.A);
  solver.trace = options.trace;
  const SoftQpResult solution = solve_soft_qp(qp, solver);
  result.iterations = solution.iterations;
  result.converged = solution.converged;
  result.solver_status = solution.status + " (" + solution.method + ")";
  if (!solution.converged) {
    std::ostringstream msg;
    msg << "the profile fit did not converge (" << solution.status << " after " << solution.iterations
        << " interior-point iterations; stationarity " << solution.stationarity << ", gap " << solution.gap
        << "): this is a defect of relief, please report it";
    diagnostics.report(Severity::error, codes::kFitNotConverged, msg.str());
  }

  // Back to per-road profiles.
  result.profiles = raw;
  for (std::size_t r = 0; r < raw.size(); ++r) {
    RoadProfile& p = result.profiles[r];
    for (std::size_t i = 0; i < p.size(); ++i)
      p.z[i] = solution.x[static_cast<Eigen::Index>(vars.of(r, i, p.size()))];
  }
  result.junction_z.resize(network.junctions.size());
  result.junction_gradient.assign(network.junctions.size(), Vec2::Zero());
  for (const Junction& j : network.junctions) {
    result.junction_z[j.id] = solution.x[static_cast<Eigen::Index>(vars.junction(j.id))];
    if (j.ends.size() < 2) continue;
    const auto g = static_cast<Eigen::Index>(vars.gradient(j.id));
    result.junction_gradient[j.id] = Vec2(solution.x[g], solution.x[g + 1]);
  }
  update_clearances(result.separations, result.profiles);
  // The limits left violated: the worst place per road (or junction) and limit.
  std::map<std::pair<int, int>, FitViolation> worst;  // (limit, road or -1 - junction)
  for (std::size_t r = 0; r < rows.size(); ++r) {
    const double excess = solution.violation[static_cast<Eigen::Index>(r)];
    result.max_violation_m = std::max(result.max_violation_m, excess);
    if (excess <= options.violation_tolerance_m) continue;
    const FitRows::Tag& tag = rows.tag(r);
    const int owner = tag.road >= 0 ? tag.road : -1 - static_cast<int>(tag.station);
    FitViolation& v = worst[{static_cast<int>(tag.limit), owner}];
    ++v.places;
    if (excess <= v.excess_m) continue;
    v.limit = tag.limit;
    v.excess_m = excess;
    v.road = tag.road;
    const double value = solution.row_values[static_cast<Eigen::Index>(r)];
    if (tag.road >= 0) {
      const Road& road = network.roads[tag.road];
      const RoadProfile& p = raw[tag.road];
      v.s_m = p.s[tag.station];
      v.xy = p.xy[tag.station];
      v.osm_way_id = road.osm_way_ids.empty() ? 0 : road.osm_way_ids.front();
      switch (tag.limit) {
        case FitLimit::ground_departure:
          v.value = std::abs(result.profiles[tag.road].z[tag.station] - p.z[tag.station]);
          v.bound = options.max_ground_departure_m;
          break;
        case FitLimit::grade: {
          const double ds = driven(p, tag.station + 1) - driven(p, tag.station);
          v.value = 100.0 * std::abs(value) / ds;
          v.bound = 100.0 * grade_limit(options, road.attributes);
          v.s_m += 0.5 * ds;
          break;
        }
        case FitLimit::clearance:
          v.value = value;
          v.bound = qp.lower[static_cast<Eigen::Index>(r)];
          break;
        case FitLimit::cross_slope:
          v.value = 100.0 * std::abs(value);
          v.bound = 100.0 * qp.upper[static_cast<Eigen::Index>(r)];
          break;
        case FitLimit::vertical_curve: {
          const double h1 = driven(p, tag.station) - driven(p, tag.station - 1);
          const double h2 = driven(p, tag.station + 1) - driven(p, tag.station);
          const double h = 0.5 * (h1 + h2);
          v.value = value / (h * h);
          const auto [crest, sag] = curvature_bounds(road, options);
          v.bound = v.value < 0.0 ? -crest : sag;
          break;
        }
        case FitLimit::junction_grade: {  // between two road ends across a junction
          const auto [d, g] = pair_rows.at(r);
          v.value = 100.0 * std::abs(value) / d;
          v.bound = 100.0 * g;
          break;
        }
      }
    } else {
      const Junction& j = network.junctions[tag.station];
      v.junction = j.id;
      v.xy = j.position;
      const std::size_t gx = vars.gradient(j.id);
      v.value = 100.0 * std::hypot(solution.x[static_cast<Eigen::Index>(gx)],
                                   solution.x[static_cast<Eigen::Index>(gx + 1)]);
      v.bound = 100.0 * junction_cap[j.id];
    }
  }
  for (auto& [key, v] : worst) result.violations.push_back(v);
  std::stable_sort(result.violations.begin(), result.violations.end(),
                   [](const FitViolation& a, const FitViolation& b) {
                     if (a.limit != b.limit) return a.limit < b.limit;
                     return a.excess_m > b.excess_m;
                   });
  for (const FitViolation& v : result.violations) {
    Diagnostic d;
    d.code = codes::kFitLimitViolated;
    d.severity = Severity::warning;
    std::ostringstream msg;
    msg.precision(3);
    msg << std::fixed;
    if (v.road >= 0) {
      d.road_id = v.road;
      if (v.osm_way_id != 0) d.osm_way_id = v.osm_way_id;
      msg << "road " << v.road << " (OSM way " << v.osm_way_id << ") at s = " << v.s_m << " m";
    } else {
      msg << "junction " << v.junction;
    }
    msg << " (" << v.xy.x() << ", " << v.xy.y() << "): " << to_string(v.limit) << " " << v.value
        << " against " << v.bound << ", " << v.excess_m << " m over, at " << v.places
        << " place(s); a higher-priority limit or the network's geometry leaves no room";
    d.message = msg.str();
    diagnostics.report(std::move(d));
  }
  return result;
}

}  // namespace relief
