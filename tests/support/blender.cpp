#include "support/blender.h"

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

namespace relief::test {
namespace {

// One JSON line per file, prefixed so that Blender's own console lines can be told apart.
constexpr const char* kScript = R"PY(
import bpy, json, sys
import numpy
if not hasattr(numpy, "bool"):
    numpy.bool = bool  # Blender 3.4's glTF importer still uses np.bool, gone in numpy >= 1.24
files = sys.argv[sys.argv.index("--") + 1:]
for path in files:
    bpy.ops.wm.read_factory_settings(use_empty=True)
    try:
        if path.endswith(".fbx"):
            bpy.ops.import_scene.fbx(filepath=path)
        elif path.endswith(".glb"):
            bpy.ops.import_scene.gltf(filepath=path)
        else:
            bpy.ops.wm.obj_import(filepath=path)
    except Exception as e:
        print("RELIEF_JSON " + json.dumps({"file": path, "error": str(e), "objects": {}}))
        continue
    objects = {}
    for o in bpy.context.scene.objects:
        if o.type != "MESH":
            continue
        world = [o.matrix_world @ v.co for v in o.data.vertices]
        objects[o.name] = {
            "vertices": len(o.data.vertices), "polygons": len(o.data.polygons),
            "min": [min(p[i] for p in world) for i in range(3)] if world else [0, 0, 0],
            "max": [max(p[i] for p in world) for i in range(3)] if world else [0, 0, 0],
            "materials": [m.name for m in o.data.materials if m],
            "proj": str(o.get("relief:proj", "")),
        }
    carriers = sorted(o.name for o in bpy.context.scene.objects if "relief:proj" in o)
    proj = [str(o["relief:proj"]) for o in bpy.context.scene.objects if "relief:proj" in o]
    print("RELIEF_JSON " + json.dumps({"file": path, "objects": objects, "proj_carriers": carriers,
                                       "proj": proj[0] if proj else ""}))
)PY";

constexpr std::string_view kPrefix = "RELIEF_JSON ";

std::string run_and_capture(const std::string& command) {
  std::string out;
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return out;
  char buffer[4096];
  while (std::fgets(buffer, sizeof buffer, pipe) != nullptr) out += buffer;
  pclose(pipe);
  return out;
}

}  // namespace

bool have_blender() {
  return std::system("command -v blender > /dev/null 2>&1") == 0;
}

BlenderImports import_in_blender(const std::vector<std::filesystem::path>& files,
                                 const std::filesystem::path& work_dir) {
  const auto script = work_dir / "relief_blender_import.py";
  std::ofstream(script) << kScript;
  std::string command = "blender -b --factory-startup --python '" + script.string() + "' --";
  for (const auto& p : files) command += " '" + p.string() + "'";
  BlenderImports result;
  result.output = run_and_capture(command + " 2>&1");
  std::istringstream lines(result.output);
  for (std::string line; std::getline(lines, line);) {
    if (!line.starts_with(kPrefix)) continue;
    nlohmann::json j = nlohmann::json::parse(line.substr(kPrefix.size()));
    const std::string file = j["file"].get<std::string>();
    result.by_file[file] = std::move(j);
  }
  return result;
}

}  // namespace relief::test
