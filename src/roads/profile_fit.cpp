#include "relief/roads/profile_fit.h"

#include <Eigen/OrderingMethods>
#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <numeric>
#include <sstream>

#include "relief/core/errors.h"

namespace relief {
namespace {

using SpMat = Eigen::SparseMatrix<double>;
using Triplet = Eigen::Triplet<double>;
using Vec = Eigen::VectorXd;

constexpr double kMinCurvatureSpacing = 0.5;  // m; closer stations are not used for z'' rows
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kPinnedReach = 30.0;        // m along a road under a crossing
constexpr double kPinnedStiffness = 1000.0;  // data weight factor there

// Index of every sample's height variable: interior samples own one, road ends share their
// junction's variable.
class VariableMap {
 public:
  explicit VariableMap(const RoadNetwork& network, const std::vector<RoadProfile>& profiles)
      : network_(network), junction_base_(0) {
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
  std::size_t junction_base_;
  std::vector<std::size_t> gradient_index_;
  std::size_t count_ = 0;
};

// Linear constraint rows l <= A x <= u, assembled as triplets.
struct Constraints {
  std::vector<Triplet> entries;
  std::vector<double> lower, upper;
  /// Rows that couple variables P does not already couple (clearances, two-station roads).
  std::vector<Triplet> extra_pattern;

  void add(std::initializer_list<std::pair<std::size_t, double>> row, double lo, double hi,
           bool within_pattern_of_p = true) {
    const auto r = static_cast<int>(lower.size());
    for (const auto& [col, value] : row) {
      entries.emplace_back(r, static_cast<int>(col), value);
      if (!within_pattern_of_p) extra_pattern.emplace_back(r, static_cast<int>(col), 1.0);
    }
    lower.push_back(lo);
    upper.push_back(hi);
  }
};

// Second divided difference z'' at the middle of three stations spaced h1, h2.
std::array<double, 3> curvature_row(double h1, double h2) {
  h1 = std::max(h1, kMinCurvatureSpacing);
  h2 = std::max(h2, kMinCurvatureSpacing);
  return {2.0 / (h1 * (h1 + h2)), -2.0 / (h1 * h2), 2.0 / (h2 * (h1 + h2))};
}

bool is_structure(const Road& road) {
  return road.attributes.bridge || road.attributes.tunnel;
}

struct Triple {
  std::size_t a, b, c;
  double h1, h2;
  double lambda;  // smoothing weight of the road it lies on
};

// The smoothness triples: consecutive stations of each road.
// lambda = (cutoff / 2 pi)^4: a smoothing spline halves the amplitude at the cutoff wavelength.
double smoothing_weight(double cutoff_wavelength_m) {
  return std::pow(cutoff_wavelength_m / (2.0 * std::numbers::pi), 4.0);
}

std::vector<Triple> smoothness_triples(const RoadNetwork& network, const std::vector<RoadProfile>& profiles,
                                       const VariableMap& vars, const ProfileFitOptions& options) {
  const double ground = smoothing_weight(options.cutoff_wavelength_m);
  const double structure = smoothing_weight(options.structure_cutoff_wavelength_m);
  std::vector<Triple> triples;
  for (std::size_t r = 0; r < profiles.size(); ++r) {
    const RoadProfile& p = profiles[r];
    const std::size_t n = p.size();
    const double lambda = is_structure(network.roads[r]) ? structure : ground;
    for (std::size_t i = 1; i + 1 < n; ++i) {
      triples.push_back({vars.of(r, i - 1, n), vars.of(r, i, n), vars.of(r, i + 1, n), p.s[i] - p.s[i - 1],
                         p.s[i + 1] - p.s[i], lambda});
    }
  }
  return triples;
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
      if (n < 3) continue;  // a two-station road has no interior station
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
      d.code = "fit.unanchored_structure";
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

using Permutation = Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int>;

// Fill-reducing elimination order. Road interiors come first, each road in station order: a
// chain eliminated end to end fills in only its two junctions' variables, so that part costs
// O(samples). The junction block left behind (heights and tangent planes, coupled along every
// road and at every grade separation) is small and ordered by AMD. Running AMD on the whole
// matrix gives the same fill but takes seconds on millions of stations.
Permutation elimination_order(const RoadNetwork& network, const VariableMap& vars,
                              const std::vector<GradeSeparation>& separations) {
  const auto base = static_cast<int>(vars.junction_base());
  const auto nj = static_cast<int>(vars.count()) - base;
  // Variables of the junction block that a road couples once its interior is eliminated.
  const auto road_block = [&](int road, std::vector<int>& out) {
    for (const int j : {network.roads[road].start_junction, network.roads[road].end_junction}) {
      out.push_back(static_cast<int>(vars.junction(j)) - base);
      if (network.junctions[j].ends.size() >= 2) {
        out.push_back(static_cast<int>(vars.gradient(j)) - base);
        out.push_back(static_cast<int>(vars.gradient(j)) + 1 - base);
      }
    }
  };
  std::vector<Triplet> pattern;
  std::vector<int> block;
  const auto connect_all = [&] {
    for (const int a : block)
      for (const int b : block) pattern.emplace_back(a, b, 1.0);
  };
  for (const Road& road : network.roads) {
    block.clear();
    road_block(road.id, block);
    connect_all();
  }
  for (const GradeSeparation& sep : separations) {
    block.clear();
    road_block(sep.upper_road, block);
    road_block(sep.lower_road, block);
    connect_all();
  }
  SpMat junction_pattern(nj, nj);
  junction_pattern.setFromTriplets(pattern.begin(), pattern.end());
  Permutation amd_inverse;
  Eigen::AMDOrdering<int>()(junction_pattern, amd_inverse);
  const Permutation amd = amd_inverse.inverse();  // old junction-block index -> new

  Permutation order(static_cast<int>(vars.count()));
  for (int i = 0; i < base; ++i) order.indices()[i] = i;
  for (int k = 0; k < nj; ++k) order.indices()[base + k] = base + amd.indices()[k];
  return order;
}

// min 1/2 x'Px + q'x  s.t.  l <= Ax <= u, by a primal active set with exact solves: rows found
// violated are enforced by a stiff quadratic penalty  mu/2 (a.x - bound)^2,  rows whose penalty
// pulls the wrong way (the bound is not binding) are released, and the system is refactorised
// (numerically only: the sparsity pattern of P + A'A is analysed once). A few rounds suffice
// because the active rows are few (grade caps, clearances) and every solve is exact, which the
// long, weakly determined bridge and tunnel decks need (ADMM crawls on them).
struct ActiveSetResult {
  Vec x;
  int rounds = 0;
  bool converged = false;
};

ActiveSetResult solve_active_set(const SpMat& P_original, const Vec& q_original, const SpMat& A_original,
                                 const SpMat& extra_pattern, const Vec& l, const Vec& u,
                                 const Permutation& order, double tolerance, int max_rounds) {
  // Work in the elimination order: x_new = order * x.
  SpMat P;
  P = P_original.selfadjointView<Eigen::Lower>().twistedBy(order);
  const Vec q = order * q_original;
  const SpMat A = A_original * order.transpose();
  // The penalty is stiff against the largest curvature weight, so enforced rows are met to
  // ~1e-7 of the forces involved; polish() does the rest.
  const double mu = 1e7 * std::max(1.0, P.diagonal().maxCoeff());
  const auto rows = static_cast<Eigen::Index>(A.rows());
  Vec weight = Vec::Zero(rows);  // mu on active rows, 0 elsewhere
  Vec bound = Vec::Zero(rows);

  // Every round's matrix gets the pattern of P + A'A (the factorisation needs one pattern), with
  // only the active rows' values.
  Eigen::SimplicialLDLT<SpMat, Eigen::Lower, Eigen::NaturalOrdering<int>> ldlt;
  SpMat base;
  const SpMat extra = extra_pattern * order.transpose();
  base = P + 0.0 * SpMat(extra.transpose() * extra);
  ldlt.analyzePattern(base);
  ActiveSetResult out;
  const Eigen::SparseMatrix<double, Eigen::RowMajor> A_rows = A;
  std::vector<Triplet> active_entries;
  const int freeze_after = std::clamp(max_rounds / 2, 1, 8);  // then only add rows: no cycling
  for (int round = 1; round <= max_rounds; ++round) {
    // Only the active rows enter the system: sqrt(mu) a_r, so that Aa'Aa = sum mu a_r a_r'.
    active_entries.clear();
    Vec active_rhs = Vec::Zero(P.rows());
    int k = 0;
    for (Eigen::Index r = 0; r < rows; ++r) {
      if (weight[r] == 0.0) continue;
      for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(A_rows, r); it; ++it) {
        active_entries.emplace_back(k, static_cast<int>(it.col()), std::sqrt(weight[r]) * it.value());
        active_rhs[it.col()] += weight[r] * bound[r] * it.value();
      }
      ++k;
    }
    SpMat active(k, P.cols());
    active.setFromTriplets(active_entries.begin(), active_entries.end());
    const SpMat M = base + SpMat(active.transpose() * active);
    ldlt.factorize(M);
    if (ldlt.info() != Eigen::Success)
      throw Error("profile fit: the normal equations could not be factorised");
    out.x = ldlt.solve(active_rhs - q);
    out.rounds = round;
    const Vec ax = A * out.x;
    bool changed = false;
    for (Eigen::Index r = 0; r < rows; ++r) {
      if (weight[r] > 0.0) {
        // Release a row whose bound is not binding: the solution sits inside it.
        const bool at_upper = bound[r] == u[r];
        const double inside = at_upper ? bound[r] - ax[r] : ax[r] - bound[r];
        if (round < freeze_after && inside > tolerance) {
          weight[r] = 0.0;
          changed = true;
        }
      } else if (ax[r] > u[r] + tolerance) {
        weight[r] = mu;
        bound[r] = u[r];
        changed = true;
      } else if (ax[r] < l[r] - tolerance) {
        weight[r] = mu;
        bound[r] = l[r];
        changed = true;
      }
    }
    if (!changed) {
      out.converged = true;
      break;
    }
  }
  out.x = order.transpose() * out.x;
  return out;
}

// Cyclic projections onto the violated rows, to leave no violation larger than rounding.
double polish(const SpMat& A, const Vec& l, const Vec& u, Vec& x, int sweeps) {
  Eigen::SparseMatrix<double, Eigen::RowMajor> rows = A;
  Vec norms(rows.rows());
  for (int r = 0; r < rows.rows(); ++r) norms[r] = rows.row(r).squaredNorm();
  double worst = 0.0;
  for (int sweep = 0; sweep < sweeps; ++sweep) {
    worst = 0.0;
    for (int r = 0; r < rows.rows(); ++r) {
      const double v = rows.row(r).dot(x);
      double target = v;
      if (v < l[r]) target = l[r];
      if (v > u[r]) target = u[r];
      const double excess = std::abs(target - v);
      if (excess <= 1e-9 || norms[r] == 0.0) continue;
      worst = std::max(worst, excess);
      const double step = (target - v) / norms[r];
      for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(rows, r); it; ++it) {
        x[it.col()] += step * it.value();
      }
    }
    if (worst <= 1e-9) break;
  }
  // Report what is left after the last sweep.
  const Vec Ax = A * x;
  double left = 0.0;
  for (int r = 0; r < Ax.size(); ++r) left = std::max({left, l[r] - Ax[r], Ax[r] - u[r]});
  return left;
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
  return (highway ? options.fidelity_highway_max_grade_percent : options.fidelity_max_grade_percent) / 100.0;
}

ProfileFitResult fit_profiles(const RoadNetwork& network, const std::vector<RoadProfile>& raw,
                              const ProfileFitOptions& options, Diagnostics& diagnostics) {
  if (raw.size() != network.roads.size())
    throw InvalidInput("fit_profiles: one profile per road is required");
  const VariableMap vars(network, raw);
  const std::size_t n = vars.count();

  // Data term: trapezoidal weights (metres of road per sample), none on structures; a tiny
  // weight everywhere keeps P positive definite where a component has no ground at all.
  Vec weight = Vec::Constant(static_cast<Eigen::Index>(n), 1e-6);
  Vec target = Vec::Zero(static_cast<Eigen::Index>(n));
  Vec target_weight = Vec::Zero(static_cast<Eigen::Index>(n));
  Vec initial = Vec::Zero(static_cast<Eigen::Index>(n));
  Vec initial_count = Vec::Zero(static_cast<Eigen::Index>(n));
  const std::vector<std::uint8_t> with_data = roads_with_data(network, diagnostics);
  ProfileFitResult result;
  result.separations = find_grade_separations(network, raw);
  // A road on the ground under a bridge stays on the ground: near a crossing its data term is
  // much stiffer than the deck, so the clearance is won by lifting the deck.
  std::vector<std::vector<double>> pinned(raw.size());
  for (const GradeSeparation& sep : result.separations) pinned[sep.lower_road].push_back(sep.s_lower);
  const auto stiffness = [&](std::size_t r, double s) {
    for (double at : pinned[r])
      if (std::abs(s - at) <= kPinnedReach) return kPinnedStiffness;
    return 1.0;
  };
  for (std::size_t r = 0; r < raw.size(); ++r) {
    const RoadProfile& p = raw[r];
    const bool ground = with_data[r] && p.has_height;
    for (std::size_t i = 0; i < p.size(); ++i) {
      const auto v = static_cast<Eigen::Index>(vars.of(r, i, p.size()));
      const double left = i > 0 ? p.s[i] - p.s[i - 1] : 0.0;
      const double right = i + 1 < p.size() ? p.s[i + 1] - p.s[i] : 0.0;
      const double w = ground ? 0.5 * (left + right) * stiffness(r, p.s[i]) : 0.0;
      weight[v] += w;
      target_weight[v] += w * p.z[i];
      initial[v] += p.z[i];
      initial_count[v] += 1.0;
    }
  }
  for (Eigen::Index v = 0; v < static_cast<Eigen::Index>(n); ++v) {
    initial[v] /= std::max(1.0, initial_count[v]);
    target[v] = weight[v] > 1e-6 ? (target_weight[v] + 1e-6 * initial[v]) / weight[v] : initial[v];
  }

  // Smoothness: lambda * sum (z'')^2 ds, with lambda from the cutoff wavelength.
  const double lambda = smoothing_weight(options.cutoff_wavelength_m);
  const std::vector<Triple> triples = smoothness_triples(network, raw, vars, options);
  std::vector<Triplet> p_entries;
  p_entries.reserve(n + 9 * triples.size());
  for (std::size_t v = 0; v < n; ++v)
    p_entries.emplace_back(static_cast<int>(v), static_cast<int>(v), weight[static_cast<Eigen::Index>(v)]);
  Constraints cons;
  for (const Triple& t : triples) {
    const auto c = curvature_row(t.h1, t.h2);
    const double w =
        t.lambda * 0.5 * (std::max(t.h1, kMinCurvatureSpacing) + std::max(t.h2, kMinCurvatureSpacing));
    const std::array<std::size_t, 3> idx{t.a, t.b, t.c};
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 3; ++k)
        p_entries.emplace_back(static_cast<int>(idx[i]), static_cast<int>(idx[k]), w * c[i] * c[k]);
    if (options.max_curvature_per_m > 0.0 && t.h1 >= kMinCurvatureSpacing && t.h2 >= kMinCurvatureSpacing) {
      cons.add({{t.a, c[0]}, {t.b, c[1]}, {t.c, c[2]}}, -options.max_curvature_per_m,
               options.max_curvature_per_m);
    }
  }
  add_junction_planes(network, raw, vars, lambda, p_entries);
  SpMat P(static_cast<int>(n), static_cast<int>(n));
  P.setFromTriplets(p_entries.begin(), p_entries.end());
  const Vec q = -weight.cwiseProduct(target);

  // Grade rows on every segment.
  for (std::size_t r = 0; r < raw.size(); ++r) {
    const RoadProfile& p = raw[r];
    const double g = grade_limit(options, network.roads[r].attributes.highway);
    for (std::size_t i = 0; i + 1 < p.size(); ++i) {
      const std::size_t a = vars.of(r, i, p.size()), b = vars.of(r, i + 1, p.size());
      if (a == b) continue;
      const double ds = p.s[i + 1] - p.s[i];
      cons.add({{b, 1.0}, {a, -1.0}}, -g * ds, g * ds, /*within_pattern_of_p=*/p.size() >= 3);
    }
  }

  // Clearance rows where roads on different layers cross.
  for (const GradeSeparation& sep : result.separations) {
    const auto at = [&](int road, double s) {
      const RoadProfile& p = raw[road];
      const auto it = std::upper_bound(p.s.begin(), p.s.end(), s);
      std::size_t i = static_cast<std::size_t>(std::max<std::ptrdiff_t>(1, it - p.s.begin())) - 1;
      i = std::min(i, p.size() - 2);
      const double t = std::clamp((s - p.s[i]) / (p.s[i + 1] - p.s[i]), 0.0, 1.0);
      return std::array<std::pair<std::size_t, double>, 2>{
          {{vars.of(road, i, p.size()), 1.0 - t}, {vars.of(road, i + 1, p.size()), t}}};
    };
    const auto u = at(sep.upper_road, sep.s_upper);
    const auto d = at(sep.lower_road, sep.s_lower);
    cons.add({{u[0].first, u[0].second},
              {u[1].first, u[1].second},
              {d[0].first, -d[0].second},
              {d[1].first, -d[1].second}},
             options.clearance_m, kInf, /*within_pattern_of_p=*/false);
  }

  SpMat A(static_cast<int>(cons.lower.size()), static_cast<int>(n));
  A.setFromTriplets(cons.entries.begin(), cons.entries.end());
  SpMat extra(static_cast<int>(cons.lower.size()), static_cast<int>(n));
  extra.setFromTriplets(cons.extra_pattern.begin(), cons.extra_pattern.end());
  const Vec l = Eigen::Map<const Vec>(cons.lower.data(), static_cast<Eigen::Index>(cons.lower.size()));
  const Vec u = Eigen::Map<const Vec>(cons.upper.data(), static_cast<Eigen::Index>(cons.upper.size()));

  // The penalty leaves enforced rows violated by ~1e-5 m; aim a little inside every bound so
  // that the result meets the real ones.
  constexpr double kMargin = 2e-4;  // m
  const Vec l_aim = (l.array() + kMargin).min(0.5 * (l + u).array());
  const Vec u_aim = (u.array() - kMargin).max(0.5 * (l + u).array());
  const Permutation order = elimination_order(network, vars, result.separations);
  ActiveSetResult solution =
      solve_active_set(P, q, A, extra, l_aim, u_aim, order, options.tolerance_m, options.max_iterations);
  result.max_violation_m = polish(A, l, u, solution.x, 1000);
  result.iterations = solution.rounds;
  result.converged = solution.converged;
  result.variables = n;
  result.constraints = cons.lower.size();
  if (!solution.converged) {
    diagnostics.report(Severity::warning, "fit.not_converged",
                       "the profile fit's active set still changed after " + std::to_string(solution.rounds) +
                           " rounds; the result is the last solve, polished onto the constraints");
  }
  if (result.max_violation_m > 1e-3) {
    std::ostringstream msg;
    msg << "the profile constraints cannot all be met: largest violation " << result.max_violation_m
        << " m (a clearance or grade limit that the network's geometry does not allow)";
    diagnostics.report(Severity::warning, "fit.infeasible", msg.str());
  }

  // Back to per-road profiles.
  result.profiles = raw;
  for (std::size_t r = 0; r < raw.size(); ++r) {
    RoadProfile& p = result.profiles[r];
    for (std::size_t i = 0; i < p.size(); ++i)
      p.z[i] = solution.x[static_cast<Eigen::Index>(vars.of(r, i, p.size()))];
  }
  result.junction_z.resize(network.junctions.size());
  for (std::size_t j = 0; j < network.junctions.size(); ++j) {
    result.junction_z[j] = solution.x[static_cast<Eigen::Index>(vars.junction(static_cast<int>(j)))];
  }
  update_clearances(result.separations, result.profiles);
  return result;
}

}  // namespace relief
