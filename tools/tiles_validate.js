// Validates 3D Tiles tilesets with CesiumGS's 3D Tiles validator (npm 3d-tiles-validator), their
// glb contents through the Khronos glTF validator it carries: prints one JSON line per tileset
// (errors, warnings, the first messages) and exits 1 when any has an error or a warning (the
// validator only warns of a child's geometricError above its parent's, which breaks refinement).
// Run through tools/3d-tiles-validate.sh, which installs the validator.
const {Validators} = require(process.env.RELIEF_3D_TILES_VALIDATOR || '3d-tiles-validator');

async function main() {
  let failed = false;
  for (const path of process.argv.slice(2)) {
    const result = (await Validators.validateTilesetFile(path)).toJson();
    const issues = result.issues || [];
    console.log(JSON.stringify({
      file: path,
      errors: result.numErrors,
      warnings: result.numWarnings,
      infos: result.numInfos,
      messages: issues.filter((i) => i.severity !== 'INFO').slice(0, 10).map((i) => `${i.type} ${i.path}: ${i.message}`),
    }));
    failed = failed || result.numErrors > 0 || result.numWarnings > 0;
  }
  process.exit(failed ? 1 : 0);
}
main().catch((error) => {
  console.error(error);
  process.exit(2);
});
