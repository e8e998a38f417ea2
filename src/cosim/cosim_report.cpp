#include "cosim/cosim_report.h"

#include "relief/core/xml_writer.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <map>

namespace relief::detail {
namespace {

std::string num(double v, int decimals) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}

std::string esc(const std::string& text) {
  std::string out;
  append_xml_escaped(out, text);
  return out;
}

void row(std::string& h, const std::string& key, const std::string& value) {
  h += "<tr><th>" + esc(key) + "</th><td>" + value + "</td></tr>\n";
}

std::string spread(const Spread& s, const char* unit, int d) {
  return "p50 " + num(s.p50, d) + unit + ", p99 " + num(s.p99, d) + unit + ", max " + num(s.max, d) + unit;
}

// Vehicles in range per sweep, averaged over each simulated second: seen, and hidden by what.
void occlusion_plot(std::string& h, const LidarFigures& l) {
  struct Second {
    std::array<double, 5> sum{};
    int sweeps = 0;
  };
  std::map<long, Second> seconds;
  for (const LidarFigures::Tick& t : l.timeline) {
    Second& s = seconds[static_cast<long>(std::floor(t.t))];
    const std::array<std::size_t, 5> v = {t.seen, t.road, t.terrain, t.vehicle, t.sparse};
    for (std::size_t k = 0; k < 5; ++k) s.sum[k] += static_cast<double>(v[k]);
    ++s.sweeps;
  }
  if (seconds.size() < 2) return;
  const double t0 = static_cast<double>(seconds.begin()->first),
               t1 = static_cast<double>(seconds.rbegin()->first);
  double top = 1.0;
  for (const auto& [sec, s] : seconds)
    for (const double v : s.sum) top = std::max(top, v / s.sweeps);
  const double w = 900, ht = 300, left = 50, right = 20, up = 20, bottom = 40;
  const auto x = [&](double t) { return left + (t - t0) / std::max(t1 - t0, 1.0) * (w - left - right); };
  const auto y = [&](double v) { return ht - bottom - v / top * (ht - up - bottom); };
  h += "<figure><figcaption>Vehicles within the LiDARs' range per sweep, mean over each second: seen (at "
       "least "
       "the minimum returns) and hidden, by what the line to the vehicle's centre meets.</figcaption>\n"
       "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" +
       num(w, 0) + "\" height=\"" + num(ht, 0) + "\" role=\"img\" aria-label=\"occlusion over time\">\n";
  h += "<path d=\"M" + num(left, 0) + " " + num(up, 0) + "V" + num(ht - bottom, 0) + "H" + num(w - right, 0) +
       "\" fill=\"none\" stroke=\"#555\"/>\n";
  h += "<text x=\"" + num(left - 6, 0) + "\" y=\"" + num(y(top) + 4, 0) + "\" text-anchor=\"end\">" +
       num(top, 1) + "</text><text x=\"" + num(left - 6, 0) + "\" y=\"" + num(y(0) + 4, 0) +
       "\" text-anchor=\"end\">0</text>\n";
  h += "<text x=\"" + num(left, 0) + "\" y=\"" + num(ht - 14, 0) + "\">" + num(t0, 0) +
       " s</text><text x=\"" + num(w - right, 0) + "\" y=\"" + num(ht - 14, 0) + "\" text-anchor=\"end\">" +
       num(t1, 0) + " s</text>\n";
  const std::array<const char*, 5> names = {"seen", "hidden by the road", "by the terrain", "by a vehicle",
                                            "too few returns"};
  const std::array<const char*, 5> colours = {"#2e9d4f", "#d33", "#e8a317", "#3366cc", "#999"};
  for (std::size_t k = 0; k < 5; ++k) {
    h += "<polyline fill=\"none\" stroke-width=\"1.6\" stroke=\"" + std::string(colours[k]) + "\" points=\"";
    for (const auto& [sec, s] : seconds)
      h += num(x(static_cast<double>(sec)), 1) + "," + num(y(s.sum[k] / s.sweeps), 1) + " ";
    h += "\"/>\n<text x=\"" + num(left + 10 + 170.0 * static_cast<double>(k), 0) + "\" y=\"" +
         num(ht - 2, 0) + "\" fill=\"" + colours[k] + "\">" + names[k] + "</text>\n";
  }
  h += "</svg></figure>\n";
}

}  // namespace

std::string cosim_html(const CosimInputs& inputs, const CosimOptions& options, const CosimResult& r) {
  std::string h =
      "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\"/>\n<title>relief "
      "co-simulation</title>\n"
      "<style>body{font:14px/1.45 system-ui,sans-serif;margin:24px auto;max-width:960px;color:#1d2330}"
      "table{border-collapse:collapse;margin:8px 0}th,td{padding:3px 10px;border-bottom:1px solid "
      "#dde;text-align:"
      "left}th{font-weight:600}svg text{font-size:12px}</style>\n</head>\n<body>\n<h1>relief "
      "co-simulation</h1>\n";
  h += "<p>" + esc(inputs.sumocfg.string()) + " on " + esc(inputs.xodr.filename().string()) +
       "</p>\n<table>\n";
  row(h, "steps",
      std::to_string(r.steps) + " of " + num(options.step_s, 3) + " s, " + num(r.simulated_s, 1) +
          " s simulated" + (r.stopped ? " (interrupted)" : ""));
  row(h, "vehicles",
      std::to_string(r.vehicles) + " (at most " + std::to_string(r.max_vehicles) + " at once), " +
          std::to_string(r.vehicle_steps) + " placements");
  row(h, "wall",
      num(r.wall_s, 2) + " s, " + num(r.real_time_factor(), 1) + "x real time (SUMO " + num(r.sumo_s, 2) +
          " s, relief " + num(r.relief_s, 2) + " s)");
  row(h, "z vs the OpenDRIVE surface", spread(r.z_error_m, " m", 4));
  row(h, "body z vs the same contacts on it", spread(r.z_error_body_m, " m", 4));
  row(h, "wheels under the road",
      std::to_string(r.wheels_under_road) + " over " + num(options.wheel_under_limit_m, 2) + " m (deepest " +
          num(r.wheel_under_m.max, 4) + " m)");
  if (r.egos > 0)
    row(h, "egos",
        std::to_string(r.egos) + ", sync error " + spread(r.sync_error_m, " m", 3) + ", " +
            std::to_string(r.resyncs) + " resyncs, " + std::to_string(r.ego_steps_wheels_in_air) +
            " steps with a wheel in the air (z off the surface up to " + num(r.wheels_in_air_z_max_m, 3) +
            " m)");
  h += "</table>\n";
  const LidarFigures& l = r.lidar;
  if (l.sensors > 0) {
    h += "<h2>LiDAR</h2>\n<table>\n";
    row(h, "sensors",
        std::to_string(l.sensors) + ", " + std::to_string(l.sweeps) + " sweeps (" +
            std::to_string(l.sweeps_written) + " point clouds written), " + std::to_string(l.points) +
            " points");
    row(h, "rays",
        std::to_string(l.rays) + " in " + num(l.seconds, 2) + " s (" +
            num(l.seconds > 0.0 ? static_cast<double>(l.rays) / l.seconds / 1e6 : 0.0, 1) + " M/s)");
    row(h, "vehicles in range",
        std::to_string(l.checked) + " sweep-vehicles: seen " + std::to_string(l.seen) +
            ", hidden by the road " + std::to_string(l.hidden_by_road) + ", the terrain " +
            std::to_string(l.hidden_by_terrain) + ", a vehicle " + std::to_string(l.hidden_by_vehicle) +
            ", too few returns " + std::to_string(l.hidden_sparse));
    h += "</table>\n";
    occlusion_plot(h, l);
    if (!l.crests.empty()) {
      h +=
          "<h3>Crests that hid vehicles</h3>\n<table>\n<tr><th>where</th><th>sweeps hiding one</th><th>first "
          "seen at (m): count, p50, min</th></tr>\n";
      for (std::size_t k = 0; k < std::min<std::size_t>(20, l.crests.size()); ++k) {
        const LidarFigures::Crest& c = l.crests[k];
        std::vector<float> d = c.first_seen_m;
        std::sort(d.begin(), d.end());
        h += "<tr><td>" + num(c.lat, 5) + ", " + num(c.lon, 5) + "</td><td>" + std::to_string(c.hidden) +
             "</td><td>" +
             (d.empty()
                  ? std::string("-")
                  : std::to_string(d.size()) + ", " + num(d[d.size() / 2], 1) + ", " + num(d.front(), 1)) +
             "</td></tr>\n";
      }
      h += "</table>\n";
    }
  }
  h += "</body>\n</html>\n";
  return h;
}

}  // namespace relief::detail
