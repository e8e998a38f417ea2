#include "relief/cosim/sumo_session.h"

#include <libsumo/libsumo.h>

#include <atomic>
#include <cmath>
#include <numbers>

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

SumoSession::SumoSession(const std::filesystem::path& sumocfg, double step_s,
                         const std::vector<std::string>& extra_args) {
  if (!(std::isfinite(step_s) && step_s > 0.0))
    throw InvalidInput("the SUMO step must be a finite number > 0");
  if (running.exchange(true))
    throw Error("a SUMO session is already running in this process (libsumo runs one)");
  std::vector<std::string> args = {
      "sumo", "-c", sumocfg.string(), "--step-length", std::to_string(step_s), "--no-step-log", "true"};
  args.insert(args.end(), extra_args.begin(), extra_args.end());
  try {
    libsumo::Simulation::start(args);
  } catch (const std::exception& e) {
    running = false;
    throw InvalidInput("SUMO cannot start on '" + sumocfg.string() + "': " + e.what());
  }
}

SumoSession::~SumoSession() {
  try {
    libsumo::Simulation::close();
  } catch (...) {  // NOLINT(bugprone-empty-catch): closing is best effort in a destructor
  }
  running = false;
}

// The members below act on libsumo's one simulation, which this object owns while it lives:
// members by design, not static (clang-tidy cannot see that).
// NOLINTBEGIN(readability-convert-member-functions-to-static)
void SumoSession::step() {
  try {
    libsumo::Simulation::step();
  } catch (const std::exception& e) {
    throw Error(std::string("SUMO failed a step: ") + e.what());
  }
}

double SumoSession::time() const {
  return libsumo::Simulation::getTime();
}

int SumoSession::expected() const {
  return libsumo::Simulation::getMinExpectedNumber();
}

double SumoSession::end_time() const {
  return libsumo::Simulation::getEndTime();
}

std::vector<SumoVehicleState> SumoSession::vehicles() const {
  std::vector<SumoVehicleState> out;
  const std::vector<std::string> ids = libsumo::Vehicle::getIDList();
  out.reserve(ids.size());
  for (const std::string& id : ids) {
    SumoVehicleState v;
    v.id = id;
    v.type = libsumo::Vehicle::getTypeID(id);
    v.lane = libsumo::Vehicle::getLaneID(id);
    const libsumo::TraCIPosition p = libsumo::Vehicle::getPosition3D(id);
    v.front = Vec3(p.x, p.y, p.z);
    v.angle_deg = libsumo::Vehicle::getAngle(id);
    v.speed_mps = libsumo::Vehicle::getSpeed(id);
    v.length_m = libsumo::Vehicle::getLength(id);
    v.width_m = libsumo::Vehicle::getWidth(id);
    v.height_m = libsumo::Vehicle::getHeight(id);
    v.slope_deg = libsumo::Vehicle::getSlope(id);
    out.push_back(std::move(v));
  }
  return out;
}

// NOLINTEND(readability-convert-member-functions-to-static)

}  // namespace relief
