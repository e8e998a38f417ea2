#pragma once
// Diagnostics sink: defects in the input data that the run handles and reports (a way with a
// missing node, a DEM void under a road, a degenerate way). They feed the report; they are not
// exceptions. Also the log/progress callbacks through which the library talks to its caller:
// the library itself never prints.

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace relief {

enum class Severity { info, warning, error };

[[nodiscard]] std::string_view to_string(Severity severity);

/// One reported defect. `code` is a stable machine-readable key ("osm.missing_node"), one of the
/// registry core/diagnostic_codes.h.
struct Diagnostic {
  Severity severity = Severity::warning;
  std::string code;
  std::string message;
  std::optional<std::int64_t> osm_way_id;
  std::optional<std::int64_t> osm_node_id;
  std::optional<int> road_id;
};

/// Collects diagnostics. Keeps every count, but only the first `max_kept_per_code` messages of
/// each code so that a city full of the same defect does not flood memory or the report.
class Diagnostics {
 public:
  using Listener = std::function<void(const Diagnostic&)>;

  explicit Diagnostics(std::size_t max_kept_per_code = 50) : max_kept_per_code_(max_kept_per_code) {}

  void report(Diagnostic diagnostic);
  /// `code`: a constant of core/diagnostic_codes.h (codes::kOsmMissingNode, ...).
  void report(Severity severity, std::string_view code, std::string message);

  /// Called for every reported diagnostic (the CLI prints warnings through this).
  void set_listener(Listener listener) { listener_ = std::move(listener); }

  [[nodiscard]] const std::vector<Diagnostic>& kept() const { return kept_; }
  [[nodiscard]] const std::map<std::string, std::size_t>& counts() const { return counts_; }
  [[nodiscard]] std::size_t count(std::string_view code) const;
  [[nodiscard]] std::size_t total() const { return total_; }

 private:
  std::size_t max_kept_per_code_;
  std::vector<Diagnostic> kept_;
  std::map<std::string, std::size_t> counts_;
  std::size_t total_ = 0;
  Listener listener_;
};

/// Progress callback: a stage name and the fraction done in [0, 1].
using ProgressFn = std::function<void(std::string_view stage, double fraction)>;
/// Log callback for informational messages.
using LogFn = std::function<void(std::string_view message)>;

}  // namespace relief
