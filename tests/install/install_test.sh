#!/usr/bin/env bash
# Installs relief into a scratch prefix and builds a program outside the project against it
# with find_package(relief): the exported targets and reliefConfig.cmake work for users.
set -euo pipefail
: "${RELIEF_BUILD_DIR:?}" "${RELIEF_SOURCE_DIR:?}" "${RELIEF_TMP:?}"
rm -rf "$RELIEF_TMP" && mkdir -p "$RELIEF_TMP"
cmake --install "$RELIEF_BUILD_DIR" --prefix "$RELIEF_TMP/prefix" >/dev/null
cmake -S "$RELIEF_SOURCE_DIR/tests/install/consumer" -B "$RELIEF_TMP/consumer" -G Ninja \
  -DCMAKE_PREFIX_PATH="$RELIEF_TMP/prefix" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$RELIEF_TMP/consumer" >/dev/null
"$RELIEF_TMP/consumer/consumer"
"$RELIEF_TMP/prefix/bin/relief" --version
