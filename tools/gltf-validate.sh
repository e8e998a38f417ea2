#!/usr/bin/env bash
# tools/gltf-validate.sh FILE.glb...: the Khronos glTF validator (npm gltf-validator, pinned) on
# each file; exit 0 when none has an error, 1 when one has, 77 when node/npm or the npm registry
# is not available (the validator is installed once into a cache directory, not the repository).
# --install: only install it (tools/install-deps.sh).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
version=2.0.0-dev.3.10
cache="${RELIEF_NPM_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/relief-npm}"
command -v node >/dev/null && command -v npm >/dev/null || { echo "gltf-validate: node/npm not installed" >&2; exit 77; }
if [ ! -f "$cache/node_modules/gltf-validator/package.json" ] ||
   ! grep -q "\"version\": \"$version\"" "$cache/node_modules/gltf-validator/package.json"; then
  mkdir -p "$cache"
  (cd "$cache" && timeout 300 npm install --silent --no-audit --no-fund "gltf-validator@$version" >/dev/null 2>&1) ||
    { echo "gltf-validate: cannot install gltf-validator@$version from the npm registry" >&2; exit 77; }
fi
[ "${1:-}" = "--install" ] && exit 0
NODE_PATH="$cache/node_modules" node "$here/gltf_validate.js" "$@"
