#pragma once
// view.html: the interactive 3D view of a build, beside report.html. A person opens it by
// double-click (file://, no server, no network): three.js is bundled into the page when relief
// is compiled (src/viewer/web, esbuild), and the data come as plain <script> files, which a
// browser loads from file:// where fetch() is refused:
//   view.html               the page (the bundle inlined) and view/index.js
//   view/index.js           the frame, the tiles' bounds, every road's attributes and profiles
//                           (DEM drape, paper, fit), the findings with their places, the gates
//   view/tile_X_Y.js        one plan tile of the scene, loaded when it comes into view
// Coordinates are the local frame in three.js's axes (x east, y up, z south: the glTF files'
// convention), float32, so the view and NAME.glb agree vertex for vertex.

#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "relief/export/mesh_writer.h"
#include "relief/export/report_writer.h"
#include "relief/roads/elevation_sampling.h"
#include "relief/roads/road_model.h"
#include "relief/roads/road_network.h"
#include "relief/scene/scene.h"
#include "relief/sight/sight_distance.h"
#include "relief/terrain/dem_sampler.h"

namespace relief {

struct ViewOptions {
  /// Plan tile size; 0 picks one so that a tile holds about `tile_triangles` triangles
  /// (rounded to 250 m, 250 m to 4 km).
  double tile_size_m = 0.0;
  std::size_t tile_triangles = 60000;
  /// Tiles at least this big also get a coarse copy for distant views (tile_X_Y_lod.js): the
  /// tile's layers but the marks, vertex-clustered on cells of tile size / lod_cells_per_tile.
  double lod_min_tile_m = 1000.0;
  double lod_cells_per_tile = 400.0;
  /// Profile points kept per road and method (evenly spaced in s; the ends always kept).
  std::size_t profile_points = 400;
};

/// One tile file of the view.
struct ViewTile {
  int x = 0, y = 0;            ///< grid column (east) and row (north) from 0 at the south-west tile
  std::string filename;        ///< "tile_X_Y.js": every layer but the marks
  std::string marks_filename;  ///< "tile_X_Y_marks.js", loaded only near; empty without marks
  std::string lod_filename;    ///< "tile_X_Y_lod.js", the coarse copy for afar; empty without one
  Aabb2 bounds;                ///< plan bounds of its triangles, local frame
  double z_min = 0.0, z_max = 0.0;
  std::size_t triangles = 0, marks_triangles = 0, lod_triangles = 0;
};

/// Receives each file of a tile (its name and text) as soon as it is encoded (a city's tiles
/// are tens of MB; none is kept).
using ViewTileSink = std::function<void(const std::string& filename, const std::string& script)>;

/// The scene cut into the view's tiles, each in two files, the marks (near only) and the rest,
/// and on big tiles a coarse copy of the rest for distant views.
/// Per layer and tile: positions, indices and per vertex
/// the owner (road triangles: index into ViewTiles::owners), the surface grade in percent (the
/// steepest slope of the owner's triangles around the vertex, area-weighted: on a lofted lane
/// without superelevation this is the road's grade) and the height over the DEM in metres (NaN
/// where the DEM has none). Layers: "road" (Road_Road on the ground), "structure" (Road_Road off
/// the ground: decks, tunnels), "marking", "sidewalk", "terrain". Linear in the triangles.
struct ViewTiles {
  double tile_size_m = 0.0;
  std::vector<ViewTile> tiles;  ///< row-major (y, then x)
  std::vector<int> owners;      ///< OpenDRIVE road id, or -1 - junction id (RoadMeshes's convention)
  std::size_t triangles = 0;
};

/// Throws InvalidInput for options out of range.
[[nodiscard]] ViewTiles view_tiles(const Scene& scene, const DemSampler& dem, const ViewTileSink& write,
                                   const ViewOptions& options = {});

struct ViewIndexInput {
  const RunReport* report = nullptr;                   ///< required: frame, gates, figures
  const RoadModel* model = nullptr;                    ///< required
  const RoadNetwork* network = nullptr;                ///< required
  const std::vector<RoadProfile>* raw = nullptr;       ///< required, parallel to network->roads
  const std::vector<RoadProfile>* paper = nullptr;     ///< optional
  const std::vector<RoadProfile>* fitted = nullptr;    ///< optional
  const SightResult* sight = nullptr;                  ///< optional: sight deficits as findings
  std::vector<std::pair<int, Vec3>> failed_junctions;  ///< RoadMeshes::failed_junctions
};

/// A finding the view marks and lists.
struct ViewFinding {
  std::string kind;  ///< "gate", "self_intersection", "hole", "junction_open", "sight"
  std::string text;
  std::optional<Vec3> at;  ///< local frame; none: listed without a marker (a gate without a place)
  int road = 0;            ///< OpenDRIVE road id when known, else 0
};

/// Every finding of a build, located where the build knows the place: failed gates (placed when
/// their text ends with "(x, y, z)", as quality_gates.cpp writes a worst place),
/// self-intersections and holes of Road_Road and Terrain (report->mesh), junctions left open,
/// sight deficits (the middle of each short stretch).
[[nodiscard]] std::vector<ViewFinding> view_findings(const ViewIndexInput& input);

/// view/index.js: `window.RELIEF_VIEW = {...}` with the tiles (from `tiles`), roads, profiles, findings and
/// gates. Throws InvalidInput when a required input is null or a profile set is not parallel to the network's
/// roads.
[[nodiscard]] std::string view_index_script(const ViewTiles& tiles, const ViewIndexInput& input,
                                            const ViewOptions& options = {});

/// Where a page finds its data, and what it adds.
struct ViewPageOptions {
  std::string data_dir = "view";       ///< the folder of index.js and the tiles, relative to the page
  std::string report = "report.html";  ///< the page the header links to
  std::vector<std::string> scripts;    ///< more scripts loaded after index.js (e.g. "replay.js")
};

/// view.html: the page, with the viewer's bundle and style inlined; it loads DATA/index.js and
/// the tiles from DATA. Throws InvalidInput for a path with a quote, '<', '>' or a backslash.
[[nodiscard]] std::string view_page(const std::string& title, const ViewPageOptions& options = {});

/// replay.js of a co-simulation: `window.RELIEF_REPLAY = {end_s, vehicles: [{id, size: [length,
/// width, height], hide_s, keys}]}`, keys base64 float32 (t, x, y, z, heading, pitch, roll) per
/// key, local frame, radians. Tracks without keys are left out.
[[nodiscard]] std::string view_replay_script(const std::vector<ReplayTrack>& tracks);

}  // namespace relief
