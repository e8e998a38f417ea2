#pragma once
// Private to the cosim module: the trajectory of every vehicle, streamed while the simulation
// runs, as SUMO's FCD XML (each <vehicle> with pitch and roll added) and as CSV. Both are
// written to temporary files beside their targets and renamed only by commit(): a run that
// fails leaves no half-written trajectory (an unfinished writer removes its temporaries).

#include <filesystem>
#include <fstream>
#include <string>

namespace relief::detail {

struct TrajectoryRow {
  const std::string* id = nullptr;
  const std::string* type = nullptr;
  const std::string* lane = nullptr;
  double x = 0.0, y = 0.0, z = 0.0;  ///< the vehicle's centre on the surface
  double angle_deg = 0.0;            ///< SUMO's angle (0 north, clockwise)
  double speed_mps = 0.0;
  double pitch_deg = 0.0, roll_deg = 0.0;
};

class TrajectoryWriter {
 public:
  TrajectoryWriter(std::filesystem::path fcd, std::filesystem::path csv);
  ~TrajectoryWriter();
  TrajectoryWriter(const TrajectoryWriter&) = delete;
  TrajectoryWriter& operator=(const TrajectoryWriter&) = delete;

  void begin_step(double time_s);
  void add(const TrajectoryRow& row);
  void end_step();
  /// Closes both files and renames them onto their targets. Throws IoError on a write failure.
  void commit();

 private:
  std::filesystem::path fcd_, csv_, fcd_tmp_, csv_tmp_;
  std::ofstream fcd_out_, csv_out_;
  std::string line_;
  double time_s_ = 0.0;
  bool committed_ = false;
};

}  // namespace relief::detail
