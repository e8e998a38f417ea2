#include "relief/pipeline/option_text.h"

#include <cmath>
#include <sstream>

#include "relief/core/errors.h"

namespace relief {

std::optional<double> parse_finite_number(std::string_view text) {
  try {
    const std::string s(text);
    std::size_t used = 0;
    const double value = std::stod(s, &used);
    if (used == s.size() && std::isfinite(value)) return value;
  } catch (const std::exception&) {
    // Not a number (or out of range): nullopt.
  }
  return std::nullopt;
}

std::vector<std::string> split_list(std::string_view text, char separator) {
  std::vector<std::string> items;
  std::istringstream in{std::string(text)};
  std::string item;
  while (std::getline(in, item, separator)) items.push_back(item);
  return items;
}

std::set<Output> parse_outputs(std::string_view text) {
  if (text == "all") {
    return {Output::geojson, Output::report, Output::html,  Output::xodr,
            Output::sumo,    Output::mesh,   Output::sight, Output::view};
  }
  std::set<Output> outputs;
  for (const std::string& item : split_list(text)) {
    const auto output = parse_output(item);
    if (!output)
      throw OptionError("'" + item +
                        "' is not one of xodr, sumo, mesh, sight, view, geojson, report, html, all");
    outputs.insert(*output);
  }
  return outputs;
}

std::set<MeshFormat> parse_mesh_formats(std::string_view text) {
  std::set<MeshFormat> formats;
  for (const std::string& item : split_list(text)) {
    const auto format = parse_mesh_format(item);
    if (!format) throw OptionError("'" + item + "' is not one of glb, obj, fbx");
    formats.insert(*format);
  }
  return formats;
}

void apply_vclass_max_grade(std::map<std::string, double>& max_grade_percent, std::string_view item) {
  const std::size_t eq = item.find('=');
  const std::string vclass(item.substr(0, eq));
  if (eq == std::string_view::npos || vclass.empty()) {
    throw OptionError("'" + std::string(item) + "' is not CLASS=PERCENT");
  }
  const std::string_view value = item.substr(eq + 1);
  if (value == "none") {
    max_grade_percent.erase(vclass);
    return;
  }
  const std::optional<double> percent = parse_finite_number(value);
  if (!percent || !(*percent > 0.0)) {
    throw OptionError("'" + std::string(item) + "': the grade must be a percent > 0");
  }
  max_grade_percent[vclass] = *percent;
}

void apply_gate_threshold(GateThresholds& gates, std::string_view item) {
  const std::size_t eq = item.find('=');
  const std::optional<double> value =
      eq == std::string_view::npos ? std::nullopt : parse_finite_number(item.substr(eq + 1));
  if (!value) throw OptionError("'" + std::string(item) + "' is not NAME=VALUE with a finite VALUE");
  const std::string name(item.substr(0, eq));
  if (!gates.set(name, *value)) throw OptionError("'" + name + "' is not a quality gate");
}

LonLatBox parse_lon_lat_box(std::string_view text) {
  std::vector<double> v;
  for (const std::string& item : split_list(text)) {
    const std::optional<double> number = parse_finite_number(item);
    if (!number) throw OptionError("'" + std::string(text) + "' is not MIN_LON,MIN_LAT,MAX_LON,MAX_LAT");
    v.push_back(*number);
  }
  if (v.size() != 4 || v[0] >= v[2] || v[1] >= v[3] || v[0] < -180 || v[2] > 180 || v[1] < -90 || v[3] > 90) {
    throw OptionError("'" + std::string(text) + "' is not MIN_LON,MIN_LAT,MAX_LON,MAX_LAT with min < max");
  }
  return {v[0], v[1], v[2], v[3]};
}

LonLat parse_lon_lat(std::string_view text) {
  const std::vector<std::string> items = split_list(text);
  std::vector<double> v;
  for (const std::string& item : items) {
    if (const std::optional<double> number = parse_finite_number(item)) v.push_back(*number);
  }
  if (items.size() != 2 || v.size() != 2 || std::abs(v[0]) > 180 || std::abs(v[1]) > 90) {
    throw OptionError("'" + std::string(text) + "' is not LON,LAT in degrees");
  }
  return {v[0], v[1]};
}

}  // namespace relief
