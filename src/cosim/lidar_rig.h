#pragma once
// Private to the cosim module: the LiDARs on the egos of a co-simulation (relief/sight/lidar.h),
// their point clouds and what each sweep sees of the other vehicles.

#include <cstddef>
#include <filesystem>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "relief/cosim/cosim.h"
#include "relief/cosim/sumo_session.h"
#include "relief/cosim/vehicle_pose.h"
#include "relief/geometry/geo_frame.h"
#include "relief/sight/lidar.h"

namespace relief::detail {

/// One vehicle placed this step.
struct PlacedVehicle {
  const SumoVehicleState* state = nullptr;
  SurfacePose pose;
  bool ego = false;
};

class LidarRig {
 public:
  /// `scene`: the co-simulation's surface (kept by reference). Nothing runs without sensors.
  LidarRig(const MeshScene& scene, const CosimOptions& options, std::filesystem::path out_dir,
           GeoFrame frame);

  [[nodiscard]] bool active() const { return !options_.lidars.empty(); }

  /// Scans this step (dt) from every sensor whose ego is among `placed`; a sensor that completes
  /// a turn closes a sweep: its occlusion figures, and its point cloud written when due.
  void step(double t, double dt, const std::vector<PlacedVehicle>& placed);

  /// The figures into `result` (lidar part).
  void finish(CosimResult& result) const;

 private:
  struct Sensor {
    LidarMount mount;
    LidarSpec spec;
    std::string ego;  ///< resolved: the named ego, else the first ego seen
    double azimuth = 0.0;
    double turned = 0.0;  ///< degrees of this sweep so far
    std::vector<LidarPoint> sweep;
    std::vector<LidarBox> boxes;       ///< the vehicles of this sweep's last step
    std::vector<std::string> box_ids;  ///< parallel to boxes
    LidarPose pose;
    std::map<std::string, std::uint8_t> last;  ///< vehicle -> last sweep's state (0 seen, else hidden by)
    std::map<std::string, std::uint64_t> crest_of;  ///< vehicle -> the crest cell that hid it last
    std::size_t frames = 0;
    double next_write = 0.0;
  };
  void close_sweep(Sensor& s, double t);
  /// Whether any of the box lies within the sensor's fields of view.
  [[nodiscard]] static bool in_view(const Sensor& s, const LidarBox& b, double distance);

  LidarScene scene_;
  const CosimOptions& options_;
  std::filesystem::path out_dir_;
  std::vector<Sensor> sensors_;
  LidarFigures figures_;
  GeoFrame frame_;
  std::map<std::uint64_t, std::size_t> crest_index_;  ///< 25 m cell -> index into figures_.crests
  double seconds_ = 0.0;
  std::uint64_t seed_ = 1;
};

}  // namespace relief::detail
