#include "relief/terrain/dem_source.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <utility>

#include "relief/terrain/dem_sampler.h"
#include "terrain/gdal_dataset.h"

namespace relief {
namespace {

// Lower case, surrounding blanks removed, inner blanks and hyphens as '_' ("US survey foot" ->
// "us_survey_foot", "us-ft" -> "us_ft").
std::string normalised(std::string_view text) {
  const auto first = text.find_first_not_of(" \t");
  const auto last = text.find_last_not_of(" \t");
  if (first == std::string_view::npos) return {};
  std::string out(text.substr(first, last - first + 1));
  for (char& c : out) {
    c = (c == ' ' || c == '-') ? '_' : static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  }
  return out;
}

template <typename T, std::size_t N>
std::optional<T> lookup(const std::array<std::pair<std::string_view, T>, N>& table, std::string_view key) {
  const auto it = std::find_if(table.begin(), table.end(), [&](const auto& e) { return e.first == key; });
  if (it == table.end()) return std::nullopt;
  return it->second;
}

}  // namespace

double metres_per_unit(VerticalUnit unit) {
  switch (unit) {
    case VerticalUnit::metre:
      return 1.0;
    case VerticalUnit::foot:
      return 0.3048;  // international foot, exact
    case VerticalUnit::us_survey_foot:
      return 1200.0 / 3937.0;  // US survey foot, exact
  }
  return 1.0;
}

std::string to_string(VerticalUnit unit) {
  switch (unit) {
    case VerticalUnit::metre:
      return "m";
    case VerticalUnit::foot:
      return "ft";
    case VerticalUnit::us_survey_foot:
      return "us-ft";
  }
  return "m";
}

std::optional<VerticalUnit> parse_vertical_unit(std::string_view text) {
  using U = VerticalUnit;
  static constexpr std::array<std::pair<std::string_view, U>, 15> table{{
      {"m", U::metre},
      {"metre", U::metre},
      {"meter", U::metre},
      {"metres", U::metre},
      {"meters", U::metre},
      {"ft", U::foot},
      {"foot", U::foot},
      {"feet", U::foot},
      {"international_foot", U::foot},
      {"us_ft", U::us_survey_foot},
      {"ftus", U::us_survey_foot},
      {"us_survey_foot", U::us_survey_foot},
      {"us_survey_feet", U::us_survey_foot},
      {"survey_foot", U::us_survey_foot},
      {"foot_us", U::us_survey_foot},
  }};
  return lookup(table, normalised(text));
}

std::string to_string(Interpolation interpolation) {
  switch (interpolation) {
    case Interpolation::bilinear:
      return "bilinear";
    case Interpolation::idw:
      return "idw";
    case Interpolation::nearest:
      return "nearest";
  }
  return "bilinear";
}

std::optional<Interpolation> parse_interpolation(std::string_view text) {
  using I = Interpolation;
  static constexpr std::array<std::pair<std::string_view, I>, 3> table{{
      {"bilinear", I::bilinear},
      {"idw", I::idw},
      {"nearest", I::nearest},
  }};
  return lookup(table, normalised(text));
}

DemInfo inspect_dem(const std::string& path, const DemOptions& options) {
  const auto dataset = gdal::Dataset::open_raster(path);
  return gdal::describe_dem(dataset, options.unit);
}

}  // namespace relief
