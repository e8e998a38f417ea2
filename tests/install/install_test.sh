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
# The Python module, where it was built: installed where Debian's python3 finds it under the
# prefix, and it imports from there.
if compgen -G "$RELIEF_BUILD_DIR/python/relief*.so" >/dev/null; then
  site="$RELIEF_TMP/prefix/lib/python$(/usr/bin/python3 -c 'import sys; print("%d.%d" % sys.version_info[:2])')/dist-packages"
  PYTHONPATH="$site" /usr/bin/python3 -c "import relief; assert relief.wheel_base(5.0, 1.8) == (3.0, 1.4); print('python module imports from', relief.__file__)"
fi
