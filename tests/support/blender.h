#pragma once
// Headless Blender as an independent reader of relief's mesh files: imports each file into an
// empty scene and reports, per mesh object, what Blender made of it. Tests skip when `blender`
// is not on PATH (Blender 3.4: `blender -b --factory-startup --python script.py -- files`).

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace relief::test {

/// True when `blender` is on PATH.
[[nodiscard]] bool have_blender();

struct BlenderImports {
  /// File path (as given) -> {"file", "objects": {NAME: {"vertices", "polygons", "min": [x, y, z],
  /// "max": [x, y, z] (world space, Blender's Z up, metres), "materials": [...], "proj"
  /// (custom property "relief:proj" of the object)}}, "proj_carriers": [object names with
  /// "relief:proj"], "proj"}; or {"file", "error", "objects": {}} when the import threw.
  std::map<std::string, nlohmann::json> by_file;
  std::string output;  ///< Blender's whole console output, for failure messages
};

/// Imports each file (.fbx, .glb, .obj by extension) in one Blender run; the script goes into
/// `work_dir`. A file missing from `by_file` means Blender did not get to it (see `output`).
[[nodiscard]] BlenderImports import_in_blender(const std::vector<std::filesystem::path>& files,
                                               const std::filesystem::path& work_dir);

}  // namespace relief::test
