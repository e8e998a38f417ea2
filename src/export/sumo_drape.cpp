#include "relief/export/sumo_drape.h"

#include <cmath>
#include <cstdio>
#include <optional>
#include <sstream>
#include <string_view>
#include <utility>

#include "export/sumo_lane_locator.h"
#include "export/sumo_seams.h"
#include "relief/roads/road_surface.h"

namespace relief {
namespace {

// SUMO interpolates a vehicle's height linearly between lane shape points: between two points
// whose chord leaves the surface by more than this, a point goes in (m) ...
constexpr double kChordTolerance = 0.01;
// ... down to points this close (m, plan).
constexpr double kMinPointSpacing = 0.5;
constexpr int kMaxBisections = 12;  // and at most this deep (4095 points between two)

// pugixml writes into a string.
struct StringWriter : pugi::xml_writer {
  std::string text;
  void write(const void* data, size_t size) override { text.append(static_cast<const char*>(data), size); }
};

// The lane's points take their heights once more, each located along the road from the point
// before it in the final shape. The first pass located an original point from the original point
// before it, not from the points inserted between them; where the two hints lead to different
// parts of a road lying over itself (netconvert extended a Liechtenstein path's internal lane by
// 336 m beside its own legs), the check, which reads the final shape in order, found the point
// 0.26 m off the surface.
std::string reheight_in_order(const std::string& text, const std::string& id, detail::LaneLocator& locator,
                              SumoDrape& out) {
  std::istringstream in(text);
  std::string result;
  std::optional<std::pair<int, double>> last_at;
  char z_text[64];
  for (std::string token; in >> token;) {
    if (!result.empty()) result += ' ';
    const std::size_t first = token.find(',');
    const std::size_t second = first == std::string::npos ? first : token.find(',', first + 1);
    if (second == std::string::npos) {
      result += token;
      last_at.reset();
      continue;
    }
    const Vec2 p(std::stod(token.substr(0, first)), std::stod(token.substr(first + 1, second - first - 1)));
    const auto at = locator.locate(id, p, last_at);
    if (!at) {
      result += token;
      last_at.reset();
      continue;
    }
    last_at = std::make_pair(at->road->id, at->s);
    const double z = surface_z(*at->road, at->s, at->t);
    std::snprintf(z_text, sizeof z_text, "%.3f", z);
    if (token.compare(second + 1, std::string::npos, z_text) != 0) ++out.points_reheighted;
    result += token.substr(0, second + 1) + z_text;
  }
  return result;
}

}  // namespace

SumoDrape drape_sumo_net(std::string& net_xml, const RoadModel& model, const std::string& file) {
  pugi::xml_document doc;
  const pugi::xml_node net = detail::load_net(doc, net_xml, file);
  detail::LaneLocator locator(net, model);
  SumoDrape out;
  const detail::SumoSeams seams = detail::close_handover_gaps(net, locator);
  out.ends_extended = seams.extended;
  out.max_extension_m = seams.max_extension_m;
  out.max_extension_lane = seams.max_extension_lane;
  out.ends_snapped = seams.snapped;
  out.max_snap_m = seams.max_snap_m;
  out.max_snap_lane = seams.max_snap_lane;
  char z_text[64];
  char point_text[96];
  for (pugi::xml_node edge : net.children("edge")) {
    for (pugi::xml_node lane : edge.children("lane")) {
      const std::string id = lane.attribute("id").as_string();
      pugi::xml_attribute shape = lane.attribute("shape");
      std::istringstream in(shape.as_string());
      std::string rewritten;
      bool changed = false;
      // The last point written with its surface height, for the chord to the next one, and
      // where it lies (OpenDRIVE road and station): each point is looked for along the road
      // from the one before, so that a road lying over itself in plan (a tight corner beside
      // its own legs, a spiral ramp) gives each point its own part's height.
      std::optional<Vec3> last;
      std::optional<std::pair<int, double>> last_at;
      // Points between a and b (both on the surface) where their chord leaves it, by bisection.
      using Near = std::optional<std::pair<int, double>>;
      const auto fill_chord = [&](const auto& self, const Vec3& a, const Near& a_at, const Vec3& b,
                                  int depth) -> void {
        if (depth > kMaxBisections || (b - a).head<2>().norm() < 2.0 * kMinPointSpacing) return;
        const auto round = [](const Vec2& p) -> Vec2 { return (100.0 * p).array().round() / 100.0; };
        Vec2 mid = 0.5 * (a + b).head<2>();
        auto at = locator.locate(id, mid, a_at);
        if (!at) return;
        if (at->lane.odr_shape && at->lane.lane) {
          // On an OpenDRIVE lane centre the new point goes onto it (a chord across a bend lies
          // beside it), rounded as SUMO writes positions, and takes the height there.
          // A centre far from the chord (a lane mapped across a fold) would not shrink the halves.
          const Vec2 centre =
              surface_point(*at->road, at->s, lane_centre_t(*at->road, at->s, *at->lane.lane)).head<2>();
          mid = round((centre - mid).norm() <= 0.25 * (b - a).head<2>().norm() ? centre : mid);
        } else {
          mid = round(mid);  // netconvert's own curve: on its chord
        }
        at = locator.locate(id, mid, a_at);
        if (!at) return;
        const Vec3 m(mid.x(), mid.y(), surface_z(*at->road, at->s, at->t));
        if (std::abs(m.z() - 0.5 * (a.z() + b.z())) <= kChordTolerance) return;
        const Near m_at = std::make_pair(at->road->id, at->s);
        self(self, a, a_at, m, depth + 1);
        std::snprintf(point_text, sizeof point_text, "%.2f,%.2f,%.3f", m.x(), m.y(), m.z());
        rewritten += std::string(" ") + point_text;
        ++out.points_added;
        self(self, m, m_at, b, depth + 1);
      };
      for (std::string token; in >> token;) {
        const std::size_t first = token.find(',');
        const std::size_t second = first == std::string::npos ? first : token.find(',', first + 1);
        if (first == std::string::npos) {
          rewritten += (rewritten.empty() ? "" : " ") + token;
          continue;
        }
        const std::string xy = token.substr(0, second);
        const Vec2 p(std::stod(token.substr(0, first)),
                     std::stod(token.substr(first + 1, second - first - 1)));
        const auto at = locator.locate(id, p, last_at);
        if (!at) {
          ++out.points_unmapped;
          rewritten += (rewritten.empty() ? "" : " ") + token;
          last.reset();
          last_at.reset();
          continue;
        }
        const double z = surface_z(*at->road, at->s, at->t);
        if (last) fill_chord(fill_chord, *last, last_at, Vec3(p.x(), p.y(), z), 0);
        last = Vec3(p.x(), p.y(), z);
        last_at = std::make_pair(at->road->id, at->s);
        const double old_z = second == std::string::npos ? 0.0 : std::stod(token.substr(second + 1));
        std::snprintf(z_text, sizeof z_text, "%.3f", z);
        ++out.points;
        const double move = std::abs(z - old_z);
        if (move > 1e-3) ++out.points_moved;
        if (move > out.max_move_m) {
          out.max_move_m = move;
          out.max_move_lane = id;
        }
        rewritten += (rewritten.empty() ? "" : " ") + xy + "," + z_text;
        changed = true;
      }
      if (changed) shape.set_value(reheight_in_order(rewritten, id, locator, out).c_str());
    }
  }
  StringWriter writer;
  doc.save(writer, "    ", pugi::format_default, pugi::encoding_utf8);
  net_xml = std::move(writer.text);
  return out;
}

}  // namespace relief
