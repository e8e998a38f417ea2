#pragma once
// Atomic output files: everything is written to a temporary file beside the target and renamed
// over it only when complete, so a failed run never leaves a half-written output.

#include <filesystem>
#include <functional>
#include <ostream>
#include <string_view>

namespace relief {

/// Writes `path` atomically: `write` fills a stream bound to `path`.tmp-XXXX; on success the
/// temporary is renamed to `path`, on any exception it is removed and the exception propagates.
/// Throws IoError when the file cannot be created, written or renamed.
void write_file_atomically(const std::filesystem::path& path,
                           const std::function<void(std::ostream&)>& write);

/// Convenience overload for a ready string.
void write_file_atomically(const std::filesystem::path& path, std::string_view content);

/// A set of outputs committed together: each file is written to its temporary name first and
/// all are renamed only by commit(). Destroying an uncommitted set removes its temporaries.
class OutputSet {
 public:
  OutputSet() = default;
  OutputSet(const OutputSet&) = delete;
  OutputSet& operator=(const OutputSet&) = delete;
  ~OutputSet();

  /// Writes the content of `path` to a temporary file now; throws IoError on failure.
  void add(const std::filesystem::path& path, const std::function<void(std::ostream&)>& write);
  /// Renames every temporary onto its final name.
  void commit();

 private:
  struct Pending {
    std::filesystem::path temporary;
    std::filesystem::path target;
  };
  std::vector<Pending> pending_;
};

}  // namespace relief
