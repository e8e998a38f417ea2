#pragma once
// Meshes with exact answers for the geometry tests: grids of unit squares.

#include "relief/geometry/triangle_mesh.h"

namespace relief::test {

/// Appends an nx x ny grid of 1 m squares (two triangles each, counter-clockwise seen from
/// above) from (x0, y0) at height z, with vertices of its own.
void add_grid(TriangleMesh& mesh, double x0, double y0, int nx, int ny, double z);

}  // namespace relief::test
