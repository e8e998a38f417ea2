#!/usr/bin/env bash
# relief tiles on a real Dask cluster on localhost (issue 17, item 5): a dask-scheduler and two
# dask-worker processes started here build the NE San Francisco tiles (500 m) through
# tools/relief-tiles-dask; one worker is killed (SIGKILL, its whole process group: a lost
# machine) while it builds a tile, and the job must still complete: every tile built, the
# killed worker's tile run again on the other worker. The tiles must equal a local
# `relief tiles build --all --jobs 2` of a second plan (each tile's .xodr identical but for the
# header's date), and both merges must give the same road and junction counts.
#
#   bash tests/tiles/dask_test.sh path/to/relief
#
# Exit 77 (skipped) without ../shared/data ($RELIEF_SHARED_DATA) or Debian's python3-distributed
# (/usr/bin/dask-*). Temporary files under $RELIEF_TMP (else $TMPDIR, /tmp), removed at the end.
set -euo pipefail

RELIEF=$(realpath "${1:?usage: dask_test.sh path/to/relief}")
HERE=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
DRIVER="$HERE/../../tools/relief-tiles-dask"
PY=/usr/bin/python3
SHARED=${RELIEF_SHARED_DATA:-$(cd "$HERE/../../.." && pwd)/shared/data}
DATA=$SHARED/sf-ne
OSM=$DATA/sf_ne_drive_2017.osm.gz
DEM=$DATA/sf_ne_usgs24k_30m_nad27utm10_m.tif

if [[ ! -d $SHARED ]]; then
  echo "SKIP: $SHARED is missing (the NE San Francisco inputs; or set RELIEF_SHARED_DATA)"; exit 77
fi
for f in "$OSM" "$DEM"; do
  [[ -f $f ]] || { echo "SKIP: $f is missing"; exit 77; }
done
for p in /usr/bin/dask-scheduler /usr/bin/dask-worker; do
  [[ -x $p ]] || { echo "SKIP: $p is missing (Debian python3-distributed)"; exit 77; }
done
"$PY" -c 'import distributed' 2>/dev/null || { echo "SKIP: $PY cannot import distributed"; exit 77; }

mkdir -p "${RELIEF_TMP:-${TMPDIR:-/tmp}}"
TMP=$(mktemp -d "${RELIEF_TMP:-${TMPDIR:-/tmp}}/relief-dask-test.XXXXXX")
PGIDS=()      # process groups started here (scheduler, workers): each its own session (setsid)
DRIVER_PID=""
cleanup() {
  local rc=$?
  [[ -n $DRIVER_PID ]] && kill "$DRIVER_PID" 2>/dev/null || true
  for g in "${PGIDS[@]}"; do kill -TERM -- "-$g" 2>/dev/null || true; done
  sleep 0.5
  for g in "${PGIDS[@]}"; do kill -KILL -- "-$g" 2>/dev/null || true; done
  wait 2>/dev/null || true
  if [[ $rc -ne 0 && $rc -ne 77 ]]; then
    for log in "$TMP"/*.log "$TMP"/driver.err; do
      [[ -f $log ]] && { echo "--- $log (last 30 lines)"; tail -n 30 "$log"; }
    done
  fi
  rm -rf "$TMP"
  exit "$rc"
}
trap cleanup EXIT
trap 'exit 143' TERM INT  # (a ctest timeout) through cleanup too
fail() { echo "FAIL: $*" >&2; exit 1; }

started=$(date +%s)
DIR1=$TMP/dask DIR2=$TMP/local
for d in "$DIR1" "$DIR2"; do
  "$RELIEF" tiles plan --osm "$OSM" --dem "$DEM" --tile-size 500 --out "$d" --no-compare >/dev/null
done
NTILES=$("$PY" -c 'import json,sys; print(len(json.load(open(sys.argv[1]))["tiles"]))' "$DIR1/manifest.json")
[[ $NTILES -gt 10 ]] || fail "the plan has only $NTILES tiles"

# A real scheduler on a free port, and two single-threaded worker processes (no nanny restarts
# a worker whose whole group is killed: it is gone, like a lost machine).
PORT=$("$PY" -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
SCHED=tcp://127.0.0.1:$PORT
# (--no-dashboard still serves /health and /metrics on 0.0.0.0:8787: bind it to a free local port)
setsid /usr/bin/dask-scheduler --host 127.0.0.1 --port "$PORT" --no-dashboard --dashboard-address 127.0.0.1:0 \
  >"$TMP/scheduler.log" 2>&1 &
PGIDS+=($!)
for w in wA wB; do
  setsid /usr/bin/dask-worker "$SCHED" --name "$w" --nthreads 1 --nworkers 1 --no-dashboard \
    --local-directory "$TMP/$w" >"$TMP/$w.log" 2>&1 &
  PGIDS+=($!)
  eval "PG_$w=$!"
done
"$PY" -c 'import sys
from distributed import Client
with Client(sys.argv[1], timeout="60s") as c:
    c.wait_for_workers(2, timeout=60)' "$SCHED" || fail "the scheduler did not see two workers"

# The driver, in the background; kill worker wA once a quarter of the tiles are done and it is
# building one (later rather than sooner: the survivor builds the rest alone).
t0=$(date +%s)
"$PY" "$DRIVER" "$DIR1" --scheduler "$SCHED" --relief "$RELIEF" --retries 1 --timeout 120 --merge \
  >"$TMP/driver.out" 2>"$TMP/driver.err" &
DRIVER_PID=$!
KILLED_TILE="" KILLED_PID="" KILLED_AT=0
building() {  # "PID X,Y" of a `relief tiles build` whose parent is in process group $1, if any
  # (the driver starts each build in a session of its own, tied to its worker by PR_SET_PDEATHSIG)
  ps -e -o pid=,ppid=,pgid=,args= | awk -v g="$1" '
    { pgid[$1] = $3 }
    / tiles build / { for (i = 4; i < NF; ++i) if ($i == "--tile") build[$1] = $2 " " $(i + 1) }
    END { for (p in build) { split(build[p], a, " "); if (pgid[a[1]] == g) { print p, a[2]; exit } } }'
}
while kill -0 "$DRIVER_PID" 2>/dev/null; do
  done_now=$( (find "$DIR1/tiles" -name tile.json 2>/dev/null || true) | wc -l)
  if [[ $done_now -ge $((NTILES / 4)) ]]; then
    found=$(building "$PG_wA")
    if [[ -n $found ]]; then
      kill -KILL -- "-$PG_wA"
      wait "$PG_wA" 2>/dev/null || true
      read -r KILLED_PID KILLED_TILE <<<"$found"
      KILLED_AT=$done_now
      echo "killed worker wA (process group $PG_wA) while it built tile $KILLED_TILE" \
           "(relief pid $KILLED_PID), $done_now of $NTILES tiles done"
      break
    fi
  fi
  sleep 0.1
done
[[ -n $KILLED_TILE ]] || fail "the driver ended before worker wA could be killed mid-tile"
alive() { local st; st=$(ps -o stat= -p "$1" 2>/dev/null) && [[ $st != Z* ]]; }
for _ in $(seq 50); do alive "$KILLED_PID" || break; sleep 0.1; done
! alive "$KILLED_PID" || fail "the killed worker's build (pid $KILLED_PID) still runs 5 s on (orphan)"
rc=0
wait "$DRIVER_PID" || rc=$?
DRIVER_PID=""
t_dask=$(( $(date +%s) - t0 ))
grep -v "^  wrote " "$TMP/driver.out" || true
[[ $rc -eq 0 || $rc -eq 4 ]] || fail "relief-tiles-dask exited $rc"

# Every tile of the plan finished, once; the killed worker's tile started again on wB.
"$PY" - "$DIR1" <<'EOF' || fail "tiles missing after the Dask run"
import json, os, sys
d = sys.argv[1]
m = json.load(open(os.path.join(d, "manifest.json")))
bad = []
for t in m["tiles"]:
    p = os.path.join(d, "tiles", f"{t['x']}_{t['y']}", "tile.json")
    status = json.load(open(p))["status"] if os.path.exists(p) else "missing"
    if status not in ("built", "gates_failed"):
        bad.append(f"{t['x']},{t['y']}: {status}")
if bad:
    sys.exit("tiles not built: " + "; ".join(bad))
EOF
rerun_line=$(grep -F "tile $KILLED_TILE was started" "$TMP/driver.err" || true)
[[ -n $rerun_line ]] || fail "no record that tile $KILLED_TILE (killed with wA) was run again"
echo "${rerun_line#relief-tiles-dask: }"
read -r -a hops <<<"${rerun_line##*times: }"
[[ ${hops[0]} != "${hops[-1]}" ]] || fail "tile $KILLED_TILE was not run again on another worker: $rerun_line"
[[ -f $DIR1/merged/report.json ]] || fail "relief-tiles-dask --merge wrote no merged/report.json"
RERUNS=$(grep -c ' was started ' "$TMP/driver.err" || true)

# The same plan built here, without Dask.
t1=$(date +%s)
rc_local=0
"$RELIEF" tiles build "$DIR2" --all --jobs 2 >/dev/null 2>"$TMP/local.log" || rc_local=$?
[[ $rc_local -eq 0 || $rc_local -eq 4 ]] || fail "relief tiles build --all exited $rc_local"
t_local=$(( $(date +%s) - t1 ))
rc_merge=0
"$RELIEF" tiles merge "$DIR2" >/dev/null || rc_merge=$?
[[ $rc_merge -eq 0 || $rc_merge -eq 4 ]] || fail "relief tiles merge (local) exited $rc_merge"
[[ $rc -eq $rc_merge ]] || fail "the Dask run exited $rc, the local merge $rc_merge"

NAME=$("$PY" -c 'import json,sys; print(json.load(open(sys.argv[1]))["name"])' "$DIR1/manifest.json")
ndiff=0
for t1dir in "$DIR1"/tiles/*/; do
  t=$(basename "$t1dir")
  a=$t1dir/out/$NAME.xodr b=$DIR2/tiles/$t/out/$NAME.xodr
  [[ -f $a && -f $b ]] || fail "tile $t: $NAME.xodr missing in one of the runs"
  if ! cmp -s <(sed 's/ date="[^"]*"//' "$a") <(sed 's/ date="[^"]*"//' "$b"); then
    echo "tile $t: $NAME.xodr differs between the Dask and the local run" >&2
    ndiff=$((ndiff + 1))
  fi
done
[[ $ndiff -eq 0 ]] || fail "$ndiff tile(s) differ between the Dask and the local run"

COUNTS=$("$PY" - "$DIR1/merged/report.json" "$DIR2/merged/report.json" <<'EOF'
import json, sys
a, b = (json.load(open(p))["opendrive"] for p in sys.argv[1:3])
ka, kb = (a["roads"], a["junctions"]), (b["roads"], b["junctions"])
if ka != kb:
    sys.exit(f"merged roads, junctions: Dask {ka}, local {kb}")
print(f"{ka[0]} roads, {ka[1]} junctions")
EOF
) || fail "the merges differ"

echo "tiles.dask: $NTILES tiles via Dask in ${t_dask} s (worker wA killed at $KILLED_AT/$NTILES done," \
     "its tile $KILLED_TILE rerun; $RERUNS tile(s) started more than once), local --jobs 2 in ${t_local} s;" \
     "xodr identical, merged $COUNTS (exit $rc); total $(( $(date +%s) - started )) s"
