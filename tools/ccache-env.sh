# Sourced by tools/build.sh and .ci/run: compile through ccache when it is installed.
# CCACHE_BASEDIR makes the sources' absolute paths relative, so that clones at other paths (CI's
# clean clone) share one cache; the cache lives in ccache's own directory, outside the checkout.
# Sets ccache_launcher to the CMake options that use it (empty without ccache).
ccache_launcher=()
if command -v ccache >/dev/null 2>&1; then
  export CCACHE_BASEDIR="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
  export CCACHE_NOHASHDIR=true
  export CCACHE_MAXSIZE="${CCACHE_MAXSIZE:-12G}"
  ccache_launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
fi
