#pragma once
// relief's elevation profile fit: one network-wide problem over every sample of every road,
//   minimise  sum_i w_i (z_i - d_i)^2  +  lambda * sum (z'')^2 ds
//   subject to  |z_{i+1} - z_i| <= g_road * ds      (grade limit of the road's class / policy)
//               |z''| <= kappa_max                   (bounded vertical curvature)
//               z_upper - z_lower >= clearance       (where roads on different layers cross)
// with one shared variable per junction (exact continuity: every road end there has the same
// height) and a tangent plane per junction that every road leaves along (the junction is a
// smooth surface: no step and no kink between its roads, and a plane costs nothing). Bridge and tunnel
// samples have w = 0, so decks span smoothly between their abutments and portals instead of following the
// valley or the hill. Solved by a primal active-set method: exact sparse LDL^T solves (pattern analysed once)
// with the violated rows enforced as stiff penalties, a few rounds; the cost is linear in the number of
// samples (the factor of a network of chains between junctions stays sparse).

#include <optional>
#include <string_view>
#include <vector>

#include "relief/core/diagnostics.h"
#include "relief/roads/elevation_sampling.h"
#include "relief/roads/grade_separation.h"
#include "relief/roads/road_network.h"
#include "relief/roads/validation.h"

namespace relief {

enum class GradePolicy {
  fidelity,  ///< keep the real terrain grades, remove noise, cap at a physical maximum
  design,    ///< enforce the class table (like the seed paper), moving roads as little as possible
};
[[nodiscard]] std::optional<GradePolicy> parse_grade_policy(std::string_view text);
[[nodiscard]] std::string_view to_string(GradePolicy policy);

struct ProfileFitOptions {
  GradePolicy policy = GradePolicy::fidelity;
  GradeLimits limits = GradeLimits::paper();  ///< the class table (design policy)
  double fidelity_max_grade_percent = 35.0;   ///< physical cap under the fidelity policy
  /// Cap for motorways, trunks and their links under the fidelity policy: no freeway climbs
  /// like a San Francisco street, so a DEM drape that says otherwise (embankments, viaducts,
  /// cuttings) is an artefact.
  double fidelity_highway_max_grade_percent = 10.0;
  /// Wavelength below which height variations are treated as DEM noise (m). The smoothing
  /// weight is lambda = (cutoff / 2 pi)^4, where a smoothing spline halves the amplitude.
  double cutoff_wavelength_m = 40.0;
  /// The same for bridge and tunnel decks, which are stiff over hundreds of metres: a deck
  /// arches smoothly over the roads it must clear instead of bumping up at each of them.
  double structure_cutoff_wavelength_m = 200.0;
  double max_curvature_per_m = 0.05;  ///< |z''| bound (1/m); 0 disables it
  double clearance_m = 5.0;           ///< minimum vertical clearance at grade separations
  double tolerance_m = 1e-6;          ///< a row counts as violated beyond this (m)
  int max_iterations = 40;            ///< active-set rounds
};

struct ProfileFitResult {
  std::vector<RoadProfile> profiles;  ///< same stations as the input, fitted z
  std::vector<double> junction_z;     ///< height of each junction (m)
  std::vector<GradeSeparation> separations;
  int iterations = 0;            ///< active-set rounds
  bool converged = false;        ///< the active set settled
  double max_violation_m = 0.0;  ///< largest constraint violation left (m)
  std::size_t variables = 0;
  std::size_t constraints = 0;
};

/// Grade limit (fraction, 0.12 for 12 %) that `options` applies to a road of class `cls`.
[[nodiscard]] double grade_limit(const ProfileFitOptions& options, HighwayClass cls);

/// Fits every road's profile. `raw` are the DEM samples (elevation_sampling.h). Reports
/// "fit.not_converged" and "fit.infeasible" to `diagnostics` when the constraints cannot all
/// be met (e.g. a clearance that no grade-limited ramp can reach).
[[nodiscard]] ProfileFitResult fit_profiles(const RoadNetwork& network, const std::vector<RoadProfile>& raw,
                                            const ProfileFitOptions& options, Diagnostics& diagnostics);

}  // namespace relief
