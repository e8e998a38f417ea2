#pragma once
// One height surface per junction, which every road inside it and the junction's mesh patch
// sample. Each road end at the junction brings the plane its end cross-section lies in (its
// height, its grade along the road, its roll across); inside the junction the surface blends
// a trend plane T (the least-squares plane through the ends' cross-sections) with each end's
// departure from it, blended by inverse squared distance to the end's cross-section (Shepard's
// method with linear nodal functions, Franke & Nielson 1980):
//
//   S(p) = T(p) + sum_e w_e(p) (L_e(p) - T(p)) / sum_e w_e(p),   w_e = 1 / d_e(p)^2,
//
// L_e the end's plane, d_e the distance from p to its cross-section segment. (Blending the ends'
// planes themselves extrapolates a steep road's grade across the junction: Potrero's junctions
// on De Haro Street climbed 36 % between ends at 5 and 12 %.) On that segment S is the road's own
// surface, and the normalised weights have zero gradient there, so S leaves every road end with
// the road's grade and roll (C1 across the junction's edge). Where two connecting roads cross
// or overlap they take their heights from the same S and agree; the junction's mesh patch,
// whose interior points lie on their lane centres, follows it too.
//
// Where S is too steep along a connecting road, that road leaves it (surface_profiles); the
// surface then takes the road's departure (with_departures), so that the roads crossing it
// follow it there too instead of passing a step above or below it.

#include <limits>
#include <utility>
#include <vector>

#include "relief/geometry/cubic_profile.h"
#include "relief/geometry/plan_view.h"
#include "relief/geometry/types.h"
#include "relief/roads/road_model.h"

namespace relief {

/// The plane of one road end's cross-section: its segment (right to left corner), and the plane
/// z(p) = z + gradient . (p - point).
struct EndPlane {
  Vec2 right = Vec2::Zero(), left = Vec2::Zero();
  Vec2 point = Vec2::Zero();
  double z = 0.0;
  Vec2 gradient = Vec2::Zero();
};

/// The plane of the end cross-section of `road` at its start or end: the reference line's point,
/// the elevation and its slope along the road, the roll across (road_surface.h's surface), the
/// segment between the outermost lane borders.
[[nodiscard]] EndPlane end_plane(const ModelRoad& road, bool at_start);

class JunctionHeight {
 public:
  /// Throws InvalidInput for no ends.
  explicit JunctionHeight(std::vector<EndPlane> ends);

  /// Height and gradient of the surface at p, its departures included.
  [[nodiscard]] std::pair<double, Vec2> at(const Vec2& p) const;
  /// The same without the departures.
  [[nodiscard]] std::pair<double, Vec2> base_at(const Vec2& p) const;

  /// This surface raised or lowered by the departures of roads that left it, each a line of
  /// points (x, y, dz) along the road: S'(p) = S(p) + K(p) F(p), F = sum_l w_l dz_l / (1 / R^2 +
  /// sum_l w_l), dz_l the departure of line l at its point nearest p (linear between its
  /// points), w_l = (1 / d_l^2) (1 - d_l / R)^2 within R = 4 m of it (each line's own departure
  /// on it, none 4 m from every line, as the junction's mesh patch blends its lane points), K =
  /// smoothstep(min(1, d / 1 m)) of the distance d to the nearest end's cross-section, so that
  /// every end keeps its plane and its gradient exactly. Replaces any departures it had.
  [[nodiscard]] JunctionHeight with_departures(std::vector<std::vector<Vec3>> departures) const;
  [[nodiscard]] bool has_departures() const { return !departures_.empty(); }

 private:
  // K(p) F(p) and its gradient.
  [[nodiscard]] std::pair<double, Vec2> departure_at(const Vec2& p) const;

  std::vector<EndPlane> ends_;
  Vec2 centre_ = Vec2::Zero();  // of the ends' reference points
  double trend_z_ = 0.0;        // the trend plane's height at centre_
  Vec2 trend_gradient_ = Vec2::Zero();
  std::vector<std::vector<Vec3>> departures_;
};

/// Elevation and roll of a road inside the junction laid on the surface: sampled every 0.5 m
/// along its reference line, fitted by C1 cubic pieces within 1 mm and 1e-4 rad; the ends exact
/// (the elevation's value and slope, the roll's value: the roll's rate follows the surface, not
/// the zero rate a road ends with, which on a turn across a plane put the roll 1e-3 rad off it).
/// Where the samples' chords are steeper than `grade_limit`, the heights leave the surface there
/// and only there (grade_limited, blended over 5 m; the roll stays the surface's), and their
/// cubics keep the samples' grades (fit_grade_bounded_profile): two roads from one lane then
/// share the surface wherever they can, instead of one of them leaving it whole.
/// `max_departure_m` is measured from the surface without its departures (base_at); `left` holds
/// the samples (x, y, height - base height) of a road that left the given surface, for
/// with_departures (empty when it did not).
struct SurfaceProfiles {
  CubicProfile elevation, superelevation;
  double max_grade = 0.0;        ///< largest |slope| of the surface samples' chords
  double max_departure_m = 0.0;  ///< largest |height - the surface's without departures| at the samples
  std::vector<Vec3> left;
};
/// A limit under the grade between the road's two ends is raised to it.
[[nodiscard]] SurfaceProfiles surface_profiles(const PlanView& plan, const JunctionHeight& surface,
                                               double grade_limit = std::numeric_limits<double>::infinity());

}  // namespace relief
