#pragma once
// Sight distance on every lane, in both directions (AASHTO, A Policy on Geometric Design of
// Highways and Streets, 2018, ch. 3): at stations along every driving lane, how far ahead
// along the lane a driver's eye 1.08 m above it sees an object 0.60 m high on it, with the
// scene's road and terrain surfaces as obstacles (crests, cuttings on curves, a deck over a
// sag), against the stopping sight distance the lane needs at its speed and grade:
//
//   SSD = v t + v^2 / (2 (a + g G)),  t = 2.5 s reaction, a = 3.4 m/s2, G the grade (+ up)
//
// (AASHTO eq. 3-3 in SI units; a downgrade steeper than a / (2 g), -17 % at 3.4 m/s2, counts as
// that: on SF's -31 % streets the formula would ask 9 times the level distance). The lane is
// followed ahead through its links: to the next
// road, or through a junction on its straightest connecting road. Lines of sight are exact
// segment-triangle tests (Embree). Every lane-station needs only the distance it requires
// unless SightOptions::measure_beyond_required: a station whose lane is visible that far is
// not short, and its sight distance is reported as "at least the required".

#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "relief/geometry/triangle_mesh.h"
#include "relief/roads/road_model.h"

namespace relief {

struct SightOptions {
  double eye_height_m = 1.08;      ///< AASHTO driver's eye over the lane
  double object_height_m = 0.60;   ///< AASHTO object on the lane
  double station_spacing_m = 2.0;  ///< stations along every lane (> 0)
  double step_m = 2.0;             ///< the object moves ahead in these steps; the first hidden
                                   ///< step is refined to 0.05 m
  double reaction_s = 2.5;         ///< brake reaction time
  double deceleration_mps2 = 3.4;  ///< AASHTO's comfortable deceleration
  double search_m = 300.0;         ///< the farthest any lane is followed ahead
  /// Look on past the required distance (up to search_m) and report the sight distance itself.
  bool measure_beyond_required = false;
  /// Roads inside junctions get stations too (their lanes overlap; off: only approaches).
  bool junction_roads = false;
  /// Keep every station in SightResult::stations (Portland: 0.7 million; off: only the stretches).
  bool keep_stations = false;
};

/// AASHTO's stopping sight distance (m) at `speed_mps` on `grade` (rise over run, positive
/// uphill in the direction of travel). Throws InvalidInput where a + g G <= 0 (a downgrade
/// steeper than the deceleration can hold).
[[nodiscard]] double stopping_sight_distance(double speed_mps, double grade,
                                             const SightOptions& options = {});

enum class SightObstacle { none, road, terrain };
[[nodiscard]] const char* to_string(SightObstacle obstacle);

/// One station of one lane in one direction of travel.
struct SightStation {
  int road = -1;              ///< index into RoadModel::roads
  int lane = 0;               ///< OpenDRIVE lane id (negative: along the reference line)
  double s = 0.0;             ///< station on the road
  Vec3 point = Vec3::Zero();  ///< the lane centre on the surface
  double available_m = 0.0;   ///< sight distance (a lower bound when !measured)
  bool measured = false;      ///< available_m is the sight distance itself, not "at least"
  bool path_ended = false;    ///< the lane ended ahead (a dead end) before anything hid it
  double required_m = 0.0;
  double speed_mps = 0.0;
  double grade = 0.0;  ///< mean grade over the required distance, + uphill
  SightObstacle obstacle = SightObstacle::none;
  Vec3 obstacle_point = Vec3::Zero();  ///< where the first hidden line of sight meets it
  [[nodiscard]] bool short_of_required() const { return available_m < required_m; }
};

/// Consecutive short stations of one lane.
struct SightStretch {
  int road = -1;  ///< index into RoadModel::roads
  int lane = 0;
  double s_from = 0.0, s_to = 0.0;  ///< along the reference line, s_from < s_to
  std::vector<Vec3> points;         ///< the lane centre, in the direction of travel
  double available_m = 0.0;         ///< the smallest along the stretch
  double required_m = 0.0;          ///< at that station
  double speed_mps = 0.0;
  double grade = 0.0;
  SightObstacle obstacle = SightObstacle::none;
  Vec3 obstacle_point = Vec3::Zero();
  std::string road_class;
  [[nodiscard]] double length_m() const { return s_to - s_from; }
};

struct SightClassFigures {
  double km_checked = 0.0;  ///< lane-km (each lane and direction counted)
  double km_short = 0.0;
};

struct SightResult {
  double km_checked = 0.0;  ///< lane-km
  double km_short = 0.0;
  std::map<std::string, SightClassFigures> by_class;
  std::vector<SightStretch> stretches;  ///< short stretches, worst (smallest available / required) first
  std::vector<SightStation> stations;   ///< every station, by road, lane and s (keep_stations)
  std::size_t station_count = 0;
  std::size_t rays = 0;
  std::size_t obstacle_triangles = 0;
};

/// Sight distances of every driving lane of `model` (junction roads per options), with the
/// non-marking meshes of `obstacles` as obstacles. `road_class[k]`, when given (one per road),
/// names road k's class (e.g. the OSM highway value) in by_class and the stretches; else its
/// OpenDRIVE type. A road without a speed gets 13.4 m/s (30 mph). Throws InvalidInput for bad
/// options or a road_class of the wrong size.
[[nodiscard]] SightResult sight_distances(const RoadModel& model, const MeshScene& obstacles,
                                          const SightOptions& options = {},
                                          const std::vector<std::string>& road_class = {});

}  // namespace relief
