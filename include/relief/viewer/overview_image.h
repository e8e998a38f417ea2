#pragma once
// The picture report.html opens with: the scene seen from the south at an oblique angle, as the
// 3D view first shows it (roads coloured by grade on the same scale, the terrain tinted by
// height), rendered here in software (a z-buffer, Lambert shading, supersampled) so that a
// build needs no browser or GPU, and written as PNG.

#include <string>

#include "relief/geometry/triangle_mesh.h"

namespace relief {

struct OverviewImageOptions {
  int width = 1200, height = 700;  ///< pixels of the PNG
  int supersample = 2;             ///< rendered at this many times the size, then averaged
  double elevation_deg = 42.0;     ///< the view's angle below the horizon (90: straight down)
  double margin = 0.03;            ///< of the picture on each side
};

/// The PNG bytes (8-bit RGB) of `scene`'s meshes (Road_Road, Road_Marking, Road_Sidewalk and
/// Terrain by name; others grey) in an orthographic view looking north. Throws InvalidInput for
/// a size out of 16..8192 or a supersample out of 1..4.
[[nodiscard]] std::string render_overview_png(const MeshScene& scene,
                                              const OverviewImageOptions& options = {});

}  // namespace relief
