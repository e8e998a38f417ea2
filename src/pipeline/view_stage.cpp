#include "pipeline/view_stage.h"

#include <system_error>

#include "relief/core/errors.h"

namespace relief {

ViewStage write_view_tiles(const MeshStageInput& in, const Scene& built, OutputSet& files, StageTimer& timer,
                           std::vector<std::filesystem::path>& written) {
  const std::filesystem::path dir = in.options.out_dir / "view";
  std::error_code error;
  const bool created = std::filesystem::create_directories(dir, error);
  if (error) throw IoError("cannot create '" + dir.string() + "': " + error.message());
  ViewStage stage;
  if (created) stage.folder = CreatedFolder(dir);
  stage.failed_junctions = built.roads.failed_junctions;
  timer.run("write view tiles", [&] {
    stage.tiles = view_tiles(built, in.dem, [&](const std::string& filename, const std::string& script) {
      files.add(dir / filename, [&](std::ostream& out) { out << script; });
      written.push_back(dir / filename);
    });
    return 0;
  });
  return stage;
}

void write_view_page(const BuildOptions& options, const ViewStage& stage, ViewIndexInput input,
                     OutputSet& files, StageTimer& timer, std::vector<std::filesystem::path>& written,
                     std::vector<std::string>& names) {
  input.failed_junctions = stage.failed_junctions;
  timer.run("write view.html", [&] {
    const std::string index = view_index_script(stage.tiles, input);
    files.add(options.out_dir / "view" / "index.js", [&](std::ostream& out) { out << index; });
    files.add(options.out_dir / "view.html",
              [&](std::ostream& out) { out << view_page(input.report->name + " - relief view"); });
    return 0;
  });
  written.push_back(options.out_dir / "view" / "index.js");
  written.push_back(options.out_dir / "view.html");
  names.emplace_back("view.html");
}

}  // namespace relief
