#!/usr/bin/env bash
# Installs the dependencies (Debian 12 packages) and builds relief in Release into build/.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bash "$root/tools/install-deps.sh"
# Compiles through ccache (tools/ccache-env.sh): a rebuild of unchanged sources, in this checkout
# or another clone on the same machine, takes its objects from the cache.
source "$root/tools/ccache-env.sh"
cmake -S "$root" -B "$root/build" -G Ninja -DCMAKE_BUILD_TYPE=Release "${ccache_launcher[@]}" "$@" >/dev/null
cmake --build "$root/build" -j "$(nproc)"
