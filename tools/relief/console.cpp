#include "console.h"

#include <chrono>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>

namespace relief::cli {

std::string fixed(double value, int digits) {
  std::ostringstream out;
  out.setf(std::ios::fixed);
  out.precision(digits);
  out << value;
  return out.str();
}

ProgressFn stderr_progress(bool quiet) {
  if (quiet) return {};
  auto start = std::make_shared<std::chrono::steady_clock::time_point>();
  return [start](std::string_view stage, double fraction) {
    if (fraction <= 0.0) {
      *start = std::chrono::steady_clock::now();
      std::cerr << "relief: " << stage << " ..." << std::flush;
    } else if (fraction >= 1.0) {
      const std::chrono::duration<double> dt = std::chrono::steady_clock::now() - *start;
      std::cerr << " " << fixed(dt.count(), 3) << " s\n";
    }
  };
}

void print_diagnostics_live(Diagnostics& diagnostics, bool quiet) {
  constexpr std::size_t kShownPerCode = 3;
  auto shown = std::make_shared<std::map<std::string, std::size_t>>();
  diagnostics.set_listener([shown, quiet](const Diagnostic& d) {
    if (quiet && d.severity != Severity::error) return;
    if (++(*shown)[d.code] > kShownPerCode) return;
    std::cerr << "\nrelief: " << to_string(d.severity) << " [" << d.code << "] " << d.message << "\n";
  });
}

void print_diagnostics_summary(const Diagnostics& diagnostics) {
  if (diagnostics.total() == 0) return;
  std::cerr << "relief: " << diagnostics.total() << " data defect(s) reported and handled:";
  for (const auto& [code, n] : diagnostics.counts()) std::cerr << " " << code << "=" << n;
  std::cerr << "\n";
}

}  // namespace relief::cli
