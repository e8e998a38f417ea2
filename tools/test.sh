#!/usr/bin/env bash
# Installs the dependencies, builds relief with its tests (Release) and runs them with ctest.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bash "$root/tools/build.sh" -DRELIEF_BUILD_TESTS=ON
ctest --test-dir "$root/build" --output-on-failure -j "$(nproc)" "$@"
