#!/usr/bin/env bash
# Installs relief's build and test dependencies from Debian 12 packages.
# Idempotent: packages already present are skipped; waits for the apt/dpkg lock.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config ccache
  libcgal-dev libeigen3-dev libgmp-dev libmpfr-dev libboost-dev
  libproj-dev proj-data proj-bin
  libosmium2-dev libprotozero-dev libexpat1-dev libbz2-dev zlib1g-dev libdeflate-dev libssl-dev
  libgdal-dev gdal-bin
  libassimp-dev assimp-utils
  libgtest-dev libgmock-dev libbenchmark-dev
  nlohmann-json3-dev libcli11-dev libpugixml-dev
  libxml2-utils sumo sumo-tools python3-xmlschema python3-jsonschema zip blender
  pybind11-dev python3-dev python3-pytest
  libbullet-dev python3-numpy libembree-dev python3-open3d
  nodejs chromium python3-distributed
  osmium-tool
)
# npm: Debian's own package when Node.js is Debian's (a Node.js with its own npm has it already).
command -v npm >/dev/null || packages+=(npm)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  sudo=""
  [ "$(id -u)" -ne 0 ] && sudo="sudo"
  apt_opts=(-o DPkg::Lock::Timeout=600 -y -q)
  export DEBIAN_FRONTEND=noninteractive
  echo "install-deps: installing ${missing[*]}" >&2
  $sudo apt-get "${apt_opts[@]}" update >/dev/null
  $sudo apt-get "${apt_opts[@]}" install --no-install-recommends "${missing[@]}" >/dev/null
fi

# The viewer's npm packages (three.js, esbuild; puppeteer-core for its browser test), exactly as
# package-lock.json pins them, from the npm registry; again only when the lock file changed.
web="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)/src/viewer/web"
if [ ! -f "$web/node_modules/.package-lock.json" ] || [ "$web/package-lock.json" -nt "$web/node_modules/.package-lock.json" ]; then
  echo "install-deps: npm ci in src/viewer/web" >&2
  npm ci --prefix "$web" --no-audit --no-fund --loglevel=error >/dev/null
fi

# The validators the tests run on glTF and 3D Tiles output (npm gltf-validator and
# 3d-tiles-validator, pinned in their scripts), into the user's cache, not the repository. Where
# the registry lacks one (a mirror without 3d-tiles-validator), its checks say SKIP and
# tools/tileset_check.py (the 3D Tiles schema, no network) still runs.
bash "$(dirname "${BASH_SOURCE[0]}")/gltf-validate.sh" --install || true
bash "$(dirname "${BASH_SOURCE[0]}")/3d-tiles-validate.sh" --install || true
