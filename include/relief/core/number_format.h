#pragma once
// Fast, locale-independent number formatting for the text outputs (GeoJSON, OpenDRIVE, ...).

#include <string>

namespace relief {

/// Appends `value` with exactly `decimals` digits after the point ("-0.000" is written "0.000").
void append_fixed(std::string& out, double value, int decimals);

/// Appends an integer.
void append_int(std::string& out, long long value);

}  // namespace relief
