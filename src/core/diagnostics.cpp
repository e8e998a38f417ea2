#include "relief/core/diagnostics.h"

namespace relief {

std::string_view to_string(Severity severity) {
  switch (severity) {
    case Severity::info:
      return "info";
    case Severity::warning:
      return "warning";
    case Severity::error:
      return "error";
  }
  return "unknown";
}

void Diagnostics::report(Diagnostic diagnostic) {
  ++total_;
  const std::size_t n = ++counts_[diagnostic.code];
  if (listener_) listener_(diagnostic);
  if (n <= max_kept_per_code_) kept_.push_back(std::move(diagnostic));
}

void Diagnostics::report(Severity severity, std::string_view code, std::string message) {
  Diagnostic d;
  d.severity = severity;
  d.code = code;
  d.message = std::move(message);
  report(std::move(d));
}

std::size_t Diagnostics::count(std::string_view code) const {
  const auto it = counts_.find(std::string(code));
  return it == counts_.end() ? 0 : it->second;
}

}  // namespace relief
