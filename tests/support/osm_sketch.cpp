#include "support/osm_sketch.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <numbers>
#include <stdexcept>

#include "relief/core/xml_writer.h"

namespace relief::test {

LonLat offset_lonlat(const LonLat& origin, double east_m, double north_m) {
  const double ky = 6371008.8 * std::numbers::pi / 180.0;
  const double kx = ky * std::cos(origin.lat_deg * std::numbers::pi / 180.0);
  return {origin.lon_deg + east_m / kx, origin.lat_deg + north_m / ky};
}

namespace {

bool is_letter(char c) {
  return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z');
}

double round7(double deg) {
  return std::round(deg * 1e7) / 1e7;
}

// Tags as OSM writes them: <tag k=".." v=".."/>, escaped.
void write_tags(XmlWriter& xml, const OsmSketch::Tags& tags) {
  for (const auto& [k, v] : tags) {
    xml.start("tag");
    xml.attribute("k", k);
    xml.attribute("v", v);
    xml.end("tag");
  }
}

}  // namespace

OsmSketch::OsmSketch(std::string_view art, double grid_m, LonLat origin) : origin_(origin) {
  // Split into lines; drop leading blank lines; column 0 is the smallest indentation.
  std::vector<std::string_view> lines;
  for (std::size_t start = 0; start <= art.size();) {
    const std::size_t end = std::min(art.find('\n', start), art.size());
    lines.push_back(art.substr(start, end - start));
    start = end + 1;
  }
  const auto blank = [](std::string_view l) {
    return std::all_of(l.begin(), l.end(),
                       [](char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; });
  };
  while (!lines.empty() && blank(lines.front())) lines.erase(lines.begin());
  std::size_t indent = std::string_view::npos;
  for (const auto l : lines) {
    if (!blank(l)) indent = std::min(indent, l.find_first_not_of(" \t"));
  }
  for (std::size_t row = 0; row < lines.size(); ++row) {
    for (std::size_t col = 0; col < lines[row].size(); ++col) {
      const char c = lines[row][col];
      if (!is_letter(c)) continue;
      if (offsets_.contains(c))
        throw std::invalid_argument(std::string("OsmSketch: node '") + c + "' drawn twice");
      offsets_[c] =
          Vec2(static_cast<double>(col - indent) * grid_m, -static_cast<double>(row) * 2.0 * grid_m);
    }
  }
}

OsmSketch& OsmSketch::way(std::string_view letters, Tags tags, std::optional<std::int64_t> id) {
  for (const char c : letters) {
    if (!offsets_.contains(c)) throw std::invalid_argument(std::string("OsmSketch: no node '") + c + "'");
  }
  ways_.push_back(
      {id.value_or(static_cast<std::int64_t>(ways_.size()) + 1), std::string(letters), std::move(tags)});
  return *this;
}

OsmSketch& OsmSketch::node_tags(char letter, Tags tags) {
  if (!offsets_.contains(letter))
    throw std::invalid_argument(std::string("OsmSketch: no node '") + letter + "'");
  auto& all = node_tags_[letter];
  all.insert(all.end(), tags.begin(), tags.end());
  return *this;
}

OsmSketch& OsmSketch::bounds(const LonLatBox& box) {
  bounds_ = box;
  return *this;
}

std::int64_t OsmSketch::node_id(char letter) {
  if (letter >= 'A' && letter <= 'Z') return 1000 + (letter - 'A');
  if (letter >= 'a' && letter <= 'z') return 1026 + (letter - 'a');
  throw std::invalid_argument(std::string("OsmSketch: '") + letter + "' is not a node letter");
}

Vec2 OsmSketch::offset_m(char letter) const {
  const auto it = offsets_.find(letter);
  if (it == offsets_.end()) throw std::invalid_argument(std::string("OsmSketch: no node '") + letter + "'");
  return it->second;
}

LonLat OsmSketch::lonlat(char letter) const {
  // WGS84 meridian (M) and prime-vertical (N) radii of curvature at the origin latitude.
  constexpr double a = 6378137.0;
  constexpr double f = 1.0 / 298.257223563;
  constexpr double e2 = f * (2.0 - f);
  const double phi = origin_.lat_deg * std::numbers::pi / 180.0;
  const double w = 1.0 - e2 * std::sin(phi) * std::sin(phi);
  const double m = a * (1.0 - e2) / std::pow(w, 1.5);
  const double n = a / std::sqrt(w);
  const Vec2 d = offset_m(letter);
  const double to_deg = 180.0 / std::numbers::pi;
  return {round7(origin_.lon_deg + d.x() / (n * std::cos(phi)) * to_deg),
          round7(origin_.lat_deg + d.y() / m * to_deg)};
}

std::string OsmSketch::xml() const {
  // Degrees at 1e-7, as OSM stores them.
  const auto degrees = [](XmlWriter& xml, const char* name, double deg) {
    xml.attribute_fixed(name, deg, 7);
  };
  std::string out;
  XmlWriter xml(out, {.indent = 2});
  xml.declaration();
  xml.start("osm");
  xml.attribute("version", "0.6");
  xml.attribute("generator", "relief OsmSketch");
  if (bounds_) {
    xml.start("bounds");
    degrees(xml, "minlat", bounds_->min_lat);
    degrees(xml, "minlon", bounds_->min_lon);
    degrees(xml, "maxlat", bounds_->max_lat);
    degrees(xml, "maxlon", bounds_->max_lon);
    xml.end("bounds");
  }
  for (const auto& [letter, offset] : offsets_) {
    const LonLat p = lonlat(letter);
    xml.start("node");
    xml.attribute_int("id", node_id(letter));
    xml.attribute("version", "1");
    degrees(xml, "lat", p.lat_deg);
    degrees(xml, "lon", p.lon_deg);
    const auto tags = node_tags_.find(letter);
    if (tags != node_tags_.end()) write_tags(xml, tags->second);
    xml.end("node");
  }
  for (const Way& w : ways_) {
    xml.start("way");
    xml.attribute_int("id", w.id);
    xml.attribute("version", "1");
    for (const char c : w.letters) {
      xml.start("nd");
      xml.attribute_int("ref", node_id(c));
      xml.end("nd");
    }
    write_tags(xml, w.tags);
    xml.end("way");
  }
  xml.end("osm");
  xml.finish();
  return out;
}

std::filesystem::path OsmSketch::write(const std::filesystem::path& path) const {
  std::ofstream file(path, std::ios::binary);
  file << xml();
  if (!file) throw std::runtime_error("OsmSketch: cannot write " + path.string());
  return path;
}

}  // namespace relief::test
