#include "geometry/soft_qp_fixed.h"

#include <Eigen/SparseCore>

#include <cmath>
#include <limits>
#include <vector>

namespace relief::detail {

SoftQpResult solve_with_fixed_variables(const SoftQp& problem, const SoftQpOptions& options) {
  using Triplet = Eigen::Triplet<double>;
  const auto n = static_cast<int>(problem.P.rows());
  const auto m = static_cast<int>(problem.A.rows());
  // Free variables renumbered in order; the held values, 0 where free.
  std::vector<int> free_index(static_cast<std::size_t>(n), -1);
  Eigen::VectorXd held = Eigen::VectorXd::Zero(n);
  int nf = 0;
  for (int v = 0; v < n; ++v) {
    const double value = problem.fixed[static_cast<std::size_t>(v)];
    if (std::isnan(value))
      free_index[static_cast<std::size_t>(v)] = nf++;
    else
      held[v] = value;
  }
  SoftQp reduced;
  reduced.q = Eigen::VectorXd::Zero(nf);
  std::vector<Triplet> p_entries;
  for (int col = 0; col < n; ++col) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(problem.P, col); it; ++it) {
      const int row = static_cast<int>(it.row());
      const int fr = free_index[static_cast<std::size_t>(row)],
                fc = free_index[static_cast<std::size_t>(col)];
      if (fr < 0) continue;
      if (fc >= 0)
        p_entries.emplace_back(fr, fc, it.value());
      else
        reduced.q[fr] += it.value() * held[col];
    }
  }
  for (int v = 0; v < n; ++v) {
    if (const int f = free_index[static_cast<std::size_t>(v)]; f >= 0) reduced.q[f] += problem.q[v];
  }
  reduced.P.resize(nf, nf);
  reduced.P.setFromTriplets(p_entries.begin(), p_entries.end());
  // Rows: the held part of a x shifts both bounds; a row without a free variable is left out.
  std::vector<int> kept;
  std::vector<Triplet> a_entries;
  std::vector<double> lower, upper, price;
  for (int r = 0; r < m; ++r) {
    double shift = 0.0;
    bool any_free = false;
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(problem.A, r); it; ++it) {
      const int f = free_index[static_cast<std::size_t>(it.col())];
      if (f < 0) {
        shift += it.value() * held[it.col()];
      } else if (it.value() != 0.0) {
        any_free = true;
      }
    }
    if (!any_free) continue;
    const int row = static_cast<int>(kept.size());
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(problem.A, r); it; ++it) {
      const int f = free_index[static_cast<std::size_t>(it.col())];
      if (f >= 0) a_entries.emplace_back(row, f, it.value());
    }
    kept.push_back(r);
    lower.push_back(problem.lower[r] - shift);
    upper.push_back(problem.upper[r] - shift);
    price.push_back(problem.price[r]);
    if (!problem.always.empty()) reduced.always.push_back(problem.always[static_cast<std::size_t>(r)]);
    if (!problem.group.empty()) reduced.group.push_back(problem.group[static_cast<std::size_t>(r)]);
  }
  const auto mk = static_cast<int>(kept.size());
  reduced.A.resize(mk, nf);
  reduced.A.setFromTriplets(a_entries.begin(), a_entries.end());
  reduced.lower = Eigen::Map<const Eigen::VectorXd>(lower.data(), mk);
  reduced.upper = Eigen::Map<const Eigen::VectorXd>(upper.data(), mk);
  reduced.price = Eigen::Map<const Eigen::VectorXd>(price.data(), mk);

  // The caller's ordering, restricted to the free variables (their relative order kept).
  SoftQpOptions reduced_options = options;
  if (options.ordering) {
    std::vector<int> by_position(static_cast<std::size_t>(n), -1);
    for (int v = 0; v < n; ++v) by_position[static_cast<std::size_t>(options.ordering->indices()[v])] = v;
    Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> order(nf);
    int next = 0;
    for (const int v : by_position) {
      if (const int f = free_index[static_cast<std::size_t>(v)]; f >= 0) order.indices()[f] = next++;
    }
    reduced_options.ordering = order;
  }
  SoftQpResult solved;
  if (nf > 0) {
    solved = solve_soft_qp(reduced, reduced_options);
  } else {
    solved.converged = true;
    solved.status = "converged";
    solved.method = "every variable held";
  }

  SoftQpResult out = solved;
  out.x = held;
  for (int v = 0; v < n; ++v) {
    if (const int f = free_index[static_cast<std::size_t>(v)]; f >= 0) out.x[v] = solved.x[f];
  }
  out.row_values = problem.A * out.x;
  out.violation = Eigen::VectorXd::Zero(m);
  out.multiplier = Eigen::VectorXd::Zero(m);
  double penalty = 0.0;
  for (int r = 0; r < m; ++r) {
    const double a = out.row_values[r];
    out.violation[r] = std::max({0.0, problem.lower[r] - a, a - problem.upper[r]});
    penalty += problem.price[r] * out.violation[r];
  }
  for (int k = 0; k < mk; ++k) out.multiplier[kept[static_cast<std::size_t>(k)]] = solved.multiplier[k];
  out.objective = 0.5 * out.x.dot(problem.P * out.x) + problem.q.dot(out.x) + penalty;
  return out;
}

}  // namespace relief::detail
