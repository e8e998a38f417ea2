#pragma once
// A scratch directory for tools that need files (netconvert, randomTrips), removed with
// everything in it when it goes out of scope.

#include <filesystem>

namespace relief {

class ScratchDir {
 public:
  /// Creates PARENT/.relief-sumo-PID. Throws IoError when it cannot.
  explicit ScratchDir(const std::filesystem::path& parent);
  ~ScratchDir();
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  [[nodiscard]] const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

}  // namespace relief
