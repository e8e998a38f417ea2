#include "relief/demand/traffic_counts.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "relief/core/errors.h"
#include "relief/core/number_format.h"
#include "relief/core/xml_writer.h"

namespace relief {
namespace {

constexpr double kMatchWithin_deg = 60.0;

std::string trim(const std::string& s) {
  const std::size_t a = s.find_first_not_of(" \t\r"), b = s.find_last_not_of(" \t\r");
  return a == std::string::npos ? std::string() : s.substr(a, b - a + 1);
}

std::string upper(std::string s) {
  for (char& c : s) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return s;
}

// NB, N, NE, ... or degrees; nullopt for "both"; throws on anything else.
std::optional<double> parse_direction(const std::string& text, const std::string& where) {
  static const std::map<std::string, double> kCompass = {{"N", 0.0},    {"NE", 45.0}, {"E", 90.0},
                                                         {"SE", 135.0}, {"S", 180.0}, {"SW", 225.0},
                                                         {"W", 270.0},  {"NW", 315.0}};
  std::string t = upper(trim(text));
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

}  // namespace

std::vector<CountRow> read_counts_csv(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw IoError("cannot read the counts '" + path.string() + "'");
  std::string line;
  std::getline(in, line);
  std::vector<std::string> header;
  std::stringstream h(line);
  for (std::string f; std::getline(h, f, ',');) header.push_back(trim(f));
  const auto column = [&](const std::string& name) {
    const auto it = std::find(header.begin(), header.end(), name);
    if (it == header.end())
      throw InvalidInput("'" + path.string() + "' line 1: no column '" + name +
                         "' (osm_way,direction,count)");
    return static_cast<std::size_t>(it - header.begin());
  };
  const std::size_t way_col = column("osm_way"), dir_col = column("direction"), count_col = column("count");
  std::vector<CountRow> rows;
  for (int number = 2; std::getline(in, line); ++number) {
    if (trim(line).empty() || trim(line).starts_with('#')) continue;
    std::vector<std::string> f;
    std::stringstream fields(line);
    for (std::string x; std::getline(fields, x, ',');) f.push_back(trim(x));
    std::string where = "'";  // not "'" + ...: GCC 12's false -Wrestrict (bug 105329)
    where += path.string();
    where += "' line ";
    where += std::to_string(number);
    if (f.size() < header.size())
      throw InvalidInput(where + ": " + std::to_string(f.size()) + " fields, the header has " +
                         std::to_string(header.size()));
    CountRow row;
    row.line = number;
    try {
      std::size_t used = 0;
      row.osm_way = std::stoll(f[way_col], &used);
      if (used != f[way_col].size()) throw std::invalid_argument("trailing");
      row.count = std::stod(f[count_col], &used);
      if (used != f[count_col].size()) throw std::invalid_argument("trailing");
    } catch (const std::exception&) {
      throw InvalidInput(where + ": the OSM way must be an integer and the count a number");
    }
    if (!(std::isfinite(row.count) && row.count >= 0.0))
      throw InvalidInput(where + ": the count must be a number >= 0");
    row.bearing_deg = parse_direction(f[dir_col], where);
    rows.push_back(row);
  }
  return rows;
}

CountsOnEdges counts_on_edges(const std::vector<CountRow>& rows, const std::vector<NetEdge>& edges) {
  std::map<std::int64_t, std::vector<const NetEdge*>> by_way;
  for (const NetEdge& e : edges)
    for (const std::int64_t way : e.osm_way_ids) by_way[way].push_back(&e);
  std::map<std::string, double> total;
  CountsOnEdges out;
  for (const CountRow& row : rows) {
    const auto it = by_way.find(row.osm_way);
    const std::string where =
        "line " + std::to_string(row.line) + " (OSM way " + std::to_string(row.osm_way) + ")";
    if (it == by_way.end()) {
      out.unmatched.push_back(where + ": no edge of the net was built from this way");
      continue;
    }
    if (row.bearing_deg) {
      bool any = false;
      for (const NetEdge* e : it->second) {
        if (angle_between(e->bearing_deg(), *row.bearing_deg) > kMatchWithin_deg) continue;
        total[e->id] += row.count;
        any = true;
      }
      if (!any) out.unmatched.push_back(where + ": no edge of this way travels that direction");
      continue;
    }
    // Both directions: the edges split by the direction of the first, half the count each way.
    const double reference = it->second.front()->bearing_deg();
    std::vector<const NetEdge*> with, against;
    for (const NetEdge* e : it->second)
      (angle_between(e->bearing_deg(), reference) <= 90.0 ? with : against).push_back(e);
    const double share = against.empty() ? row.count : 0.5 * row.count;
    for (const NetEdge* e : with) total[e->id] += share;
    for (const NetEdge* e : against) total[e->id] += share;
  }
  for (const auto& [edge, count] : total) out.edges.push_back({edge, count});
  return out;
}

void write_edge_counts(std::ostream& out, const CountsOnEdges& counts, double begin_s, double end_s) {
  std::string text;
  XmlWriter xml(text, {.indent = 4});
  xml.declaration();
  xml.comment("generated by relief: traffic counts per OSM way put onto the net's edges");
  xml.start("data");
  xml.start("interval");
  std::string b, e;
  append_fixed(b, begin_s, 2);
  append_fixed(e, end_s, 2);
  xml.attribute("id", "counts");
  xml.attribute("begin", b);
  xml.attribute("end", e);
  for (const EdgeCount& c : counts.edges) {
    xml.start("edge");
    xml.attribute("id", c.edge);
    std::string n;
    append_fixed(n, c.count, 2);
    xml.attribute("entered", n);
    xml.end("edge");
  }
  xml.end("interval");
  xml.end("data");
  out << text;
}

}  // namespace relief
