#pragma once
// SUMO behind a small adapter: in this process by default (libsumo, Debian's libsumocpp), or as
// its own process over TraCI (libtraci, Debian's libtracicpp): a `sumo` or `sumo-gui` the
// session launches, or one already running with --remote-port. No SUMO type appears in relief's
// headers, and SUMO's errors become relief's exceptions at the seam. One session at a time per
// process (each client library drives one simulation); a second one throws.

#include <filesystem>
#include <memory>
#include <string>
#include <utility>
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

namespace detail {
class SumoBackend;
}

/// Which SUMO a session talks to.
struct SumoEndpoint {
  enum class Mode {
    in_process,  ///< libsumo: SUMO runs inside relief (the fastest)
    launch,      ///< libtraci: relief starts `program` as its own process and talks TraCI to it
    attach,      ///< libtraci: a SUMO already running with --remote-port `port` on `host`
  };
  Mode mode = Mode::in_process;
  /// launch: the SUMO program; "sumo-gui" to watch (it is started with --start and
  /// --quit-on-end, so it runs without a click and closes at the end).
  std::string program = "sumo";
  std::string host = "localhost";  ///< attach
  int port = 0;                    ///< attach
  /// attach: how many times to try to connect, a second apart.
  int connect_attempts = 10;

  /// "in process (libsumo)", "TraCI to sumo-gui (launched)", "TraCI to localhost:8813".
  [[nodiscard]] std::string describe() const;
};

class SumoSession {
 public:
  /// Starts SUMO on `sumocfg` with a step of `step_s` seconds (SUMO's --step-length) and the
  /// extra command-line arguments given, or, for SumoEndpoint::Mode::attach, connects to a
  /// SUMO already running (started by its user on that configuration with --remote-port and
  /// the same --step-length; `extra_args` are not used). Throws InvalidInput when SUMO rejects
  /// the configuration or its files (SUMO's message), when no SUMO answers at the port or when
  /// its step differs from `step_s`; Error when a session is already running.
  SumoSession(const std::filesystem::path& sumocfg, double step_s,
              const std::vector<std::string>& extra_args = {}, const SumoEndpoint& endpoint = {});
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

  // For vehicles another simulator drives (the egos).
  /// The vClass of a vehicle type ("passenger", "truck", ...).
  [[nodiscard]] std::string vehicle_class(const std::string& type) const;
  /// The speed SUMO would give the vehicle now if nothing outside drove it (its car following,
  /// the speed limit, the junction ahead).
  [[nodiscard]] double desired_speed(const std::string& id) const;
  /// The centre line of `lane`, by default the lane the vehicle should be on (its own, or the
  /// nearest lane of its edge from which its route goes on), from the point nearest `from` on,
  /// then through the junctions along its route (internal lanes included) for at least
  /// `length_m` where the route goes that far.
  [[nodiscard]] std::vector<Vec2> lane_path_ahead(const std::string& id, const Vec2& from, double length_m,
                                                  const std::string& lane = {}) const;
  /// The edges of the vehicle's route, each with the centre lines of its lanes.
  [[nodiscard]] std::vector<std::pair<std::string, std::vector<std::vector<Vec2>>>> route_shapes(
      const std::string& id) const;
  /// The vehicle's current edge (for an internal lane, the route edge it came from).
  [[nodiscard]] std::string route_edge(const std::string& id) const;
  /// Whether the vehicle is in a junction or its back still is (on an internal lane, or its
  /// front less than its length into its lane), or its lane is shorter than twice its length
  /// (junctions close together).
  [[nodiscard]] bool spans_junction(const std::string& id) const;
  /// How far the vehicle's front lies from the end of its route's last edge when it is on that
  /// edge (infinity elsewhere).
  [[nodiscard]] double distance_to_route_end(const std::string& id) const;
  /// Moves the vehicle for the next step to a front bumper at `front` facing `angle_deg`
  /// (SUMO's angle), mapped onto its route (moveToXY with keepRoute 1: the nearest lane of
  /// the route's edges; its current lane a hint).
  void move_to(const std::string& id, const std::string& lane, const Vec2& front, double angle_deg);

 private:
  std::unique_ptr<detail::SumoBackend> sumo_;
};

}  // namespace relief
