#include "relief/cosim/sumo_session.h"

#include <atomic>
#include <cmath>
#include <numbers>

#include "cosim/sumo_backend.h"
#include "relief/core/errors.h"

namespace relief {
namespace {

std::atomic<bool> running{false};

}  // namespace

double SumoVehicleState::heading() const {
  return (90.0 - angle_deg) * std::numbers::pi / 180.0;
}

Vec2 SumoVehicleState::centre() const {
  const double h = heading();
  return Vec2(front.x(), front.y()) - 0.5 * length_m * Vec2(std::cos(h), std::sin(h));
}

std::string SumoEndpoint::describe() const {
  switch (mode) {
    case Mode::in_process:
      return "in process (libsumo)";
    case Mode::launch:
      return "TraCI to " + program + " (launched)";
    case Mode::attach:
      return "TraCI to " + host + ":" + std::to_string(port);
  }
  return {};
}

SumoSession::SumoSession(const std::filesystem::path& sumocfg, double step_s,
                         const std::vector<std::string>& extra_args, const SumoEndpoint& endpoint) {
  if (!(std::isfinite(step_s) && step_s > 0.0))
    throw InvalidInput("the SUMO step must be a finite number > 0");
  if (endpoint.mode == SumoEndpoint::Mode::attach && !(endpoint.port > 0 && endpoint.port < 65536))
    throw InvalidInput("the SUMO port must be a number from 1 to 65535");
  if (running.exchange(true)) throw Error("a SUMO session is already running in this process");
  const bool gui = endpoint.mode == SumoEndpoint::Mode::launch &&
                   std::filesystem::path(endpoint.program).filename().string().starts_with("sumo-gui");
  std::vector<std::string> args = {endpoint.mode == SumoEndpoint::Mode::launch ? endpoint.program : "sumo",
                                   "-c",
                                   sumocfg.string(),
                                   "--step-length",
                                   std::to_string(step_s),
                                   "--no-step-log",
                                   "true"};
  if (gui) args.insert(args.end(), {"--start", "--quit-on-end"});
  args.insert(args.end(), extra_args.begin(), extra_args.end());
  try {
    switch (endpoint.mode) {
      case SumoEndpoint::Mode::in_process:
        sumo_ = detail::start_in_process(args);
        break;
      case SumoEndpoint::Mode::launch:
        sumo_ = detail::start_over_traci(args);
        break;
      case SumoEndpoint::Mode::attach:
        sumo_ = detail::attach_over_traci(endpoint.host, endpoint.port, endpoint.connect_attempts);
        break;
    }
  } catch (const std::exception& e) {
    running = false;
    if (endpoint.mode == SumoEndpoint::Mode::attach) {
      throw InvalidInput("no SUMO answers at " + endpoint.host + ":" + std::to_string(endpoint.port) +
                         " (start it with -c " + sumocfg.string() + " --remote-port " +
                         std::to_string(endpoint.port) + "): " + e.what());
    }
    throw InvalidInput("SUMO (" + endpoint.describe() + ") cannot start on '" + sumocfg.string() +
                       "': " + e.what());
  }
  if (endpoint.mode == SumoEndpoint::Mode::attach) {
    const double dt = sumo_->step_length();
    if (std::abs(dt - step_s) > 1e-9) {
      sumo_.reset();
      running = false;
      throw InvalidInput("the SUMO at " + endpoint.host + ":" + std::to_string(endpoint.port) + " steps " +
                         std::to_string(dt) + " s, not " + std::to_string(step_s) +
                         " s: start it with --step-length " + std::to_string(step_s));
    }
  }
}

SumoSession::~SumoSession() {
  sumo_.reset();
  running = false;
}

void SumoSession::step() {
  sumo_->step();
}

double SumoSession::time() const {
  return sumo_->time();
}

int SumoSession::expected() const {
  return sumo_->expected();
}

double SumoSession::end_time() const {
  return sumo_->end_time();
}

std::vector<SumoVehicleState> SumoSession::vehicles() const {
  return sumo_->vehicles();
}

std::string SumoSession::vehicle_class(const std::string& type) const {
  return sumo_->vehicle_class(type);
}

double SumoSession::desired_speed(const std::string& id) const {
  return sumo_->desired_speed(id);
}

std::vector<Vec2> SumoSession::lane_path_ahead(const std::string& id, const Vec2& from, double length_m,
                                               const std::string& lane) const {
  return sumo_->lane_path_ahead(id, from, length_m, lane);
}

std::vector<std::pair<std::string, std::vector<std::vector<Vec2>>>> SumoSession::route_shapes(
    const std::string& id) const {
  return sumo_->route_shapes(id);
}

std::string SumoSession::route_edge(const std::string& id) const {
  return sumo_->route_edge(id);
}

bool SumoSession::spans_junction(const std::string& id) const {
  return sumo_->spans_junction(id);
}

double SumoSession::distance_to_route_end(const std::string& id) const {
  return sumo_->distance_to_route_end(id);
}

void SumoSession::move_to(const std::string& id, const std::string& lane, const Vec2& front,
                          double angle_deg) {
  sumo_->move_to(id, lane, front, angle_deg);
}

}  // namespace relief
