#pragma once
// Stages shared by `build` and `info`: timing, reading the OSM file and building the network.

#include <chrono>
#include <future>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "relief/core/diagnostics.h"
#include "relief/pipeline/build.h"
#include "relief/roads/road_network.h"

namespace relief {

/// Runs named stages, reports them to the progress callback and records their wall time.
class StageTimer {
 public:
  explicit StageTimer(ProgressFn progress)
      : progress_(std::move(progress)), start_(std::chrono::steady_clock::now()) {}

  /// Wall time since the timer was made, seconds.
  [[nodiscard]] double elapsed() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }

  template <typename F>
  auto run(const std::string& stage, F&& f) {
    if (progress_) progress_(stage, 0.0);
    const auto t0 = std::chrono::steady_clock::now();
    auto value = f();
    const std::chrono::duration<double> dt = std::chrono::steady_clock::now() - t0;
    timings_.emplace_back(stage, dt.count());
    if (progress_) progress_(stage, 1.0);
    return value;
  }

  /// A progress callback for a library call that brackets its own stages with (stage, 0) and
  /// (stage, 1): forwards them and records each stage's wall time as run() does. Valid while
  /// the timer lives; for one thread.
  [[nodiscard]] ProgressFn stage_progress() {
    return [this, t0 = std::chrono::steady_clock::time_point{}](std::string_view stage,
                                                                double fraction) mutable {
      if (fraction == 0.0) t0 = std::chrono::steady_clock::now();
      if (progress_) progress_(stage, fraction);
      if (fraction == 1.0) {
        const std::chrono::duration<double> dt = std::chrono::steady_clock::now() - t0;
        timings_.emplace_back(std::string(stage), dt.count());
      }
    };
  }

  /// Records a stage timed elsewhere (work done on another thread).
  void add(const std::string& stage, double seconds) { timings_.emplace_back(stage, seconds); }

  [[nodiscard]] const std::vector<std::pair<std::string, double>>& timings() const { return timings_; }

 private:
  ProgressFn progress_;
  std::chrono::steady_clock::time_point start_;
  std::vector<std::pair<std::string, double>> timings_;
};

/// A stage run on a thread of its own beside the stages that follow it (the machine has more
/// than one core; the work must only read what the main thread does not change meanwhile).
/// take() waits for it, records its time under `stage` and returns its value (or rethrows).
template <typename T>
class BackgroundStage {
 public:
  template <typename F>
  BackgroundStage(std::string stage, F&& f)
      : stage_(std::move(stage)), future_(std::async(std::launch::async, [f = std::forward<F>(f)]() mutable {
          const auto t0 = std::chrono::steady_clock::now();
          T value = f();
          return std::pair<T, double>(
              std::move(value), std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
        })) {}

  T take(StageTimer& timer) {
    auto [value, seconds] = future_.get();
    timer.add(stage_, seconds);
    return std::move(value);
  }

 private:
  std::string stage_;
  std::future<std::pair<T, double>> future_;
};

struct LoadedNetwork {
  OsmRoads osm;
  RoadNetwork network;
};

/// Reads the OSM file, picks the frame (options.crs or the UTM zone of the roads' centre) and
/// builds the network.
[[nodiscard]] LoadedNetwork load_network(const BuildOptions& options, Diagnostics& diagnostics,
                                         StageTimer& timer);

/// Bounding box of every road point (local frame).
[[nodiscard]] Aabb2 network_bounds(const RoadNetwork& network);

}  // namespace relief
