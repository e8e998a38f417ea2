#pragma once
// Minimum vertical curves for a design speed, from the stopping sight distance (AASHTO, A Policy
// on Geometric Design of Highways and Streets, 7th ed. 2018, metric):
//   SSD = 0.278 V t + 0.039 V^2 / a          (eq. 3-2; t = 2.5 s brake reaction, a = 3.4 m/s^2)
//   crest K = SSD^2 / 658                    (eq. 3-43 for SSD < L: eye 1.08 m, object 0.60 m)
//   sag   K = SSD^2 / (120 + 3.5 SSD)        (eq. 3-49 for SSD < L: headlights 0.60 m, 1 degree)
// K is the length (m) per percent of grade change, so the curvature bound is |z''| <= 1 / (100 K)
// (a crest curve has z'' < 0, a sag curve z'' > 0). The Green Book's rounded design values follow
// from these: crest K 7 and sag 13 at 50 km/h, crest 52 and sag 45 at 100 km/h.

namespace relief {

/// Stopping sight distance (m) at `speed_kmh` on a level road (eq. 3-2).
[[nodiscard]] double stopping_sight_distance_m(double speed_kmh);

struct VerticalCurveBounds {
  double crest_k = 0.0;  ///< m per % of grade change
  double sag_k = 0.0;
  /// Largest downward curvature -z'' (1/m) on a crest: 1 / (100 crest_k).
  [[nodiscard]] double crest_curvature_per_m() const;
  /// Largest upward curvature z'' (1/m) in a sag: 1 / (100 sag_k).
  [[nodiscard]] double sag_curvature_per_m() const;
};

/// Minimum crest and sag K for a design speed (km/h, > 0).
[[nodiscard]] VerticalCurveBounds vertical_curve_bounds(double design_speed_kmh);

}  // namespace relief
