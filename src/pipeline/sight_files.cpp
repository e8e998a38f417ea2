#include "relief/pipeline/sight_files.h"

#include <chrono>

#include "relief/core/atomic_file.h"
#include "relief/core/errors.h"
#include "relief/export/mesh_writer.h"
#include "relief/roads/opendrive_reader.h"

namespace relief {

SightFilesResult sight_from_files(const std::filesystem::path& xodr, std::filesystem::path scene,
                                  const std::filesystem::path& out_dir, const SightOptions& options) {
  const std::string name = xodr.stem().string();
  if (scene.empty()) scene = xodr.parent_path() / (name + ".glb");
  if (!std::filesystem::exists(xodr)) throw IoError("'" + xodr.string() + "' does not exist");
  if (!std::filesystem::exists(scene))
    throw IoError("'" + scene.string() +
                  "' does not exist (the scene: pass --scene, or build with the mesh output)");
  const RoadModel model = read_opendrive(xodr);
  if (model.frame.crs().empty())
    throw InvalidInput("'" + xodr.string() +
                       "' has no geoReference: its stretches cannot be placed in WGS84");
  const MeshScene obstacles = read_mesh_file(scene);
  const auto start = std::chrono::steady_clock::now();
  const SightResult result = sight_distances(model, obstacles, options);
  SightFilesResult out;
  out.summary = summarize_sight(result, model, model.frame, options);
  out.summary.file = name + ".sight.geojson";
  out.summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::error_code ec;
  std::filesystem::create_directories(out_dir, ec);
  if (ec) throw IoError("cannot create the output directory '" + out_dir.string() + "': " + ec.message());
  OutputSet files;
  files.add(out_dir / out.summary.file,
            [&](std::ostream& o) { write_sight_geojson(o, result, model, model.frame); });
  files.add(out_dir / "sight.json", [&](std::ostream& o) { o << sight_summary_json(out.summary); });
  files.commit();
  out.written = {out_dir / out.summary.file, out_dir / "sight.json"};
  return out;
}

}  // namespace relief
