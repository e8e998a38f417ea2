#pragma once
// OsmSketch: an ASCII-art road network turned into an OSM XML file, so that topology tests
// read like the network they test.
//
//   OsmSketch(R"(
//       A---B---C
//           |
//           D
//   )", /*grid_m=*/10.0)
//     .way("ABC", {{"highway", "residential"}})
//     .way("BD", {{"highway", "service"}, {"oneway", "yes"}})
//     .node_tags('B', {{"highway", "traffic_signals"}})
//     .write(path);
//
// Layout: every letter (A-Z, a-z, each at most once) is a node at its character position;
// every other character is decoration. Column c is c * grid_m metres east, row r is
// r * 2 * grid_m metres south (text rows are about twice as tall as columns are wide), counted
// from the first non-blank line and the smallest indentation. Positions are placed around
// `origin` (default lon -122.40, lat 37.75, San Francisco) with a local equirectangular
// approximation on the WGS84 ellipsoid (meridian and prime-vertical radii at the origin),
// then rounded to 1e-7 degrees as OSM stores them.
// Node ids are 1000 + letter index (A = 1000 ... Z = 1025, a = 1026 ... z = 1051); way ids are
// 1, 2, ... in the order of way() calls unless given.

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "relief/geometry/types.h"

namespace relief::test {

/// The WGS84 position `east_m` east and `north_m` north of `origin` on a sphere of radius
/// 6371008.8 m (equirectangular: good to millimetres over a few hundred metres), for tests that
/// draw OsmWay records in metres.
[[nodiscard]] LonLat offset_lonlat(const LonLat& origin, double east_m, double north_m);

class OsmSketch {
 public:
  using Tags = std::vector<std::pair<std::string, std::string>>;

  explicit OsmSketch(std::string_view art, double grid_m = 10.0, LonLat origin = {-122.40, 37.75});

  /// Adds a way through the nodes named by `letters`, in order. Throws std::invalid_argument
  /// for a letter that is not in the sketch.
  OsmSketch& way(std::string_view letters, Tags tags, std::optional<std::int64_t> id = std::nullopt);
  /// Adds tags to the node `letter`.
  OsmSketch& node_tags(char letter, Tags tags);
  /// Writes a <bounds> element with this box.
  OsmSketch& bounds(const LonLatBox& box);

  /// The OSM XML text.
  [[nodiscard]] std::string xml() const;
  /// Writes xml() to `path` and returns `path`. Throws std::runtime_error when it cannot.
  std::filesystem::path write(const std::filesystem::path& path) const;

  [[nodiscard]] static std::int64_t node_id(char letter);
  /// Position of `letter` as written to the file (rounded to 1e-7 degrees).
  [[nodiscard]] LonLat lonlat(char letter) const;
  /// Exact grid offset of `letter` from the origin: x metres east, y metres north.
  [[nodiscard]] Vec2 offset_m(char letter) const;
  /// Id of the i-th way added (0-based).
  [[nodiscard]] std::int64_t way_id(std::size_t i) const { return ways_.at(i).id; }

 private:
  struct Way {
    std::int64_t id;
    std::string letters;
    Tags tags;
  };

  LonLat origin_;
  std::map<char, Vec2> offsets_;  // letter -> metres east/north of the origin
  std::map<char, Tags> node_tags_;
  std::vector<Way> ways_;
  std::optional<LonLatBox> bounds_;
};

}  // namespace relief::test
