#include "relief/cosim/sumo_session.h"

#include <libsumo/libsumo.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <numbers>

#include "relief/core/errors.h"

namespace relief {
namespace {

std::atomic<bool> running{false};

bool is_internal(const std::string& lane) {
  return lane.starts_with(':');
}

// SUMO's lane ids are EDGE_INDEX.
std::string edge_of(const std::string& lane) {
  const std::size_t cut = lane.rfind('_');
  return cut == std::string::npos ? lane : lane.substr(0, cut);
}

int lane_index(const std::string& lane) {
  const std::size_t cut = lane.rfind('_');
  return cut == std::string::npos ? 0 : std::atoi(lane.c_str() + cut + 1);
}

// The lane after `lane` on the way along `route`: an internal lane's one successor; from a
// normal lane on route edge `index`, the connection to the route's next edge (into the
// continuation lane when one is listed), through its internal lane when it has one.
std::string next_lane(const std::string& lane, const std::vector<std::string>& route, std::size_t& index,
                      const std::vector<std::string>& continuation) {
  const std::vector<libsumo::TraCIConnection> links = libsumo::Lane::getLinks(lane);
  if (is_internal(lane)) {
    if (links.empty()) return {};
    return links.front().approachedInternal.empty() ? links.front().approachedLane
                                                    : links.front().approachedInternal;
  }
  const std::string edge = edge_of(lane);
  while (index < route.size() && route[index] != edge) ++index;
  if (index + 1 >= route.size()) return {};
  const std::string& next_edge = route[index + 1];
  const libsumo::TraCIConnection* chosen = nullptr;
  for (const libsumo::TraCIConnection& link : links) {
    if (edge_of(link.approachedLane) != next_edge) continue;
    const bool listed =
        std::find(continuation.begin(), continuation.end(), link.approachedLane) != continuation.end();
    if (chosen == nullptr || listed) chosen = &link;
    if (listed) break;
  }
  if (chosen == nullptr) return {};
  return chosen->approachedInternal.empty() ? chosen->approachedLane : chosen->approachedInternal;
}

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
    // libsumo 1.15 keeps the vehicles moved for the next step in a static list that close()
    // does not clear: the next session in this process would step them after they were freed.
    // One more step consumes the list.
    if (moves_pending_) libsumo::Simulation::step();
  } catch (...) {  // NOLINT(bugprone-empty-catch): best effort in a destructor
  }
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
    moves_pending_ = false;
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

std::string SumoSession::vehicle_class(const std::string& type) const {
  return libsumo::VehicleType::getVehicleClass(type);
}

double SumoSession::desired_speed(const std::string& id) const {
  return libsumo::Vehicle::getSpeedWithoutTraCI(id);
}

std::vector<Vec2> SumoSession::lane_path_ahead(const std::string& id, const Vec2& from, double length_m,
                                               const std::string& given_lane) const {
  std::string lane = given_lane.empty() ? libsumo::Vehicle::getLaneID(id) : given_lane;
  if (lane.empty()) return {};
  const std::vector<std::string> route = libsumo::Vehicle::getRoute(id);
  auto route_index = static_cast<std::size_t>(std::max(0, libsumo::Vehicle::getRouteIndex(id)));
  std::vector<std::string> continuation;
  if (given_lane.empty() &&
      !is_internal(lane)) {  // the lane from which the route goes on, nearest the current one
    int best = std::numeric_limits<int>::max();
    for (const libsumo::TraCIBestLanesData& b : libsumo::Vehicle::getBestLanes(id)) {
      if (edge_of(b.laneID) != edge_of(lane)) continue;
      const int offset = std::abs(lane_index(b.laneID) - lane_index(lane));
      if (b.bestLaneOffset == 0 && offset < best) {
        best = offset;
        lane = b.laneID;
        continuation = b.continuationLanes;
      }
    }
  }
  std::vector<Vec2> path;
  double length = 0.0;
  bool first = true;
  for (int hops = 0; hops < 16 && !lane.empty(); ++hops) {
    const libsumo::TraCIPositionVector shape = libsumo::Lane::getShape(lane);
    std::size_t start = 0;
    if (first) {  // from the segment nearest the vehicle on
      double best = std::numeric_limits<double>::infinity();
      for (std::size_t i = 0; i < shape.value.size(); ++i) {
        const double d = (Vec2(shape.value[i].x, shape.value[i].y) - from).squaredNorm();
        if (d < best) {
          best = d;
          start = i;
        }
      }
      start = start > 0 ? start - 1 : 0;
      first = false;
    }
    for (std::size_t i = start; i < shape.value.size(); ++i) {
      const Vec2 p(shape.value[i].x, shape.value[i].y);
      if (!path.empty()) length += (p - path.back()).norm();
      if (path.empty() || (p - path.back()).squaredNorm() > 1e-6) path.push_back(p);
    }
    if (length >= length_m) break;
    lane = next_lane(lane, route, route_index, continuation);
  }
  return path;
}

std::vector<std::pair<std::string, std::vector<std::vector<Vec2>>>> SumoSession::route_shapes(
    const std::string& id) const {
  std::vector<std::pair<std::string, std::vector<std::vector<Vec2>>>> out;
  for (const std::string& edge : libsumo::Vehicle::getRoute(id)) {
    std::vector<std::vector<Vec2>> lanes;
    for (int i = 0; i < libsumo::Edge::getLaneNumber(edge); ++i) {
      std::vector<Vec2>& line = lanes.emplace_back();
      for (const libsumo::TraCIPosition& p : libsumo::Lane::getShape(edge + "_" + std::to_string(i)).value)
        line.emplace_back(p.x, p.y);
    }
    out.emplace_back(edge, std::move(lanes));
  }
  return out;
}

std::string SumoSession::route_edge(const std::string& id) const {
  const std::vector<std::string> route = libsumo::Vehicle::getRoute(id);
  const int index = libsumo::Vehicle::getRouteIndex(id);
  return index >= 0 && index < static_cast<int>(route.size()) ? route[static_cast<std::size_t>(index)]
                                                              : std::string();
}

bool SumoSession::spans_junction(const std::string& id) const {
  const std::string lane = libsumo::Vehicle::getLaneID(id);
  if (lane.empty() || is_internal(lane)) return true;
  const double length = libsumo::Vehicle::getLength(id);
  return libsumo::Vehicle::getLanePosition(id) < length || libsumo::Lane::getLength(lane) < 2.0 * length;
}

double SumoSession::distance_to_route_end(const std::string& id) const {
  const std::string lane = libsumo::Vehicle::getLaneID(id);
  const std::vector<std::string> route = libsumo::Vehicle::getRoute(id);
  if (lane.empty() || is_internal(lane) || route.empty() || edge_of(lane) != route.back())
    return std::numeric_limits<double>::infinity();
  return libsumo::Lane::getLength(lane) - libsumo::Vehicle::getLanePosition(id);
}

void SumoSession::move_to(const std::string& id, const std::string& lane, const Vec2& front,
                          double angle_deg) {
  try {
    libsumo::Vehicle::moveToXY(id, edge_of(lane), lane_index(lane), front.x(), front.y(), angle_deg, 1);
    moves_pending_ = true;
  } catch (const std::exception& e) {
    throw Error("SUMO cannot move vehicle '" + id + "': " + e.what());
  }
}

// NOLINTEND(readability-convert-member-functions-to-static)

}  // namespace relief
