#include "demand/directions.h"

#include <cctype>
#include <cmath>
#include <map>

#include "demand/csv_table.h"
#include "relief/core/errors.h"

namespace relief::detail {

namespace {

std::string upper(std::string s) {
  for (char& c : s) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return s;
}

}  // namespace

std::optional<double> parse_direction(const std::string& text, const std::string& where) {
  static const std::map<std::string, double> kCompass = {{"N", 0.0},    {"NE", 45.0}, {"E", 90.0},
                                                         {"SE", 135.0}, {"S", 180.0}, {"SW", 225.0},
                                                         {"W", 270.0},  {"NW", 315.0}};
  std::string t = upper(detail::trim(text));
  if (t == "BOTH" || t.empty()) return std::nullopt;
  if (t.size() >= 2 && t.back() == 'B') t.pop_back();  // NB, SB, EB, WB
  if (const auto it = kCompass.find(t); it != kCompass.end()) return it->second;
  try {
    std::size_t used = 0;
    const double deg = std::stod(t, &used);
    if (used == t.size() && std::isfinite(deg)) return std::fmod(std::fmod(deg, 360.0) + 360.0, 360.0);
  } catch (const std::exception&) {  // NOLINT(bugprone-empty-catch): reported below
  }
  throw InvalidInput(where + ": unknown direction '" + text +
                     "' (NB, SB, EB, WB, N, NE, ..., degrees or both)");
}

double angle_between(double a_deg, double b_deg) {
  const double d = std::fmod(std::abs(a_deg - b_deg), 360.0);
  return d > 180.0 ? 360.0 - d : d;
}

}  // namespace relief::detail
