#pragma once
// Private to the demand module: travel directions as count stations write them, and the angle
// between two bearings.

#include <optional>
#include <string>

namespace relief::detail {

/// Edges within this angle of a row's direction take its count.
inline constexpr double kMatchWithin_deg = 60.0;

/// NB, SB, EB, WB, N, NE, ... or a compass bearing in degrees (clockwise from north, any
/// range); nullopt for `both` or an empty field. Throws InvalidInput naming `where` otherwise.
[[nodiscard]] std::optional<double> parse_direction(const std::string& text, const std::string& where);

/// The angle between two bearings, 0..180 degrees.
[[nodiscard]] double angle_between(double a_deg, double b_deg);

}  // namespace relief::detail
