// Validates glTF files with the Khronos glTF validator (npm gltf-validator): prints one JSON
// line per file (errors, warnings, the first messages) and exits 1 when any file has an error.
// Run through tools/gltf-validate.sh, which installs the validator.
const fs = require('fs');
const validator = require('gltf-validator');

async function main() {
  let failed = false;
  for (const path of process.argv.slice(2)) {
    const report = await validator.validateBytes(new Uint8Array(fs.readFileSync(path)), {maxIssues: 100});
    const issues = report.issues;
    console.log(JSON.stringify({
      file: path,
      errors: issues.numErrors,
      warnings: issues.numWarnings,
      animations: report.info ? report.info.animationCount : 0,
      messages: issues.messages.filter((m) => m.severity <= 1).slice(0, 10).map((m) => `${m.code} ${m.pointer}: ${m.message}`),
    }));
    failed = failed || issues.numErrors > 0;
  }
  process.exit(failed ? 1 : 0);
}
main().catch((error) => {
  console.error(error);
  process.exit(2);
});
