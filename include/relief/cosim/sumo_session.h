#pragma once
// SUMO in this process (libsumo, Debian's libsumocpp), behind a small adapter: no libsumo type
// appears in relief's headers, and its errors become relief's exceptions at the seam. One
// session at a time per process (libsumo is a singleton); a second one throws.

#include <filesystem>
#include <string>
#include <vector>

#include "relief/geometry/types.h"

namespace relief {

/// A vehicle as SUMO has it after a step.
struct SumoVehicleState {
  std::string id, type, lane;
  Vec3 front;              ///< middle of the front bumper (SUMO's position), z from the lane shape
  double angle_deg = 0.0;  ///< SUMO's angle: 0 north, clockwise
  double speed_mps = 0.0;
  double length_m = 0.0, width_m = 0.0, height_m = 0.0;
  double slope_deg = 0.0;  ///< SUMO's slope of the vehicle (from its lane's z)

  /// Heading in relief's frame: radians counter-clockwise from +x (east).
  [[nodiscard]] double heading() const;
  /// The middle of the vehicle in plan: the front bumper moved back half the length.
  [[nodiscard]] Vec2 centre() const;
};

class SumoSession {
 public:
  /// Starts SUMO on `sumocfg` with a step of `step_s` seconds (SUMO's --step-length) and the
  /// extra command-line arguments given. Throws InvalidInput when SUMO rejects the
  /// configuration or its files (SUMO's message), Error when a session is already running.
  SumoSession(const std::filesystem::path& sumocfg, double step_s,
              const std::vector<std::string>& extra_args = {});
  ~SumoSession();
  SumoSession(const SumoSession&) = delete;
  SumoSession& operator=(const SumoSession&) = delete;

  /// Advances SUMO by one step. Throws Error with SUMO's message when the step fails.
  void step();
  /// SUMO's simulation time, in seconds.
  [[nodiscard]] double time() const;
  /// Vehicles running or still to be inserted (SUMO's minimum expected number).
  [[nodiscard]] int expected() const;
  /// Every vehicle in the network now.
  [[nodiscard]] std::vector<SumoVehicleState> vehicles() const;
  /// SUMO's end time of the configuration (nothing set: a negative value).
  [[nodiscard]] double end_time() const;
};

}  // namespace relief
