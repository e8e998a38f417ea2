#pragma once
// relief's elevation profile fit: one network-wide problem over every sample of every road,
//   minimise  sum_i w_i (z_i - d_i)^2  +  lambda * sum (z'')^2 ds  +  prices of the limits left violated
// with one shared variable per junction (exact continuity, the only hard constraint: every road
// end there has the same height) and a tangent plane per junction that every road leaves along
// (no step and no kink between its roads). Every other limit is a soft row with an L1 price, in
// this order of priority (what gives way first is listed last):
//   1. |z_i - d_i| <= max_ground_departure_m    a ground road stays near the DEM
//   2. |z_{i+1} - z_i| <= g_road ds             grade limit of the road's class / policy,
//      |grad of the junction plane| <= g          and of every junction (so its connecting roads)
//   3. z_upper - z_lower >= clearance           where roads on different layers cross
//   4. -k_crest <= z'' <= k_sag                  vertical curves of the road's design speed
//                                                (vertical_curves.h), else the physical bound
// A conflict costs only where it is, and every limit left violated is returned with its place.
// Bridge and tunnel samples have w = 0 (anchored structures span between abutments and portals).
// Solved by a primal-dual interior point (geometry/soft_qp.h): the problem is always feasible
// and its dual bounded, so it converges; the cost is linear in the number of samples (the
// factor of a network of chains between junctions stays sparse).

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
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

/// Heights and junction planes the fit holds at given values instead of solving for them (region
/// tiles: what a neighbouring tile fitted, so that both build the same surface where they meet).
/// Hard: no limit can move them (SoftQp::fixed); a limit they leave violated is reported.
struct FitHolds {
  /// Per network road, per sample: the height held (NaN: free). Empty, or an empty road: free.
  std::vector<std::vector<double>> road_z;
  /// Per network junction: the gradient of its plane held. Empty, or nullopt: free.
  std::vector<std::optional<Vec2>> junction_gradient;
  [[nodiscard]] bool empty() const { return road_z.empty() && junction_gradient.empty(); }
};

struct ProfileFitOptions {
  GradePolicy policy = GradePolicy::fidelity;
  GradeLimits limits = GradeLimits::paper();  ///< the class table (design policy)
  double fidelity_max_grade_percent = 35.0;   ///< physical cap under the fidelity policy
  /// Cap for motorways, trunks and their links under the fidelity policy: no freeway climbs
  /// like a San Francisco street, so a DEM drape that says otherwise (embankments, viaducts,
  /// cuttings) is an artefact.
  double fidelity_highway_max_grade_percent = 10.0;
  /// Cap for the ways only people walk (is_foot_way: footways, paths, steps) under the fidelity
  /// policy: a mountain path or a flight of steps climbs at 45 degrees where a street could not,
  /// and a vehicle's cap on it would pull it tens of metres off the slope it lies on.
  double fidelity_foot_max_grade_percent = 100.0;
  /// Wavelength below which height variations are treated as DEM noise (m). The smoothing
  /// weight is lambda = (cutoff / 2 pi)^4, where a smoothing spline halves the amplitude.
  double cutoff_wavelength_m = 40.0;
  /// The same for bridge decks, which are stiff over hundreds of metres: a deck arches smoothly
  /// over the roads it must clear instead of bumping up at each of them. Tunnels keep the
  /// roads' wavelength: their vertical curves sit at the portals, where a tunnel meets an
  /// approach road at its own grade, instead of carrying that grade hundreds of metres into the
  /// mountain (a 3 km base tunnel humped 18 m over its portals with the deck's stiffness).
  double structure_cutoff_wavelength_m = 200.0;
  /// A road's cross slope where its junction's plane rolls it: at most its own grade cap, and at
  /// most this (percent; 0: only the cap). A junction's plane follows its steepest road, and a
  /// through street would otherwise lie across it at that road's grade (35 % where a San
  /// Francisco hill street crosses). 12 % is the highest superelevation rate road design uses
  /// (AASHTO's e_max): a steeper street flattens over the junction instead, as San Francisco's
  /// do, and a street crossing a 10 % avenue still lies on the plane they share.
  double max_cross_slope_percent = 12.0;
  double max_curvature_per_m = 0.05;  ///< physical |z''| bound of every road (1/m); 0 disables it
  /// Roads of these classes (motorway ... the class named here, in HighwayClass order) keep the
  /// minimum crest and sag curves of their design speed (maxspeed, else the class default);
  /// slower classes (SF's steep residential grid) keep only the physical bound.
  HighwayClass design_curves_through = HighwayClass::primary_link;
  bool design_curves = true;
  double clearance_m = 5.0;  ///< minimum vertical clearance at grade separations
  /// A ground road stays within this of the DEM (m); 0: no bound. Not for bridges and tunnels.
  double max_ground_departure_m = 15.0;
  /// A limit counts as violated beyond this (m of height; grades: over a 1 m segment).
  double violation_tolerance_m = 1e-3;
  int max_iterations = 200;  ///< interior-point iterations per screening round (soft_qp.h)
  /// Called with one line per solver iteration when set (for diagnosis).
  std::function<void(const std::string&)> trace;
  FitHolds holds;
};

/// Where the road model will cut the roads for their junctions (plan only): the fit bounds the
/// grades across each junction between those cuts (junction_cuts in road_model_builder.h).
struct JunctionCuts {
  /// Per road: the length cut off its start and its end. Empty: each junction's widest
  /// half-width plus 2 m.
  std::vector<std::array<double, 2>> end_trims;
  /// Per junction: the junction that stands for the joined junction it is part of (itself when
  /// not joined), whose connecting roads run between the ends of all its members. Empty: none.
  std::vector<int> joined_into;
  /// Per road: 1 where the road lies inside a joined junction (it has no end of its own there).
  std::vector<std::uint8_t> absorbed;
};

/// The limits of the fit, in their order of priority. cross_slope: a road end's roll, the slope
/// of its junction's plane across it.
enum class FitLimit { ground_departure, grade, junction_grade, cross_slope, clearance, vertical_curve };
[[nodiscard]] std::string_view to_string(FitLimit limit);

/// A limit left violated on one road (the worst place of that road and limit).
struct FitViolation {
  FitLimit limit = FitLimit::grade;
  int road = -1;      ///< -1 for a junction's grade
  int junction = -1;  ///< the junction of a junction_grade violation
  std::int64_t osm_way_id = 0;
  double s_m = 0.0;  ///< station along the road (m)
  Vec2 xy = Vec2::Zero();
  /// In the limit's own unit: m (departure, clearance), percent (grades), 1/m (curves).
  double value = 0.0;
  double bound = 0.0;      ///< the limit, same unit
  double excess_m = 0.0;   ///< the violation as height (m)
  std::size_t places = 0;  ///< rows of this road and limit violated
};

struct ProfileFitResult {
  std::vector<RoadProfile> profiles;  ///< same stations as the input, fitted z
  std::vector<double> junction_z;     ///< height of each junction (m)
  /// Gradient (dz/dx, dz/dy) of each junction's tangent plane, the plane every road leaves it
  /// on; zero for a junction with fewer than two road ends.
  std::vector<Vec2> junction_gradient;
  std::vector<GradeSeparation> separations;
  int iterations = 0;                    ///< interior-point iterations
  bool converged = false;                ///< the solver met its optimality tolerance
  std::string solver_status;             ///< "converged", or why not
  double max_violation_m = 0.0;          ///< largest limit violation left, as height (m)
  std::vector<FitViolation> violations;  ///< worst place per road and limit, by priority then size
  std::size_t variables = 0;
  std::size_t held_variables = 0;  ///< of `variables`: held at FitHolds' values
  std::size_t constraints = 0;
};

/// Grade limit (fraction, 0.12 for 12 %) that `options` applies to a road of class `cls`.
[[nodiscard]] double grade_limit(const ProfileFitOptions& options, HighwayClass cls);
/// The same for a road with these attributes: a tunnel also keeps the class table's limit, but
/// not below the highways' physical cap (fidelity_highway_max_grade_percent), under the fidelity
/// policy: nothing measures it (no data term) and it does not follow the terrain whose steepness
/// the physical cap allows a street. Bridges keep the street's cap: a short deck on a steep
/// street climbs with it.
[[nodiscard]] double grade_limit(const ProfileFitOptions& options, const WayAttributes& attributes);

/// Design speed (km/h) of a road for its vertical curves: maxspeed, else the class default.
[[nodiscard]] double design_speed_kmh(const WayAttributes& attributes);

/// Fits every road's profile. `raw` are the DEM samples (elevation_sampling.h). Reports
/// "fit.not_converged" when the solver did not meet its tolerance and "fit.limit_violated"
/// (one per road and limit, with the place) when limits conflict, e.g. a clearance that no
/// grade-limited ramp can reach.
///
/// `cuts`: where the road model cuts each road's ends for its junctions and which junctions it
/// joins (junction_cuts, a first pass on the raw profiles). The connecting roads across a
/// junction, a joined one too, run between those cut ends, and the fit keeps every two of them
/// within the steeper road's grade cap over their plan distance; without trims it takes the
/// junction's widest half-width plus 2 m.
[[nodiscard]] ProfileFitResult fit_profiles(const RoadNetwork& network, const std::vector<RoadProfile>& raw,
                                            const ProfileFitOptions& options, Diagnostics& diagnostics,
                                            const JunctionCuts& cuts = {});

}  // namespace relief
