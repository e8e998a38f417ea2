#pragma once
// The ego vehicles' physics (issue 16): a Bullet world whose only static body is relief's scene
// (roads, junctions, sidewalks, terrain as one triangle mesh; markings left out: they lie on the
// road), and per ego a raycast vehicle (Bullet's btRaycastVehicle): a rigid box of the vehicle's
// size on four suspended wheels whose rays find the surface. Only the wheel rays touch the
// scene: the body never collides with the triangle mesh, so Bullet's contacts on the mesh's
// internal edges (a body catching on a seam between triangles) cannot arise; egos collide with
// each other.
//
// Bullet is private to the module: no Bullet type appears here. Debian's Bullet is single
// precision, so the scene is shifted to its bounding box's centre before it is handed over
// (a float's step at 5 km is 0.5 mm; at the centre of a 10 km scene it stays under 0.25 mm).

#include <array>
#include <memory>
#include <string>

#include "relief/geometry/triangle_mesh.h"
#include "relief/geometry/types.h"

namespace relief {

/// A vehicle class's dynamics, from SUMO's vClass (ego_spec_for). Forces are totals over the
/// vehicle; the engine drives the rear axle, the front axle steers.
struct EgoSpec {
  std::string vclass = "passenger";
  double mass_kg = 1500.0;
  double length_m = 4.5, width_m = 1.8, height_m = 1.5;  ///< the body box
  double wheelbase_m = 2.7, track_m = 1.6;               ///< wheel_base_of(length, width)
  double wheel_radius_m = 0.33;
  double engine_power_w = 110e3;       ///< at the wheels
  double max_drive_force_n = 6000.0;   ///< at low speed (the gearbox's limit)
  double max_brake_force_n = 12000.0;  ///< all four wheels
  double tyre_friction = 0.9;          ///< Bullet's frictionSlip: the friction coefficient
  double rolling_resistance = 0.012;   ///< c_rr
  double drag_area_m2 = 0.7;           ///< c_d times frontal area
  double max_steer_rad = 0.6;
  /// Suspension: stiffness and dampers per kg of body (Bullet's units: 1/s^2 and 1/s), rest
  /// length and travel.
  double suspension_stiffness = 25.0, suspension_compression = 4.0, suspension_relaxation = 5.0;
  double suspension_rest_m = 0.25, suspension_travel_m = 0.2;
};

/// The documented table (README, "Ego vehicles"): passenger 1.5 t 110 kW; delivery 3.5 t 100 kW;
/// truck (loaded rigid truck) 20 t 240 kW; trailer (loaded articulated truck, one rigid body)
/// 40 t 330 kW; bus and coach 15 t 220 kW; any other class the passenger's. The box takes the
/// SUMO type's length, width and height (height 0: the class's), the wheels wheel_base_of.
/// Throws InvalidInput for a size that is not finite and > 0.
[[nodiscard]] EgoSpec ego_spec_for(const std::string& vclass, double length_m, double width_m,
                                   double height_m);

/// The driver's inputs, held until changed.
struct EgoControls {
  double steer_rad = 0.0;      ///< front wheels, positive to the left
  double drive_force_n = 0.0;  ///< at the rear wheels, >= 0
  double brake_force_n = 0.0;  ///< over all wheels, >= 0
};

/// An ego's state after a step, in the scene's frame.
struct EgoState {
  Vec2 centre;                     ///< the footing's centre in plan (under the body along its up axis)
  double ground_z_m = 0.0;         ///< under the centre, the plane through the four wheel contacts
  double heading_rad = 0.0;        ///< counter-clockwise from +x
  double pitch_rad = 0.0;          ///< the body's, nose up positive (the road's plus the suspension's)
  double roll_rad = 0.0;           ///< the body's, right side down positive
  double speed_mps = 0.0;          ///< along the heading (negative when rolling back)
  std::array<Vec3, 4> contacts{};  ///< front left, front right, rear left, rear right
  int wheels_on_ground = 0;
};

class EgoWorld {
 public:
  /// The static world: every mesh of `scene` but its markings. `substep_s` is Bullet's fixed
  /// internal step (a raycast vehicle's suspension wants 200 Hz or more).
  explicit EgoWorld(const MeshScene& scene, double substep_s = 0.005);
  ~EgoWorld();
  EgoWorld(const EgoWorld&) = delete;
  EgoWorld& operator=(const EgoWorld&) = delete;

  /// Sets an ego down with its centre over `centre`, heading `heading_rad`, tilted by
  /// `pitch_rad` (nose up) and `roll_rad` (right side down), its wheels at rest on the surface
  /// near `ground_z_m`, moving forward at `speed_mps`. An existing id is moved there (a
  /// resynchronisation: the body's spin is cleared).
  void place(const std::string& id, const EgoSpec& spec, const Vec2& centre, double heading_rad,
             double ground_z_m, double speed_mps, double pitch_rad = 0.0, double roll_rad = 0.0);
  void remove(const std::string& id);
  [[nodiscard]] bool has(const std::string& id) const;
  void set_controls(const std::string& id, const EgoControls& controls);
  /// Advances the world by dt (whole substeps). Rolling resistance and air drag act on every
  /// ego at every substep.
  void step(double dt_s);
  /// Throws Error for an unknown id.
  [[nodiscard]] EgoState state(const std::string& id) const;
  [[nodiscard]] const EgoSpec& spec(const std::string& id) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace relief
