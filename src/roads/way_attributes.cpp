#include "relief/roads/way_attributes.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <sstream>

namespace relief {

namespace {

using Tags = std::map<std::string, std::string, std::less<>>;

constexpr double kMph = 0.44704;    // m/s, exact
constexpr double kKmh = 1.0 / 3.6;  // m/s
constexpr double kKnot = 1852.0 / 3600.0;
constexpr double kFoot = 0.3048;  // m, exact
constexpr double kInch = 0.0254;  // m, exact
constexpr double kMinLaneWidth_m = 2.0;
constexpr double kMaxLaneWidth_m = 6.0;

std::string_view trim(std::string_view s) {
  const auto is_space = [](char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; };
  while (!s.empty() && is_space(s.front())) s.remove_prefix(1);
  while (!s.empty() && is_space(s.back())) s.remove_suffix(1);
  return s;
}

std::string lower(std::string_view s) {
  std::string out(s);
  std::transform(out.begin(), out.end(), out.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return out;
}

// Consumes a non-negative decimal number ("12", "3.5", ".5") from the front of `s`.
// No sign, exponent, "inf" or "nan": OSM values never use them.
std::optional<double> take_number(std::string_view& s) {
  std::size_t n = 0;
  bool digit = false;
  while (n < s.size() && (std::isdigit(static_cast<unsigned char>(s[n])) != 0 || s[n] == '.')) {
    digit = digit || s[n] != '.';
    ++n;
  }
  if (!digit) return std::nullopt;
  double value = 0.0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + n, value);
  if (ec != std::errc() || end != s.data() + n) return std::nullopt;
  s.remove_prefix(n);
  return value;
}

// Whole-string integer with optional sign ("+1", "-2").
std::optional<int> parse_int(std::string_view text) {
  text = trim(text);
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  int value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || ec != std::errc() || end != text.data() + text.size()) return std::nullopt;
  return value;
}

const std::string* find_tag(const Tags& tags, std::string_view key) {
  const auto it = tags.find(key);
  return it == tags.end() ? nullptr : &it->second;
}

// Collects warning texts, joined with "; ".
class Warnings {
 public:
  explicit Warnings(std::string* sink) : sink_(sink) {}
  void add(std::string_view key, std::string_view value, std::string_view what) {
    if (sink_ == nullptr) return;
    std::ostringstream text;
    text << key << "='" << value << "' " << what;
    if (!sink_->empty()) *sink_ += "; ";
    *sink_ += text.str();
  }

 private:
  std::string* sink_;
};

// A lane count tag: a whole number >= 1, else nullopt with a warning.
std::optional<int> lane_tag(const Tags& tags, std::string_view key, Warnings& warnings) {
  const std::string* value = find_tag(tags, key);
  if (value == nullptr) return std::nullopt;
  const auto n = parse_int(*value);
  if (!n || *n < 1) {
    warnings.add(key, *value, "is not a lane count; ignored");
    return std::nullopt;
  }
  return n;
}

}  // namespace

bool lane_allows(std::string_view turn_entry, std::string_view movement) {
  std::string entry(turn_entry);
  if (trim(entry).empty()) return movement == "through";
  std::istringstream in(entry);
  for (std::string token; std::getline(in, token, ';');) {
    token = lower(trim(token));
    if (token == "none" || token == "through" || token == "merge_to_left" || token == "merge_to_right") {
      if (movement == "through") return true;
    } else if (token == "left" || token == "sharp_left") {
      if (movement == "left") return true;
    } else if (token == "right" || token == "sharp_right") {
      if (movement == "right") return true;
    } else if (token == "slight_left") {
      if (movement == "left" || movement == "through") return true;
    } else if (token == "slight_right") {
      if (movement == "right" || movement == "through") return true;
    }
  }
  return false;
}

std::optional<double> parse_speed_mps(std::string_view value) {
  std::string_view rest = trim(value);
  const auto number = take_number(rest);
  if (!number || !(*number > 0.0)) return std::nullopt;
  const std::string unit = lower(trim(rest));
  // A bare number is km/h (OSM default unit).
  if (unit.empty() || unit == "km/h" || unit == "kmh" || unit == "kph") return *number * kKmh;
  if (unit == "mph") return *number * kMph;
  if (unit == "knots" || unit == "knot" || unit == "kn") return *number * kKnot;
  return std::nullopt;
}

std::optional<double> parse_length_m(std::string_view value) {
  std::string_view rest = trim(value);
  const auto number = take_number(rest);
  if (!number) return std::nullopt;
  rest = trim(rest);
  // Feet and inches: 12' or 12'6".
  if (!rest.empty() && rest.front() == '\'') {
    rest = trim(rest.substr(1));
    double inches = 0.0;
    if (!rest.empty()) {
      const auto in = take_number(rest);
      if (!in || trim(rest) != "\"") return std::nullopt;
      inches = *in;
    }
    return *number * kFoot + inches * kInch;
  }
  const std::string unit = lower(rest);
  if (unit.empty() || unit == "m") return *number;
  if (unit == "cm") return *number * 0.01;
  if (unit == "km") return *number * 1000.0;
  if (unit == "ft" || unit == "feet" || unit == "foot") return *number * kFoot;
  if (unit == "\"" || unit == "in") return *number * kInch;
  return std::nullopt;
}

std::optional<ParsedWay> parse_way_tags(const Tags& tags, std::string* warnings_out) {
  const std::string* highway = find_tag(tags, "highway");
  if (highway == nullptr) return std::nullopt;
  const auto cls = parse_highway_class(*highway);
  if (!cls) return std::nullopt;

  Warnings warnings(warnings_out);
  ParsedWay parsed;
  WayAttributes& a = parsed.attributes;
  a.highway = *cls;

  // junction=circular is a roundabout without priority rules; both are one-way rings.
  if (const std::string* junction = find_tag(tags, "junction")) {
    a.roundabout = *junction == "roundabout" || *junction == "circular";
  }

  // Direction: explicit oneway tag, else implied by motorway and roundabouts.
  if (const std::string* oneway = find_tag(tags, "oneway")) {
    const std::string v = lower(trim(*oneway));
    if (v == "yes" || v == "true" || v == "1") {
      a.oneway = true;
    } else if (v == "-1" || v == "reverse") {
      a.oneway = true;
      parsed.reversed = true;
    } else if (v == "no" || v == "false" || v == "0") {
      a.oneway = false;
    } else {
      // reversible, alternating: traffic in both directions at different times.
      a.oneway = false;
      if (v != "reversible" && v != "alternating") {
        warnings.add("oneway", *oneway, "not understood; treated as two-way");
      }
    }
  } else {
    a.oneway = a.highway == HighwayClass::motorway || a.roundabout;
  }

  // Lanes per direction. For a reversed way the tags' forward is our backward.
  const int per_direction = default_lanes_per_direction(a.highway);
  const auto forward = lane_tag(tags, parsed.reversed ? "lanes:backward" : "lanes:forward", warnings);
  const auto backward = lane_tag(tags, parsed.reversed ? "lanes:forward" : "lanes:backward", warnings);
  const auto total = lane_tag(tags, "lanes", warnings);
  if (a.oneway) {
    a.lanes_forward = forward ? *forward : total ? *total : per_direction;
    a.lanes_backward = 0;
    a.lanes_tagged = forward.has_value() || total.has_value();
  } else if (forward || backward) {
    // One directional tag plus the total gives the other direction.
    const auto rest_of_total = [&](const std::optional<int>& other) {
      return total && other && *total > *other ? *total - *other : per_direction;
    };
    a.lanes_forward = forward ? *forward : rest_of_total(backward);
    a.lanes_backward = backward ? *backward : rest_of_total(forward);
    a.lanes_tagged = true;
  } else if (total) {
    a.lanes_forward = std::max(1, (*total + 1) / 2);
    a.lanes_backward = std::max(1, *total / 2);
    a.lanes_tagged = true;
  } else {
    a.lanes_forward = per_direction;
    a.lanes_backward = per_direction;
  }

  // Turn lanes, in the normalised direction; dropped (with a warning) when the count is off.
  const auto turn_tag = [&](const char* key, int lanes, std::vector<std::string>& out) {
    const std::string* value = find_tag(tags, key);
    if (!value) return;
    std::vector<std::string> entries;
    std::string entry;
    std::istringstream in(*value);
    while (std::getline(in, entry, '|')) entries.emplace_back(trim(entry));
    if (!value->empty() && value->back() == '|') entries.emplace_back();
    if (!a.lanes_tagged && lanes > 0 && static_cast<int>(entries.size()) != lanes) {
      // Without a lanes tag, the turn lanes tell how many lanes there are.
      (&out == &a.turn_forward ? a.lanes_forward : a.lanes_backward) = static_cast<int>(entries.size());
      lanes = static_cast<int>(entries.size());
    }
    if (static_cast<int>(entries.size()) != lanes) {
      warnings.add(
          key, *value,
          "has " + std::to_string(entries.size()) + " lanes, the way " + std::to_string(lanes) + "; ignored");
      return;
    }
    out = std::move(entries);
  };
  if (a.oneway) {
    turn_tag(find_tag(tags, "turn:lanes") ? "turn:lanes" : "turn:lanes:forward", a.lanes_forward,
             a.turn_forward);
  } else {
    turn_tag(parsed.reversed ? "turn:lanes:backward" : "turn:lanes:forward", a.lanes_forward, a.turn_forward);
    turn_tag(parsed.reversed ? "turn:lanes:forward" : "turn:lanes:backward", a.lanes_backward,
             a.turn_backward);
  }
  // Lane width from the carriageway width, when plausible.
  a.lane_width_m = default_lane_width_m(a.highway);
  if (const std::string* width = find_tag(tags, "width")) {
    const auto w = parse_length_m(*width);
    const double lanes = a.lanes_forward + a.lanes_backward;
    if (!w) {
      warnings.add("width", *width, "is not a length; ignored");
    } else if (const double per_lane = *w / lanes; per_lane < kMinLaneWidth_m || per_lane > kMaxLaneWidth_m) {
      std::ostringstream what;
      what << "gives " << per_lane << " m per lane (outside 2..6 m); ignored";
      warnings.add("width", *width, what.str());
    } else {
      a.lane_width_m = per_lane;
      a.width_tagged = true;
    }
  }

  // Structures: any value but "no" (bridge=viaduct, tunnel=building_passage, culvert ...).
  if (const std::string* bridge = find_tag(tags, "bridge")) a.bridge = *bridge != "no";
  if (const std::string* tunnel = find_tag(tags, "tunnel")) a.tunnel = *tunnel != "no";

  if (const std::string* layer = find_tag(tags, "layer")) {
    if (const auto l = parse_int(*layer)) {
      a.layer = *l;
    } else {
      warnings.add("layer", *layer, "is not an integer; using 0");
    }
  }

  if (const std::string* maxspeed = find_tag(tags, "maxspeed")) {
    a.maxspeed_mps = parse_speed_mps(*maxspeed);
    const std::string v = lower(trim(*maxspeed));
    const bool symbolic =
        v == "none" || v == "signals" || v == "walk" || v == "variable" || v.find(':') != std::string::npos;
    if (!a.maxspeed_mps && !symbolic) warnings.add("maxspeed", *maxspeed, "not understood; ignored");
  }

  if (const std::string* name = find_tag(tags, "name")) a.name = *name;

  return parsed;
}

}  // namespace relief
