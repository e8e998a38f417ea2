#pragma once
// The mesh vocabulary shared by the road, junction and terrain builders, the mesh-quality
// report and the mesh writers: an indexed triangle mesh in double precision, in the local
// frame (metres, x east, y north, z up). Writers convert to float and to the target
// format's axes only when they write (export/mesh_writer.h).

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "relief/geometry/geo_frame.h"
#include "relief/geometry/types.h"

namespace relief {

/// What a mesh is, for materials and for CARLA's classification of imported meshes.
enum class SurfaceKind { road, marking, sidewalk, shoulder, junction, terrain };

/// Indexed triangle mesh. Triangles are counter-clockwise seen from their front side (from
/// above, +z, for every surface relief builds). `normals` and `uvs` are either empty or one
/// per vertex.
struct TriangleMesh {
  std::string name;  ///< e.g. "Road_Road", "Road_Marking", "Terrain"
  SurfaceKind kind = SurfaceKind::road;
  std::vector<Vec3> vertices;
  std::vector<std::array<std::uint32_t, 3>> triangles;
  std::vector<Vec3> normals;
  std::vector<Vec2> uvs;

  [[nodiscard]] bool empty() const { return triangles.empty(); }
  /// Appends `other`'s vertices and triangles (indices shifted), and normals/uvs when both
  /// meshes carry them (dropped otherwise).
  void append(const TriangleMesh& other);
};

/// Where a file puts its own origin, for a scene far from its frame's origin (a region tile
/// 150 km out, where a float step is 1.6 cm and narrow triangles collapse or fold over). The
/// writers round x and y to whole multiples of `quantum_m` (a power of two) and write them
/// relative to `at` (whole metres), which every such value then holds exactly as a float; z
/// stays as it is. The same point gives the same value in every tile whose origins share the
/// quantum, so neighbouring tiles still share their border vertices bit for bit.
struct FileOrigin {
  Vec2 at = Vec2::Zero();  ///< local frame, whole metres
  double quantum_m = 0.0;  ///< a power of two
};

/// A set of named meshes in one frame, as written to one file.
struct MeshScene {
  GeoFrame frame;  ///< the local frame the vertices are in
  std::vector<TriangleMesh> meshes;
  std::map<std::string, std::string> metadata;  ///< e.g. "relief:proj" -> frame PROJ string
  /// Unset: files carry the local frame's coordinates as floats (half a float step is 0.24 mm
  /// at 4 km from the origin). Set: as FileOrigin says (export/mesh_writer.h).
  std::optional<FileOrigin> file_origin;
};

/// The triangles with keep[i] != 0 (keep.size() == triangles.size(), else InvalidInput), with
/// only the vertices they use (renumbered in order of first use); normals/uvs follow.
[[nodiscard]] TriangleMesh submesh(const TriangleMesh& mesh, const std::vector<std::uint8_t>& keep);

/// Closed boundary loops of a mesh: edges used by exactly one triangle, chained head to tail
/// (first vertex not repeated), as vertex indices. Where loops touch at a vertex they are
/// split there, so every loop is simple in index terms.
[[nodiscard]] std::vector<std::vector<std::uint32_t>> boundary_loops(const TriangleMesh& mesh);

/// The mesh with vertices at bit-identical positions merged into one (the first; normals and
/// UVs dropped). Files that store one vertex per triangle corner (OBJ and FBX read back with
/// assimp) regain their topology this way, and meshes that share exact positions (terrain and
/// road outline) join.
[[nodiscard]] TriangleMesh weld_identical_vertices(const TriangleMesh& mesh);

/// Area-weighted vertex normals (unit length; +z for a vertex with no non-degenerate triangle).
[[nodiscard]] std::vector<Vec3> vertex_normals(const TriangleMesh& mesh);

}  // namespace relief
