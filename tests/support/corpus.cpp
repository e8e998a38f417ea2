#include "support/corpus.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <limits>
#include <map>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <unordered_map>
#include <utility>

#include "relief/core/xml_writer.h"
#include "relief/geometry/crs_transform.h"
#include "relief/terrain/dem_writer.h"
#include "support/synthetic.h"
#include "support/test_data.h"

namespace relief::test {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kNodata = -32768.0;

// Smooth ramp max(t, 0), rounded over about +-eps: a piecewise linear profile built from these
// has exactly its slopes away from its corners.
double soft_ramp(double t, double eps) {
  return 0.5 * (t + std::sqrt(t * t + eps * eps));
}

// A 1-D profile: `z0` plus, for each corner (position, change of slope, rounding), the change
// of slope times soft_ramp. The slope is exactly the sum of the changes left of a point.
struct Profile {
  double z0 = 0.0;
  std::vector<std::array<double, 3>> corners;  // {position, slope change, rounding}
  [[nodiscard]] double operator()(double t) const {
    double z = z0;
    for (const auto& c : corners) z += c[1] * soft_ramp(t - c[0], c[2]);
    return z;
  }
};

// First t in [lo, hi] where f changes sign (f(lo) and f(hi) of opposite signs), by bisection.
double bisect(const std::function<double(double)>& f, double lo, double hi) {
  const bool lo_negative = f(lo) < 0.0;
  for (int i = 0; i < 100; ++i) {
    const double mid = 0.5 * (lo + hi);
    ((f(mid) < 0.0) == lo_negative ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

// A centreline drawn like a turtle: straights and circular arcs, sampled every `step` metres.
class Path {
 public:
  Path(const Vec2& start, double heading_rad) : heading_(heading_rad) { points_.push_back(start); }
  void straight(double length_m, double step_m = 5.0) {
    const int n = std::max(1, static_cast<int>(std::ceil(length_m / step_m)));
    const Vec2 d(std::cos(heading_), std::sin(heading_));
    const Vec2 a = points_.back();
    for (int i = 1; i <= n; ++i) points_.push_back(a + d * (length_m * i / n));
  }
  // Turns by `turn_rad` (> 0 left) on a circle of `radius_m`.
  void arc(double radius_m, double turn_rad, double step_m = 2.5) {
    const int n = std::max(2, static_cast<int>(std::ceil(radius_m * std::abs(turn_rad) / step_m)));
    const double side = turn_rad > 0.0 ? 1.0 : -1.0;
    const Vec2 a = points_.back();
    const Vec2 centre = a + side * radius_m * Vec2(-std::sin(heading_), std::cos(heading_));
    const double phi0 = std::atan2(a.y() - centre.y(), a.x() - centre.x());
    for (int i = 1; i <= n; ++i) {
      const double phi = phi0 + turn_rad * i / n;
      points_.push_back(centre + radius_m * Vec2(std::cos(phi), std::sin(phi)));
    }
    heading_ += turn_rad;
  }
  [[nodiscard]] const Polyline2& points() const { return points_; }
  [[nodiscard]] const Vec2& end() const { return points_.back(); }
  [[nodiscard]] double heading() const { return heading_; }
  [[nodiscard]] std::size_t size() const { return points_.size(); }

 private:
  Polyline2 points_;
  double heading_;
};

std::vector<double> arc_lengths(const Polyline2& line) {
  std::vector<double> s(line.size(), 0.0);
  for (std::size_t i = 1; i < line.size(); ++i) s[i] = s[i - 1] + (line[i] - line[i - 1]).norm();
  return s;
}

double plan_length(const Polyline2& line) {
  return line.size() < 2 ? 0.0 : arc_lengths(line).back();
}

// Road platforms cut and filled into the natural ground: within half_width_m of a designed
// centreline the ground is at its designed height, then a 1.5:1 batter back to nature. The
// nearest centreline decides; a grid of buckets keeps the lookup local.
class RoadBeds {
 public:
  explicit RoadBeds(std::function<double(const Vec2&)> natural) : natural_(std::move(natural)) {}

  // Adds the segments of `line` with designed heights `z` (one per point).
  void add(const Polyline2& line, const std::vector<double>& z) {
    for (std::size_t i = 0; i + 1 < line.size(); ++i) {
      Segment seg{line[i], line[i + 1], z[i], z[i + 1], 0.0};
      const double lift =
          std::max(std::abs(z[i] - natural_(line[i])), std::abs(z[i + 1] - natural_(line[i + 1])));
      seg.reach_m = kHalfWidth + kBatter * lift + 2.0;
      const std::size_t id = segments_.size();
      segments_.push_back(seg);
      const Vec2 lo = line[i].cwiseMin(line[i + 1]) - Vec2::Constant(seg.reach_m);
      const Vec2 hi = line[i].cwiseMax(line[i + 1]) + Vec2::Constant(seg.reach_m);
      for (long bx = bucket(lo.x()); bx <= bucket(hi.x()); ++bx)
        for (long by = bucket(lo.y()); by <= bucket(hi.y()); ++by) buckets_[key(bx, by)].push_back(id);
    }
  }

  [[nodiscard]] double operator()(const Vec2& p) const {
    const double nature = natural_(p);
    const auto it = buckets_.find(key(bucket(p.x()), bucket(p.y())));
    if (it == buckets_.end()) return nature;
    double best = std::numeric_limits<double>::infinity();
    const Segment* nearest = nullptr;
    Vec2 foot = Vec2::Zero();
    double t_best = 0.0;
    for (const std::size_t id : it->second) {
      const Segment& seg = segments_[id];
      const Vec2 d = seg.b - seg.a;
      const double t = std::clamp((p - seg.a).dot(d) / std::max(d.squaredNorm(), 1e-12), 0.0, 1.0);
      const Vec2 q = seg.a + t * d;
      const double dist = (p - q).norm();
      if (dist < best) {
        best = dist;
        nearest = &seg;
        foot = q;
        t_best = t;
      }
    }
    if (nearest == nullptr || best >= nearest->reach_m) return nature;
    const double design = nearest->za + t_best * (nearest->zb - nearest->za);
    const double lift = design - natural_(foot);
    if (best <= kHalfWidth) return nature + lift;
    const double run = std::max(3.0, kBatter * std::abs(lift));
    const double u = std::clamp((best - kHalfWidth) / run, 0.0, 1.0);
    const double w = 1.0 - u * u * (3.0 - 2.0 * u);  // smoothstep from the platform to nature
    return nature + lift * w;
  }

 private:
  static constexpr double kHalfWidth = 7.0;
  static constexpr double kBatter = 1.5;
  static constexpr double kBucket = 32.0;
  struct Segment {
    Vec2 a, b;
    double za, zb;
    double reach_m;
  };
  static long bucket(double v) { return static_cast<long>(std::floor(v / kBucket)); }
  static std::int64_t key(long bx, long by) {
    return (static_cast<std::int64_t>(bx) << 32) ^ (by & 0xffffffff);
  }

  std::function<double(const Vec2&)> natural_;
  std::vector<Segment> segments_;
  std::unordered_map<std::int64_t, std::vector<std::size_t>> buckets_;
};

// OSM XML with nodes given in the local frame of synthetic_frame().
class OsmWriter {
 public:
  using Tags = std::vector<std::pair<std::string, std::string>>;

  OsmWriter() : frame_(synthetic_frame()), to_wgs84_(frame_.crs(), "EPSG:4326") {}

  // Every node written is shifted by this (copies of a world side by side).
  void set_offset(const Vec2& offset) { offset_ = offset; }

  std::int64_t node(const Vec2& p) {
    const Vec2 ll = to_wgs84_.apply(frame_.to_crs(p + offset_));
    nodes_.push_back({next_node_, ll.y(), ll.x()});
    return next_node_++;
  }
  std::vector<std::int64_t> nodes(const Polyline2& line) {
    std::vector<std::int64_t> ids;
    for (const Vec2& p : line) ids.push_back(node(p));
    return ids;
  }
  // A way through `refs`; `plan` is its centreline (for the length).
  std::int64_t way(const std::vector<std::int64_t>& refs, const Tags& tags, const Polyline2& plan) {
    const std::int64_t id = next_way_++;
    ways_.push_back({id, refs, tags});
    if (std::any_of(tags.begin(), tags.end(), [](const auto& t) { return t.first == "highway"; }))
      length_m_ += plan_length(plan);
    ++count_;
    return id;
  }
  [[nodiscard]] LonLat lonlat(const Vec2& p) const {
    const Vec2 ll = to_wgs84_.apply(frame_.to_crs(p));
    return {ll.x(), ll.y()};
  }
  // Nodes first, then ways, as OSM files have them; degrees at 10 significant digits.
  [[nodiscard]] std::string xml() const {
    const auto degrees = [](double v) {
      std::ostringstream text;
      text << std::setprecision(10) << v;
      return text.str();
    };
    std::string out;
    XmlWriter xml(out, {.indent = 2});
    xml.declaration();
    xml.start("osm");
    xml.attribute("version", "0.6");
    xml.attribute("generator", "relief corpus");
    for (const Node& n : nodes_) {
      xml.start("node");
      xml.attribute_int("id", n.id);
      xml.attribute("version", "1");
      xml.attribute("lat", degrees(n.lat));
      xml.attribute("lon", degrees(n.lon));
      xml.end("node");
    }
    for (const Way& w : ways_) {
      xml.start("way");
      xml.attribute_int("id", w.id);
      xml.attribute("version", "1");
      for (const std::int64_t r : w.refs) {
        xml.start("nd");
        xml.attribute_int("ref", r);
        xml.end("nd");
      }
      for (const auto& [k, v] : w.tags) {
        xml.start("tag");
        xml.attribute("k", k);
        xml.attribute("v", v);
        xml.end("tag");
      }
      xml.end("way");
    }
    xml.end("osm");
    xml.finish();
    return out;
  }
  [[nodiscard]] std::size_t count() const { return count_; }
  [[nodiscard]] double length_km() const { return length_m_ / 1000.0; }

 private:
  struct Node {
    std::int64_t id;
    double lat, lon;
  };
  struct Way {
    std::int64_t id;
    std::vector<std::int64_t> refs;
    Tags tags;
  };

  GeoFrame frame_;
  CrsTransform to_wgs84_;
  Vec2 offset_ = Vec2::Zero();
  std::vector<Node> nodes_;
  std::vector<Way> ways_;
  std::int64_t next_node_ = 1, next_way_ = 1;
  std::size_t count_ = 0;
  double length_m_ = 0.0;
};

// Writes an Int16 DEM over local [x0, x1] x [y0, y1] (cell centres sample `ground`), with voids
// (nodata -32768) within each radius of its centre and in the cell holding the centre, so that a
// hole smaller than a 90 m cell still removes one.
std::string write_int16_dem(const std::filesystem::path& path, double x0, double y0, double x1, double y1,
                            double cell_m, const std::function<double(const Vec2&)>& ground,
                            const std::vector<Vec2>& void_centres, const std::vector<double>& void_radii) {
  const GeoFrame frame = synthetic_frame();
  const int w = static_cast<int>(std::lround((x1 - x0) / cell_m));
  const int h = static_cast<int>(std::lround((y1 - y0) / cell_m));
  DemGrid grid =
      make_dem_grid(frame.crs(), frame.origin().x() + x0, frame.origin().y() + y1, cell_m, cell_m, w, h,
                    [&](double x, double y) {
                      const Vec2 p(x - frame.origin().x(), y - frame.origin().y());
                      for (std::size_t i = 0; i < void_centres.size(); ++i) {
                        const Vec2 d = (p - void_centres[i]).cwiseAbs();
                        if (d.norm() < void_radii[i] || (d.x() <= 0.5 * cell_m && d.y() <= 0.5 * cell_m))
                          return kNodata;
                      }
                      return std::round(ground(p));
                    });
  grid.nodata = kNodata;
  grid.data_type = DemDataType::int16;
  grid.unit_type = "m";
  write_geotiff(path.string(), grid);
  return path.string();
}

// ---------------------------------------------------------------------------------------------
// The mountain. A ridge running east-west: plain at 300 m, a V valley (30 % sides, 135 m deep)
// south of it, the south flank at 35 % from y = 0 up to the crest at y = 2400 (1140 m before
// rounding), the north flank at 35 % down to y = 4057 (560 m), then an apron at 12 %.

const Profile& mountain_profile() {
  static const Profile p{300.0,
                         {{{-1500.0, -0.30, 30.0}},
                          {{-1050.0, 0.60, 30.0}},
                          {{-600.0, -0.30, 30.0}},
                          {{0.0, 0.35, 30.0}},
                          {{2400.0, -0.70, 80.0}},
                          {{4057.0, 0.23, 30.0}},
                          {{5000.0, 0.12, 30.0}}}};
  return p;
}

double mountain_natural(const Vec2& p) {
  return mountain_profile()(p.y());
}

constexpr double kHairpinHalfWidth = 450.0;  // the legs run between x = -450 and 450
constexpr double kTrunkTop = 2300.0;         // the trunk ends where its last leg reaches this y
constexpr double kTrunkGrade = 0.09;         // designed grade of the climb
constexpr double kTunnelX = 1500.0;
constexpr double kTunnelRise = 0.005;  // the main tunnel rises northward at 0.5 % (drainage)

struct Trunk {
  Polyline2 line;
  std::vector<double> z;                     // designed heights
  std::size_t loop_start = 0, loop_end = 0;  // the spiral's bridge: points [loop_start, loop_end]
  std::vector<std::size_t> east_apexes;      // midpoints of the hairpins at the east end
  Vec2 crossing = Vec2::Zero();
  double crossing_clearance = 0.0;
  double climb = 0.0;
  double end_mismatch = 0.0;  // designed minus natural height at the top
};

// The trunk for legs at `theta` off the contour: up from the valley road, a first leg east along
// the foot, a spiral hairpin (a 270 degree loop on the valley side that crosses back over the
// first leg on a bridge, which ends where the deck meets the ground), then hairpins of 25 m
// radius between x = -450 and 450 up to y = kTrunkTop. The designed profile follows the plain to
// the first leg, then climbs at kTrunkGrade.
Trunk trace_trunk(double theta) {
  Trunk t;
  Path path(Vec2(0.0, -300.0), 0.5 * kPi);
  path.straight(260.0, 20.0);
  path.arc(60.0, -(0.5 * kPi - theta));
  const std::size_t climb_start = path.size() - 1;
  const double z_start = mountain_natural(path.end());
  const auto design = [&](double s, double s_start) { return z_start + kTrunkGrade * (s - s_start); };
  path.straight((kHairpinHalfWidth - path.end().x()) / std::cos(theta), 20.0);
  t.loop_start = path.size() - 1;
  const Vec2 loop_entry = path.end();
  const Vec2 leg_dir(std::cos(theta), std::sin(theta));
  const Vec2 leg_normal(-leg_dir.y(), leg_dir.x());  // uphill side of the first leg
  path.arc(50.0, -1.5 * kPi, 5.0);
  // North across the first leg, on until the deck has come down to the ground.
  std::vector<double> s = arc_lengths(path.points());
  const double s_climb = s[climb_start];
  std::size_t cross = 0;
  while (true) {
    path.straight(10.0, 10.0);
    s.push_back(s.back() + 10.0);
    const double side = (path.end() - loop_entry).dot(leg_normal);
    if (cross == 0 && side >= 0.0) cross = path.size() - 1;
    if (cross != 0 && (path.end() - path.points()[cross]).norm() >= 30.0 &&
        design(s.back(), s_climb) <= mountain_natural(path.end()))
      break;
  }
  t.loop_end = path.size() - 1;
  path.arc(30.0, 0.5 * kPi - 2.0 * theta, 2.5);  // to the second leg, heading west
  bool east = false;
  while (true) {
    const double target_x = east ? kHairpinHalfWidth : -kHairpinHalfWidth;
    const double length = std::abs(target_x - path.end().x()) / std::cos(theta);
    if (path.end().y() + length * std::sin(theta) >= kTrunkTop) {
      path.straight((kTrunkTop - path.end().y()) / std::sin(theta), 20.0);
      break;
    }
    path.straight(length, 20.0);
    const std::size_t before = path.size() - 1;
    path.arc(25.0, (east ? 1.0 : -1.0) * (kPi - 2.0 * theta), 2.5);
    if (east) t.east_apexes.push_back((before + path.size() - 1) / 2);
    east = !east;
  }
  t.line = path.points();
  s = arc_lengths(t.line);
  for (std::size_t i = 0; i < t.line.size(); ++i)
    t.z.push_back(i <= climb_start ? mountain_natural(t.line[i]) : design(s[i], s_climb));
  t.climb = t.z.back() - z_start;
  t.end_mismatch = t.z.back() - mountain_natural(t.line.back());
  t.crossing = t.line[cross];
  // The lower pass: the first leg's point under the crossing (before the loop's start).
  const double s_lower = s[t.loop_start] + (t.crossing - loop_entry).dot(leg_dir);
  t.crossing_clearance = t.z[cross] - design(s_lower, s_climb);
  return t;
}

// The trunk whose designed top meets the ground: the legs' angle by bisection (a flatter leg
// makes a longer road, which climbs more at the same grade).
const Trunk& mountain_trunk() {
  static const Trunk trunk =
      trace_trunk(bisect([](double theta) { return trace_trunk(theta).end_mismatch; }, 0.05, 0.6));
  return trunk;
}

struct MountainWorld {
  MountainFeatures features;
  RoadBeds beds{mountain_natural};
  std::vector<Vec2> void_centres;
  std::vector<double> void_radii;
  std::string osm_xml;
  std::size_t ways = 0;
  double road_km = 0.0;
};

Polyline2 straight_line(const Vec2& a, const Vec2& b, double step_m) {
  const int n = std::max(1, static_cast<int>(std::ceil((b - a).norm() / step_m)));
  Polyline2 line;
  for (int i = 0; i <= n; ++i) line.push_back(a + (b - a) * (static_cast<double>(i) / n));
  return line;
}

Polyline2 slice(const Polyline2& line, std::size_t from, std::size_t to) {
  return Polyline2(line.begin() + static_cast<std::ptrdiff_t>(from),
                   line.begin() + static_cast<std::ptrdiff_t>(to) + 1);
}

// The valley road's two end nodes: where copies of the mountain side by side are linked.
struct ValleyEnds {
  std::int64_t west = 0, east = 0;
};
constexpr double kValleyWest = -900.0, kValleyEast = 2200.0, kValleyY = -300.0;

// Writes one mountain into `osm` (at its offset) and sets w's features (way ids of this copy),
// road beds and voids (in the mountain's own frame).
ValleyEnds add_mountain(OsmWriter& osm, MountainWorld& w) {
  MountainFeatures& f = w.features;
  const Trunk& trunk = mountain_trunk();
  f.crest_m = mountain_natural(Vec2(0.0, 2400.0));
  f.trunk_design_grade = kTrunkGrade;
  f.trunk_climb_m = trunk.climb;
  f.loop_crossing = trunk.crossing;
  f.loop_design_clearance_m = trunk.crossing_clearance;
  double sum = 0.0;
  std::size_t count = 0;
  for (std::size_t i = 0; i < trunk.line.size(); ++i) {
    if (i > trunk.loop_start && i < trunk.loop_end) continue;
    const double d = trunk.z[i] - mountain_natural(trunk.line[i]);
    sum += d * d;
    ++count;
    f.trunk_cut_fill_max_m = std::max(f.trunk_cut_fill_max_m, std::abs(d));
  }
  f.trunk_cut_fill_rms_m = std::sqrt(sum / static_cast<double>(count));

  // The valley road along the plain, with the trunk's and the viaduct's junctions.
  const std::int64_t valley_west = osm.node(Vec2(kValleyWest, kValleyY));
  std::vector<std::int64_t> trunk_ids = osm.nodes(trunk.line);
  const std::int64_t valley_east = osm.node(Vec2(kValleyEast, kValleyY));
  Polyline2 valley_line = straight_line(Vec2(kValleyWest, kValleyY), Vec2(kValleyEast, kValleyY), 100.0);
  std::vector<std::int64_t> valley_ids;
  std::int64_t viaduct_top = 0;
  for (const Vec2& p : valley_line) {
    if (p.x() == kValleyWest) {
      valley_ids.push_back(valley_west);
    } else if (p.x() == kValleyEast) {
      valley_ids.push_back(valley_east);
    } else if (std::abs(p.x()) < 1e-6) {
      valley_ids.push_back(trunk_ids.front());
    } else {
      valley_ids.push_back(osm.node(p));
      if (std::abs(p.x() - kTunnelX) < 1e-6) viaduct_top = valley_ids.back();
    }
  }
  osm.way(valley_ids, {{"highway", "secondary"}, {"name", "Valley Road"}}, valley_line);
  w.beds.add(valley_line, std::vector<double>(valley_line.size(), 300.0));

  // The trunk: to the loop, the loop's bridge, the climb.
  const auto ids = [&](std::size_t a, std::size_t b) {
    return std::vector<std::int64_t>(trunk_ids.begin() + static_cast<std::ptrdiff_t>(a),
                                     trunk_ids.begin() + static_cast<std::ptrdiff_t>(b) + 1);
  };
  const OsmWriter::Tags trunk_tags{{"highway", "trunk"}, {"name", "Pass Road"}, {"lanes", "2"}};
  OsmWriter::Tags bridge_tags = trunk_tags;
  bridge_tags.insert(bridge_tags.end(), {{"bridge", "yes"}, {"layer", "1"}});
  const std::size_t last = trunk.line.size() - 1;
  f.trunk.way_ids.push_back(
      osm.way(ids(0, trunk.loop_start), trunk_tags, slice(trunk.line, 0, trunk.loop_start)));
  f.loop_bridge_way = osm.way(ids(trunk.loop_start, trunk.loop_end), bridge_tags,
                              slice(trunk.line, trunk.loop_start, trunk.loop_end));
  f.trunk.way_ids.push_back(f.loop_bridge_way);
  f.trunk.way_ids.push_back(
      osm.way(ids(trunk.loop_end, last), trunk_tags, slice(trunk.line, trunk.loop_end, last)));
  f.trunk.centreline = trunk.line;
  w.beds.add(slice(trunk.line, 0, trunk.loop_start),
             std::vector<double>(trunk.z.begin(),
                                 trunk.z.begin() + static_cast<std::ptrdiff_t>(trunk.loop_start) + 1));
  w.beds.add(
      slice(trunk.line, trunk.loop_end, last),
      std::vector<double>(trunk.z.begin() + static_cast<std::ptrdiff_t>(trunk.loop_end), trunk.z.end()));

  // The road along the contour from the east hairpin nearest 560 m to the tunnel's south portal.
  std::size_t apex = trunk.east_apexes.front();
  for (const std::size_t a : trunk.east_apexes)
    if (std::abs(trunk.z[a] - 560.0) < std::abs(trunk.z[apex] - 560.0)) apex = a;
  const double z_tunnel = trunk.z[apex];
  const double y_south = bisect([&](double y) { return mountain_profile()(y) - z_tunnel; }, 0.0, 2400.0);
  const Vec2 south_portal(kTunnelX, y_south);
  Polyline2 contour{trunk.line[apex]};
  for (const Vec2& p : straight_line(trunk.line[apex] + Vec2(60.0, 0.0), south_portal, 50.0))
    contour.push_back(p);
  std::vector<std::int64_t> contour_ids{trunk_ids[apex]};
  for (std::size_t i = 1; i < contour.size(); ++i) contour_ids.push_back(osm.node(contour[i]));
  osm.way(contour_ids, {{"highway", "secondary"}, {"name", "Portal Road"}}, contour);
  w.beds.add(contour, std::vector<double>(contour.size(), z_tunnel));

  // The base tunnel: north, rising at 0.5 %, a junction under the crest, a side branch to a
  // portal of its own on the north flank (both portals short of the apron's roundabout).
  const auto tunnel_z = [&](double y) { return z_tunnel + kTunnelRise * (y - y_south); };
  const double y_north =
      bisect([&](double y) { return mountain_profile()(y) - tunnel_z(y); }, 2400.0, 5000.0);
  const Vec2 inner(kTunnelX, 2400.0);
  const Vec2 north_portal(kTunnelX, y_north);
  const double z_inner = tunnel_z(2400.0);
  const double y_branch = bisect([&](double y) { return mountain_profile()(y) - z_inner; }, 2400.0, 5000.0);
  const Vec2 branch_portal(2050.0, y_branch);
  const OsmWriter::Tags tunnel_tags{
      {"highway", "primary"}, {"tunnel", "yes"}, {"layer", "-1"}, {"name", "Base Tunnel"}};
  const Polyline2 south_half = straight_line(south_portal, inner, 100.0);
  const Polyline2 north_half = straight_line(inner, north_portal, 100.0);
  Polyline2 branch = straight_line(inner, Vec2(1800.0, 2520.0), 100.0);
  for (const Vec2& p : straight_line(Vec2(1800.0, 2520.0), branch_portal, 100.0)) {
    if (p != branch.back()) branch.push_back(p);
  }
  std::vector<std::int64_t> south_ids = osm.nodes(south_half);
  south_ids.front() = contour_ids.back();
  std::vector<std::int64_t> north_ids = osm.nodes(north_half);
  north_ids.front() = south_ids.back();
  std::vector<std::int64_t> branch_ids = osm.nodes(branch);
  branch_ids.front() = south_ids.back();
  f.tunnel_ways.push_back(osm.way(south_ids, tunnel_tags, south_half));
  f.tunnel_ways.push_back(osm.way(north_ids, tunnel_tags, north_half));
  OsmWriter::Tags branch_tags = tunnel_tags;
  branch_tags.back().second = "Base Tunnel Branch";
  f.tunnel_ways.push_back(osm.way(branch_ids, branch_tags, branch));
  f.tunnel_portals = {south_portal, north_portal, branch_portal};

  // The roundabout on the 12 % apron and its four arms.
  f.roundabout_centre = Vec2(kTunnelX, 4500.0);
  f.roundabout_radius_m = 25.0;
  f.roundabout_slope = 0.12;
  Polyline2 ring;
  for (int k = 0; k <= 16; ++k) {
    const double a = 2.0 * kPi * k / 16.0;
    ring.push_back(f.roundabout_centre + f.roundabout_radius_m * Vec2(std::cos(a), std::sin(a)));
  }
  std::vector<std::int64_t> ring_ids = osm.nodes(Polyline2(ring.begin(), ring.end() - 1));
  ring_ids.push_back(ring_ids.front());
  osm.way(ring_ids, {{"highway", "secondary"}, {"junction", "roundabout"}, {"oneway", "yes"}}, ring);
  const std::int64_t ring_east = ring_ids[0], ring_north = ring_ids[4], ring_west = ring_ids[8],
                     ring_south = ring_ids[12];
  const auto arm = [&](const Polyline2& line, std::int64_t first, std::int64_t last_id) {
    std::vector<std::int64_t> arm_ids = osm.nodes(line);
    if (first != 0) arm_ids.front() = first;
    if (last_id != 0) arm_ids.back() = last_id;
    osm.way(arm_ids, {{"highway", "secondary"}}, line);
  };
  arm(straight_line(north_portal, ring[12], 50.0), north_ids.back(), ring_south);
  arm(straight_line(ring[4], ring[4] + Vec2(0.0, 350.0), 50.0), ring_north, 0);
  arm(straight_line(ring[8], ring[8] - Vec2(400.0, 0.0), 50.0), ring_west, 0);
  Polyline2 east_arm = straight_line(branch_portal, Vec2(branch_portal.x(), 4500.0), 50.0);
  for (const Vec2& p : straight_line(Vec2(branch_portal.x(), 4500.0), ring[0], 50.0)) {
    if (p != east_arm.back()) east_arm.push_back(p);
  }
  arm(east_arm, branch_ids.back(), ring_east);

  // The viaduct: south across the valley, a bridge between its rims.
  f.viaduct_abutment_south = Vec2(kTunnelX, -1560.0);
  f.viaduct_abutment_north = Vec2(kTunnelX, -540.0);
  const Polyline2 approach = straight_line(Vec2(kTunnelX, -2050.0), f.viaduct_abutment_south, 50.0);
  const Polyline2 deck = straight_line(f.viaduct_abutment_south, f.viaduct_abutment_north, 60.0);
  const Polyline2 ramp = straight_line(f.viaduct_abutment_north, Vec2(kTunnelX, -300.0), 60.0);
  std::vector<std::int64_t> approach_ids = osm.nodes(approach);
  std::vector<std::int64_t> deck_ids = osm.nodes(deck);
  deck_ids.front() = approach_ids.back();
  std::vector<std::int64_t> ramp_ids = osm.nodes(ramp);
  ramp_ids.front() = deck_ids.back();
  ramp_ids.back() = viaduct_top;
  const OsmWriter::Tags viaduct_tags{{"highway", "primary"}, {"name", "Valley Viaduct"}};
  OsmWriter::Tags deck_tags = viaduct_tags;
  deck_tags.insert(deck_tags.end(), {{"bridge", "yes"}, {"layer", "1"}});
  osm.way(approach_ids, viaduct_tags, approach);
  f.viaduct_way = osm.way(deck_ids, deck_tags, deck);
  osm.way(ramp_ids, viaduct_tags, ramp);

  // Voids of 24..100 m: on a trunk leg, on the valley road, under the viaduct, on the
  // roundabout's west arm, on the crest over the tunnel.
  const std::vector<double> s = arc_lengths(trunk.line);
  std::size_t on_leg = 0;
  while (s[on_leg] < 0.4 * s.back()) ++on_leg;
  w.void_centres = {trunk.line[on_leg], Vec2(-500.0, -300.0), Vec2(kTunnelX, -1050.0), Vec2(1250.0, 4500.0),
                    Vec2(kTunnelX, 2400.0)};
  w.void_radii = {30.0, 12.0, 50.0, 20.0, 40.0};
  return {valley_west, valley_east};
}

const MountainWorld& mountain_world() {
  static const MountainWorld world = [] {
    MountainWorld w;
    OsmWriter osm;
    (void)add_mountain(osm, w);
    w.ways = osm.count();
    w.road_km = osm.length_km();
    w.osm_xml = osm.xml();
    return w;
  }();
  return world;
}

// ---------------------------------------------------------------------------------------------
// The old town: a coast rising north from the shore (y = 0) at 20 %, a hill of 50 m on it
// around (150, 480) that a tunnel passes under.

constexpr double kCoastSlope = 0.20;

double old_town_ground(const Vec2& p) {
  const double dx = p.x() - 150.0, dy = p.y() - 480.0;
  return kCoastSlope * soft_ramp(p.y(), 10.0) +
         50.0 * std::exp(-(dx * dx / (2.0 * 60.0 * 60.0) + dy * dy / (2.0 * 70.0 * 70.0)));
}

struct OldTownWorld {
  OldTownFeatures features;
  std::string osm_xml;
  std::size_t ways = 0;
  double road_km = 0.0;
};

const OldTownWorld& old_town_world() {
  static const OldTownWorld world = [] {
    OldTownWorld w;
    OldTownFeatures& f = w.features;
    f.slope = kCoastSlope;
    OsmWriter osm;
    // Grid nodes: columns x = 35 c (c = 0..8), rows y = 40 + 40 r (r = 0..7); the two shore
    // streets at y = 10 and 14 meet the columns 0, 4 and 8.
    std::map<std::pair<int, int>, std::int64_t> at;  // (x, y) in metres -> node
    const auto node = [&](int x, int y) {
      const auto it = at.find({x, y});
      if (it != at.end()) return it->second;
      return at[{x, y}] = osm.node(Vec2(x, y));
    };
    static const char* const kClasses[] = {"residential", "living_street", "service"};
    static const char* const kWidths[] = {"3", "4", "5"};
    for (int r = 0; r < 8; ++r) {  // streets along the slope, one-way east and west in turn
      std::vector<std::int64_t> refs;
      Polyline2 line;
      for (int c = 0; c <= 8; ++c) {
        refs.push_back(node(35 * c, 40 + 40 * r));
        line.emplace_back(35 * c, 40 + 40 * r);
      }
      if (r % 2 == 1) std::reverse(refs.begin(), refs.end());
      f.oneway_ways.push_back(osm.way(
          refs, {{"highway", kClasses[r % 3]}, {"oneway", "yes"}, {"lanes", "1"}, {"width", kWidths[r % 3]}},
          line));
    }
    for (int c = 0; c <= 8; ++c) {  // streets up the 20 % slope, one-way up and down in turn
      std::vector<std::int64_t> refs;
      Polyline2 line;
      if (c % 4 == 0) {
        refs = {node(35 * c, 10), node(35 * c, 14)};
        line = {Vec2(35 * c, 10), Vec2(35 * c, 14)};
      }
      for (int r = 0; r < 8; ++r) {
        refs.push_back(node(35 * c, 40 + 40 * r));
        line.emplace_back(35 * c, 40 + 40 * r);
      }
      if (c % 2 == 1) std::reverse(refs.begin(), refs.end());
      f.oneway_ways.push_back(osm.way(
          refs,
          {{"highway", kClasses[(c + 1) % 3]}, {"oneway", "yes"}, {"lanes", "1"}, {"width", kWidths[c % 3]}},
          line));
    }
    // Two quays 4 m apart, each 6 m wide: closer than their widths.
    for (const int y : {10, 14}) {
      std::vector<std::int64_t> refs;
      Polyline2 line;
      for (int c = 0; c <= 8; c += 4) {
        refs.push_back(node(35 * c, y));
        line.emplace_back(35 * c, y);
      }
      if (y == 14) std::reverse(refs.begin(), refs.end());
      f.close_pair.push_back(
          osm.way(refs, {{"highway", "residential"}, {"oneway", "yes"}, {"width", "6"}}, line));
    }
    // The tunnel under the hill, level, its mouths where the hill has come down to 5 m over the
    // slope; a junction at each mouth (a street on to the grid, a street away).
    const double half = std::sqrt(2.0 * 60.0 * 60.0 * std::log(10.0));
    const Vec2 west(150.0 - half, 480.0), east(150.0 + half, 480.0);
    f.tunnel_portals = {west, east};
    const Polyline2 bore = straight_line(west, east, 25.0);
    std::vector<std::int64_t> bore_ids = osm.nodes(bore);
    f.tunnel_ways.push_back(osm.way(
        bore_ids, {{"highway", "tertiary"}, {"tunnel", "yes"}, {"layer", "-1"}, {"width", "7"}}, bore));
    const auto street = [&](const Polyline2& line, std::int64_t first, std::int64_t last) {
      std::vector<std::int64_t> refs = osm.nodes(line);
      refs.front() = first;
      if (last != 0) refs.back() = last;
      osm.way(refs, {{"highway", "tertiary"}, {"width", "6"}}, line);
    };
    street(straight_line(west, Vec2(-60.0, 480.0), 20.0), bore_ids.front(), 0);
    street(straight_line(west, Vec2(35.0, 320.0), 20.0), bore_ids.front(), node(35, 320));
    street(straight_line(east, Vec2(360.0, 480.0), 20.0), bore_ids.back(), 0);
    street(straight_line(east, Vec2(280.0, 320.0), 20.0), bore_ids.back(), node(280, 320));
    // Steps up a block and a footway ramp (relief builds them only with include_non_motor).
    f.path_ways.push_back(
        osm.way({node(0, 40), osm.node(Vec2(17.5, 45.0)), osm.node(Vec2(17.5, 75.0)), node(0, 80)},
                {{"highway", "steps"}}, {Vec2(0, 40), Vec2(17.5, 45), Vec2(17.5, 75), Vec2(0, 80)}));
    f.path_ways.push_back(osm.way({node(70, 80), osm.node(Vec2(52.5, 100.0)), node(70, 120)},
                                  {{"highway", "footway"}, {"ramp", "yes"}, {"incline", "up"}},
                                  {Vec2(70, 80), Vec2(52.5, 100), Vec2(70, 120)}));
    w.ways = osm.count();
    w.road_km = osm.length_km();
    w.osm_xml = osm.xml();
    return w;
  }();
  return world;
}

}  // namespace

const MountainFeatures& mountain_features() {
  return mountain_world().features;
}

CorpusCase make_mountain(double cell_m, const std::filesystem::path& dir) {
  const MountainWorld& w = mountain_world();
  CorpusCase c;
  c.cell_m = cell_m;
  c.osm = dir / "mountain.osm";
  std::ofstream(c.osm) << w.osm_xml;
  c.ways = w.ways;
  c.road_km = w.road_km;
  c.ground = [&w](const Vec2& p) { return w.beds(p); };
  c.void_centres = w.void_centres;
  c.void_radii_m = w.void_radii;
  const auto dem = dir / ("mountain_" + std::to_string(static_cast<int>(cell_m)) + "m.tif");
  if (cell_m < 10.0) {
    // The hairpins only (1.28 x 2.52 km): roads clipped to a lon/lat box inside the DEM's edge
    // by 60 m (the UTM grid turns by under half a degree against the meridians here).
    const double x0 = -640.0, y0 = -120.0, x1 = 640.0, y1 = 2400.0, inset = 60.0;
    const OsmWriter osm;
    const LonLat sw = osm.lonlat(Vec2(x0 + inset, y0 + inset)), se = osm.lonlat(Vec2(x1 - inset, y0 + inset));
    const LonLat nw = osm.lonlat(Vec2(x0 + inset, y1 - inset)), ne = osm.lonlat(Vec2(x1 - inset, y1 - inset));
    c.bbox = LonLatBox{std::max(sw.lon_deg, nw.lon_deg), std::max(sw.lat_deg, se.lat_deg),
                       std::min(se.lon_deg, ne.lon_deg), std::min(nw.lat_deg, ne.lat_deg)};
    c.dem = write_int16_dem(dem, x0, y0, x1, y1, cell_m, c.ground, c.void_centres, c.void_radii_m);
  } else {
    c.dem = write_int16_dem(dem, -1100.0, -2250.0, 2400.0, 5050.0, cell_m, c.ground, c.void_centres,
                            c.void_radii_m);
  }
  return c;
}

CorpusCase make_mountain_range(int copies, double cell_m, const std::filesystem::path& dir) {
  if (copies < 1) throw std::invalid_argument("make_mountain_range: copies must be at least 1");
  // The ridge's terrain varies with y only, so copies kPitch apart in x join seamlessly;
  // each valley road is linked to the next by a 400 m road on the plain.
  constexpr double kPitch = 3500.0, kWest = -1100.0, kSouth = -2250.0, kNorth = 5050.0;
  const MountainWorld& one = mountain_world();
  OsmWriter osm;
  CorpusCase c;
  std::int64_t previous_east = 0;
  for (int i = 0; i < copies; ++i) {
    const Vec2 offset(kPitch * i, 0.0);
    osm.set_offset(offset);
    MountainWorld copy;
    const ValleyEnds ends = add_mountain(osm, copy);
    if (i > 0) {
      osm.set_offset(Vec2::Zero());
      const Polyline2 link = straight_line(Vec2(kValleyEast + kPitch * (i - 1), kValleyY),
                                           Vec2(kValleyWest + kPitch * i, kValleyY), 100.0);
      std::vector<std::int64_t> ids = osm.nodes(link);
      ids.front() = previous_east;
      ids.back() = ends.west;
      osm.way(ids, {{"highway", "secondary"}, {"name", "Valley Link"}}, link);
    }
    previous_east = ends.east;
    for (std::size_t k = 0; k < one.void_centres.size(); ++k) {
      c.void_centres.push_back(one.void_centres[k] + offset);
      c.void_radii_m.push_back(one.void_radii[k]);
    }
  }
  c.cell_m = cell_m;
  c.osm = dir / "mountain_range.osm";
  std::ofstream(c.osm) << osm.xml();
  c.ways = osm.count();
  c.road_km = osm.length_km();
  c.ground = [&one, copies](const Vec2& p) {
    const int i = std::clamp(static_cast<int>(std::floor((p.x() - kWest) / kPitch)), 0, copies - 1);
    return one.beds(p - Vec2(kPitch * i, 0.0));
  };
  c.dem = write_int16_dem(dir / ("mountain_range_" + std::to_string(static_cast<int>(cell_m)) + "m.tif"),
                          kWest, kSouth, kWest + kPitch * copies, kNorth, cell_m, c.ground, c.void_centres,
                          c.void_radii_m);
  return c;
}

const OldTownFeatures& old_town_features() {
  return old_town_world().features;
}

CorpusCase make_old_town(const std::filesystem::path& dir) {
  const OldTownWorld& w = old_town_world();
  CorpusCase c;
  c.cell_m = 30.0;
  c.osm = dir / "old_town.osm";
  std::ofstream(c.osm) << w.osm_xml;
  c.ways = w.ways;
  c.road_km = w.road_km;
  c.ground = old_town_ground;
  c.void_centres = {Vec2(105.0, 200.0)};
  c.void_radii_m = {20.0};
  c.dem = write_int16_dem(dir / "old_town_30m.tif", -250.0, -200.0, 560.0, 700.0, 30.0, c.ground,
                          c.void_centres, c.void_radii_m);
  return c;
}

}  // namespace relief::test
