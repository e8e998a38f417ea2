#include "relief/roads/profile_fit.h"

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

#include "relief/core/errors.h"

namespace relief {
namespace {

using SpMat = Eigen::SparseMatrix<double>;
using Triplet = Eigen::Triplet<double>;
using Vec = Eigen::VectorXd;

constexpr double kMinCurvatureSpacing = 0.5;  // m; closer stations are not used for z'' rows
constexpr double kInf = std::numeric_limits<double>::infinity();

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

  std::size_t add(std::initializer_list<std::pair<std::size_t, double>> row, double lo, double hi) {
    const auto r = static_cast<int>(lower.size());
    for (const auto& [col, value] : row) entries.emplace_back(r, static_cast<int>(col), value);
    lower.push_back(lo);
    upper.push_back(hi);
    return lower.size() - 1;
  }
};

// Second divided difference z'' at the middle of three stations spaced h1, h2.
std::array<double, 3> curvature_row(double h1, double h2) {
  h1 = std::max(h1, kMinCurvatureSpacing);
  h2 = std::max(h2, kMinCurvatureSpacing);
  return {2.0 / (h1 * (h1 + h2)), -2.0 / (h1 * h2), 2.0 / (h2 * (h1 + h2))};
}

struct Triple {
  std::size_t a, b, c;
  double h1, h2;
};

// The smoothness triples: consecutive stations of each road.
std::vector<Triple> smoothness_triples(const std::vector<RoadProfile>& profiles, const VariableMap& vars) {
  std::vector<Triple> triples;
  for (std::size_t r = 0; r < profiles.size(); ++r) {
    const RoadProfile& p = profiles[r];
    const std::size_t n = p.size();
    for (std::size_t i = 1; i + 1 < n; ++i) {
      triples.push_back({vars.of(r, i - 1, n), vars.of(r, i, n), vars.of(r, i + 1, n),
                         p.s[i] - p.s[i - 1], p.s[i + 1] - p.s[i]});
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

bool is_structure(const Road& road) { return road.attributes.bridge || road.attributes.tunnel; }

// OSQP-style ADMM for  min 1/2 x'Px + q'x  s.t.  l <= Ax <= u.
struct AdmmResult {
  Vec x;
  int iterations = 0;
  bool converged = false;
};

AdmmResult solve_admm(const SpMat& P, const Vec& q, const SpMat& A, const Vec& l, const Vec& u,
                      const Vec& x0, double eps, int max_iterations) {
  const double sigma = 1e-6, alpha = 1.6;
  const SpMat At = A.transpose();
  const SpMat AtA = At * A;
  double rho = std::max(1e-3, 0.1 * P.diagonal().mean());
  SpMat I(P.rows(), P.cols());
  I.setIdentity();

  Eigen::SimplicialLDLT<SpMat> ldlt;
  const auto factor = [&] {
    ldlt.compute(P + sigma * I + rho * AtA);
    if (ldlt.info() != Eigen::Success) throw Error("profile fit: the KKT matrix could not be factorised");
  };
  factor();

  AdmmResult out;
  Vec x = x0;
  Vec z = (A * x).cwiseMax(l).cwiseMin(u);
  Vec y = Vec::Zero(A.rows());
  for (int k = 1; k <= max_iterations; ++k) {
    const Vec rhs = sigma * x - q + At * (rho * z - y);
    const Vec x_tilde = ldlt.solve(rhs);
    const Vec z_tilde = A * x_tilde;
    x = alpha * x_tilde + (1.0 - alpha) * x;
    const Vec z_relaxed = alpha * z_tilde + (1.0 - alpha) * z;
    const Vec z_new = (z_relaxed + y / rho).cwiseMax(l).cwiseMin(u);
    y += rho * (z_relaxed - z_new);
    z = z_new;
    out.iterations = k;

    if (k % 10 != 0 && k != max_iterations) continue;
    const Vec Ax = A * x;
    const Vec Px = P * x;
    const Vec Aty = At * y;
    const double r_prim = (Ax - z).lpNorm<Eigen::Infinity>();
    const double r_dual = (Px + q + Aty).lpNorm<Eigen::Infinity>();
    const double scale_prim = std::max(Ax.lpNorm<Eigen::Infinity>(), z.lpNorm<Eigen::Infinity>());
    const double scale_dual = std::max({Px.lpNorm<Eigen::Infinity>(), Aty.lpNorm<Eigen::Infinity>(),
                                        q.lpNorm<Eigen::Infinity>()});
    // Primal tolerance in metres; dual tolerance relative to the objective's gradient.
    if (r_prim <= eps && r_dual <= eps * std::max(1.0, 1e-3 * scale_dual)) {
      out.converged = true;
      break;
    }
    if (k % 50 == 0) {
      // Residual balancing (OSQP): refactor when rho should change by more than 5x.
      const double ratio = (r_prim / std::max(scale_prim, 1e-12)) / (r_dual / std::max(scale_dual, 1e-12));
      const double new_rho = std::clamp(rho * std::sqrt(ratio), 1e-6, 1e8);
      if (new_rho > 5.0 * rho || new_rho < 0.2 * rho) {
        y *= 1.0;  // y is in absolute units; rho only scales the penalty
        rho = new_rho;
        factor();
      }
    }
  }
  out.x = x;
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
  const double percent = options.policy == GradePolicy::design ? options.limits.limit_for(cls)
                                                               : options.fidelity_max_grade_percent;
  return percent / 100.0;
}

ProfileFitResult fit_profiles(const RoadNetwork& network, const std::vector<RoadProfile>& raw,
                              const ProfileFitOptions& options, Diagnostics& diagnostics) {
  if (raw.size() != network.roads.size()) throw InvalidInput("fit_profiles: one profile per road is required");
  const VariableMap vars(network, raw);
  const std::size_t n = vars.count();

  // Data term: trapezoidal weights (metres of road per sample), none on structures; a tiny
  // weight everywhere keeps P positive definite where a component has no ground at all.
  Vec weight = Vec::Constant(static_cast<Eigen::Index>(n), 1e-6);
  Vec target = Vec::Zero(static_cast<Eigen::Index>(n));
  Vec target_weight = Vec::Zero(static_cast<Eigen::Index>(n));
  Vec initial = Vec::Zero(static_cast<Eigen::Index>(n));
  Vec initial_count = Vec::Zero(static_cast<Eigen::Index>(n));
  for (std::size_t r = 0; r < raw.size(); ++r) {
    const RoadProfile& p = raw[r];
    const bool ground = !is_structure(network.roads[r]) && p.has_height;
    for (std::size_t i = 0; i < p.size(); ++i) {
      const auto v = static_cast<Eigen::Index>(vars.of(r, i, p.size()));
      const double left = i > 0 ? p.s[i] - p.s[i - 1] : 0.0;
      const double right = i + 1 < p.size() ? p.s[i + 1] - p.s[i] : 0.0;
      const double w = ground ? 0.5 * (left + right) : 0.0;
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
  const double lambda = std::pow(options.cutoff_wavelength_m / (2.0 * std::numbers::pi), 4.0);
  const std::vector<Triple> triples = smoothness_triples(raw, vars);
  std::vector<Triplet> p_entries;
  p_entries.reserve(n + 9 * triples.size());
  for (std::size_t v = 0; v < n; ++v) p_entries.emplace_back(static_cast<int>(v), static_cast<int>(v), weight[static_cast<Eigen::Index>(v)]);
  Constraints cons;
  for (const Triple& t : triples) {
    const auto c = curvature_row(t.h1, t.h2);
    const double w = lambda * 0.5 * (std::max(t.h1, kMinCurvatureSpacing) + std::max(t.h2, kMinCurvatureSpacing));
    const std::array<std::size_t, 3> idx{t.a, t.b, t.c};
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 3; ++k)
        p_entries.emplace_back(static_cast<int>(idx[i]), static_cast<int>(idx[k]), w * c[i] * c[k]);
    if (options.max_curvature_per_m > 0.0 && t.h1 >= kMinCurvatureSpacing && t.h2 >= kMinCurvatureSpacing) {
      cons.add({{t.a, c[0]}, {t.b, c[1]}, {t.c, c[2]}}, -options.max_curvature_per_m, options.max_curvature_per_m);
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
      cons.add({{b, 1.0}, {a, -1.0}}, -g * ds, g * ds);
    }
  }

  // Clearance rows where roads on different layers cross.
  ProfileFitResult result;
  result.separations = find_grade_separations(network, raw);
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
    cons.add({{u[0].first, u[0].second}, {u[1].first, u[1].second}, {d[0].first, -d[0].second},
              {d[1].first, -d[1].second}},
             options.clearance_m, kInf);
  }

  SpMat A(static_cast<int>(cons.lower.size()), static_cast<int>(n));
  A.setFromTriplets(cons.entries.begin(), cons.entries.end());
  const Vec l = Eigen::Map<const Vec>(cons.lower.data(), static_cast<Eigen::Index>(cons.lower.size()));
  const Vec u = Eigen::Map<const Vec>(cons.upper.data(), static_cast<Eigen::Index>(cons.upper.size()));

  AdmmResult solution = solve_admm(P, q, A, l, u, initial, options.tolerance_m, options.max_iterations);
  result.max_violation_m = polish(A, l, u, solution.x, 200);
  result.iterations = solution.iterations;
  result.converged = solution.converged;
  result.variables = n;
  result.constraints = cons.lower.size();
  if (!solution.converged) {
    diagnostics.report(Severity::warning, "fit.not_converged",
                       "the profile fit stopped after " + std::to_string(solution.iterations) +
                           " iterations without meeting its tolerance; the result is the last iterate");
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
    for (std::size_t i = 0; i < p.size(); ++i) p.z[i] = solution.x[static_cast<Eigen::Index>(vars.of(r, i, p.size()))];
  }
  result.junction_z.resize(network.junctions.size());
  for (std::size_t j = 0; j < network.junctions.size(); ++j) {
    result.junction_z[j] = solution.x[static_cast<Eigen::Index>(vars.junction(static_cast<int>(j)))];
  }
  update_clearances(result.separations, result.profiles);
  return result;
}

}  // namespace relief
