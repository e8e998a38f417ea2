#pragma once
// Fast, locale-independent number formatting for the text outputs (GeoJSON, OpenDRIVE, ...).

#include <cmath>
#include <string>

namespace relief {

/// Appends `value` with exactly `decimals` digits after the point ("-0.000" is written "0.000").
void append_fixed(std::string& out, double value, int decimals);

/// Appends the shortest text that reads back as exactly `value` ("0.0001525", "-2.5e-09"):
/// for polynomial coefficients, whose size spans many orders of magnitude.
void append_shortest(std::string& out, double value);

/// Appends an integer.
void append_int(std::string& out, long long value);

/// `value` rounded to a multiple of `step` (report figures: millimetres, hundredths of a percent).
[[nodiscard]] inline double round_to(double value, double step) {
  return std::round(value / step) * step;
}

}  // namespace relief
