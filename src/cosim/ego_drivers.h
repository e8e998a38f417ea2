#pragma once
// Private to the cosim module: the ego vehicles of a run. Picks them as they depart, sets each
// into the physics world where SUMO inserted it, and every step measures how far SUMO and the
// physics lie apart (the paper's sync error, at the front bumper), resynchronises past the
// limit, drives each along its route's lane centre toward SUMO's desired speed, steps the
// physics and hands the new poses back to SUMO (moveToXY) for its next step.

#include <memory>
#include <optional>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "relief/cosim/cosim.h"
#include "relief/cosim/ego_world.h"
#include "relief/cosim/sumo_session.h"
#include "relief/cosim/vehicle_pose.h"
#include "relief/scene/surface_query.h"

namespace relief::detail {

class EgoDrivers {
 public:
  EgoDrivers(const MeshScene& scene, const SurfaceQuery& query, SumoSession& sumo,
             const CosimOptions& options);

  /// After SUMO's step to time t: new egos are picked and set down, the sync error measured
  /// and, past the limit, the physics resynchronised. Each ego's state in `vehicles` becomes
  /// the physics' (front bumper, angle, speed; SUMO's lane kept).
  void after_sumo_step(std::vector<SumoVehicleState>& vehicles, double t, CosimResult& result);
  [[nodiscard]] bool is_ego(const std::string& id) const {
    return driven_.contains(id) && !released_.contains(id);
  }
  /// The pose of an ego (is_ego) from the physics: its wheels' contacts, measured against the
  /// surface under them.
  [[nodiscard]] SurfacePose pose(const std::string& id) const;
  /// Drives every ego for one step of dt and tells SUMO where each is.
  void drive(double dt_s);
  /// The sync and speed spreads; warns of resyncs and of named egos that never ran.
  void finish(CosimResult& result, Diagnostics& diagnostics);

 private:
  void pick(const SumoVehicleState& v);
  // Whether SUMO could map `front` onto the wrong part of the ego's route: another part (not its
  // current edge or the next or previous one) within kAmbiguityMargin_m of as near in plan as its
  // own (a route over or under itself, a hairpin, the way back), or its own far (kOffRoute_m).
  [[nodiscard]] bool route_ambiguous_at(const std::string& id, const Vec2& front) const;
  // Sets the ego into the physics at SUMO's front bumper, facing `heading`, on the surface.
  void spawn(const SumoVehicleState& v, double heading);

  const MeshScene& scene_;
  const SurfaceQuery& query_;
  SumoSession& sumo_;
  const CosimOptions& options_;
  std::unique_ptr<EgoWorld> world_;  // built when the first ego departs
  std::unordered_set<std::string> named_, seen_, driven_;
  std::unordered_set<std::string> released_;  // handed back to SUMO for their last metres
  std::unordered_set<std::string> spawned_;  // driven at least once (one may leave and come back: a teleport)
  std::unordered_map<std::string, std::string> lane_, vclass_;  // an ego's SUMO lane; a type's vClass
  // Each ego's route, edge by edge with its lanes' centre lines.
  std::unordered_map<std::string, std::vector<std::pair<std::string, std::vector<std::vector<Vec2>>>>> route_;
  std::size_t picked_ = 0;
  std::unordered_map<std::string, double> gap_;  // how far SUMO's front is ahead of the physics'
  std::size_t held_steps_ = 0;                   // steps SUMO drove an ego (route_ambiguous_at)
  std::vector<float> sync_errors_, speed_gaps_;
};

}  // namespace relief::detail
