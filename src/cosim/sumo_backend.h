#pragma once
// Private to the cosim module: the SUMO a SumoSession talks to. SUMO ships two C++ clients with
// one API and one set of headers, switched by the macro LIBTRACI: libsumo runs SUMO in this
// process, libtraci talks TraCI to a SUMO process (one it launches, or one already running,
// sumo-gui to watch). The session's calls are written once (sumo_backend.inc) and compiled
// against each (sumo_in_process.cpp, sumo_traci.cpp); both libraries live in one process side by
// side (their namespaces differ), and one session runs at a time.

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "relief/cosim/sumo_session.h"

namespace relief::detail {

class SumoBackend {
 public:
  SumoBackend() = default;
  virtual ~SumoBackend() = default;
  SumoBackend(const SumoBackend&) = delete;
  SumoBackend& operator=(const SumoBackend&) = delete;

  virtual void step() = 0;
  /// Ends the simulation (and a SUMO process this backend started or attached to).
  virtual void close() = 0;
  [[nodiscard]] virtual double time() const = 0;
  [[nodiscard]] virtual double step_length() const = 0;
  [[nodiscard]] virtual int expected() const = 0;
  [[nodiscard]] virtual double end_time() const = 0;
  [[nodiscard]] virtual std::vector<SumoVehicleState> vehicles() const = 0;
  [[nodiscard]] virtual std::string vehicle_class(const std::string& type) const = 0;
  [[nodiscard]] virtual double desired_speed(const std::string& id) const = 0;
  [[nodiscard]] virtual std::vector<Vec2> lane_path_ahead(const std::string& id, const Vec2& from,
                                                          double length_m, const std::string& lane) const = 0;
  [[nodiscard]] virtual std::vector<std::pair<std::string, std::vector<std::vector<Vec2>>>> route_shapes(
      const std::string& id) const = 0;
  [[nodiscard]] virtual std::string route_edge(const std::string& id) const = 0;
  [[nodiscard]] virtual bool spans_junction(const std::string& id) const = 0;
  [[nodiscard]] virtual double distance_to_route_end(const std::string& id) const = 0;
  virtual void move_to(const std::string& id, const std::string& lane, const Vec2& front,
                       double angle_deg) = 0;
};

/// SUMO in this process (libsumo), started with `args` (args[0] the program name).
[[nodiscard]] std::unique_ptr<SumoBackend> start_in_process(const std::vector<std::string>& args);
/// SUMO as its own process (libtraci): the program args[0] started with `args`.
[[nodiscard]] std::unique_ptr<SumoBackend> start_over_traci(const std::vector<std::string>& args);
/// A SUMO already running with --remote-port `port` on `host` (libtraci), tried `attempts` times.
[[nodiscard]] std::unique_ptr<SumoBackend> attach_over_traci(const std::string& host, int port, int attempts);

}  // namespace relief::detail
