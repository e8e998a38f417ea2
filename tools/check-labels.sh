#!/usr/bin/env bash
# Proves the ctest labels of a built tree (default build/): the `unit` tests pass with neither
# ../shared/data nor any external program (an empty PATH, no SUMO_HOME), the `realdata` tests
# pass with the data but no program, and none of them is skipped (a skip would mean a test
# needs what its label says it does not; disabled tests are left out). The `tools` tests are the
# rest of the suite. Programs a test calls by absolute path (/usr/bin/python3) escape the check.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-$root/build}"
ctest="$(command -v ctest)"
empty="$(mktemp -d)"
trap 'rm -rf "$empty"' EXIT
status=0
check() {  # check LABEL ENV...: runs ctest -L LABEL under the environment given
  local label=$1; shift
  local log="$empty/$label.log"
  if ! env "$@" SUMO_HOME="$empty/no-sumo" PATH="$empty" "$ctest" --test-dir "$build" -L "^$label\$" \
      -j "$(nproc)" >"$log" 2>&1; then
    echo "check-labels: $label tests fail without what their label leaves out:"
    grep -E 'Failed|Not Run|Exception' "$log" || tail -20 "$log"
    status=1
  elif sed -n '/did not run/,$p' "$log" | grep -E '^\s+[0-9]+ - ' | grep -v '(Disabled)$'; then
    echo "check-labels: these $label tests skipped without what their label leaves out"
    status=1
  fi
  echo "$label: $(grep -E 'tests passed' "$log")"
}
check unit RELIEF_SHARED_DATA="$empty/no-data"
data="${RELIEF_SHARED_DATA:-$root/../shared/data}"
if [[ -d "$data" ]]; then
  check realdata
else
  echo "realdata: not checked (no $data)"
fi
exit $status
