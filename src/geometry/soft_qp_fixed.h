#pragma once
// Private to the geometry module: a soft QP with variables held at given values
// (SoftQp::fixed), solved as the smaller programme of the free variables.

#include "relief/geometry/soft_qp.h"

namespace relief::detail {

/// Eliminates the held variables (P's terms with them move into q, A's into the rows' bounds),
/// solves the rest with solve_soft_qp in the given ordering restricted to the free variables, and
/// returns the result over all variables: row values and violations of every row, multipliers of
/// the rows solved (0 for a row without a free variable).
[[nodiscard]] SoftQpResult solve_with_fixed_variables(const SoftQp& problem, const SoftQpOptions& options);

}  // namespace relief::detail
