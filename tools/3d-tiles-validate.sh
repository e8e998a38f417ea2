#!/usr/bin/env bash
# tools/3d-tiles-validate.sh TILESET.json...: CesiumGS's 3D Tiles validator (npm
# 3d-tiles-validator, pinned; it runs the Khronos glTF validator on glb contents) on each
# tileset; exit 0 when none has an error or a warning, 1 when one has, 77 when node/npm or the
# validator's package is not available (installed once into a cache directory, not the
# repository). --install: only install it (tools/install-deps.sh).
# RELIEF_3D_TILES_VALIDATOR=DIR: a validator built elsewhere (DIR/build/index.js) instead.
# tools/tileset_check.py is the check that needs no network (schema, boxes, errors).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
version=0.6.0
cache="${RELIEF_NPM_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/relief-npm}"
command -v node >/dev/null && command -v npm >/dev/null || { echo "3d-tiles-validate: node/npm not installed" >&2; exit 77; }
if [ -n "${RELIEF_3D_TILES_VALIDATOR:-}" ]; then
  [ "${1:-}" = "--install" ] && exit 0
  RELIEF_3D_TILES_VALIDATOR="$(cd "$RELIEF_3D_TILES_VALIDATOR" && pwd)/build/index.js" exec node "$here/tiles_validate.js" "$@"
fi
if [ ! -f "$cache/node_modules/3d-tiles-validator/package.json" ] ||
   ! grep -q "\"version\": \"$version\"" "$cache/node_modules/3d-tiles-validator/package.json"; then
  mkdir -p "$cache"
  (cd "$cache" && timeout 300 npm install --silent --no-audit --no-fund "3d-tiles-validator@$version" >/dev/null 2>&1) ||
    { echo "3d-tiles-validate: cannot install 3d-tiles-validator@$version from the npm registry ($(npm config get registry))" >&2; exit 77; }
fi
[ "${1:-}" = "--install" ] && exit 0
NODE_PATH="$cache/node_modules" node "$here/tiles_validate.js" "$@"
