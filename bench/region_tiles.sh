#!/usr/bin/env bash
# Benchmark (not a test), issue 17: a generated region of about 2000 km (relief_write_corpus
# mountain-range: 87 copies of the corpus mountain side by side, 30 m Int16 DEM with voids) planned
# in 2 km tiles, built with --jobs 1 and --jobs 2, merged, and a whole build of the same region in
# the plan's frame beside it. /usr/bin/time's wall time and peak RSS; each tile's own peak RSS
# from its tile.json. Prints road-km per core-second, the --jobs 2 speed-up, the largest tile's
# memory against the whole build's, and the merge against the whole build.
# Usage: bench/region_tiles.sh [COPIES] [TILE_M]  (after tools/test.sh; default 87, 2000)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
copies=${1:-87}
tile=${2:-2000}
relief="${RELIEF:-$root/build/tools/relief}"  # a copy, to keep rebuilding beside the run
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
export SUMO_HOME=${SUMO_HOME:-/usr/share/sumo}

"$root/build/tests/relief_write_corpus" mountain-range "$copies" 30 "$tmp" >"$tmp/case.json"
osm="$tmp/mountain_range.osm"
dem="$tmp/mountain_range_30m.tif"
t="$tmp/tiles"
"$relief" tiles plan --osm "$osm" --dem "$dem" --tile-size "$tile" --out "$t" --no-compare >/dev/null
for jobs in 1 2; do
  /usr/bin/time -f "build$jobs %e %M" -a -o "$tmp/times" "$relief" tiles build "$t" --all --force --jobs "$jobs" \
    >/dev/null 2>&1 || echo "tiles build --jobs $jobs exited $?"
done
origin=$(python3 -c "import json,sys; print('%.12f,%.12f' % tuple(json.load(open(sys.argv[1]))['frame']['centre_lon_lat']))" "$t/manifest.json")
/usr/bin/time -f "whole %e %M" -a -o "$tmp/times" "$relief" build --quiet --osm "$osm" --dem "$dem" --origin "$origin" \
  --outputs xodr,mesh,report --mesh-formats glb,fbx --no-compare --out "$tmp/whole" >/dev/null 2>&1 ||
  echo "whole build exited $?"
/usr/bin/time -f "merge %e %M" -a -o "$tmp/times" "$relief" tiles merge "$t" --compare "$tmp/whole/mountain_range.xodr" \
  >"$tmp/merge.log" 2>&1 || echo "tiles merge exited $? ($(grep -A2 FAILED "$tmp/merge.log" | tail -2 | tr '\n' ' '))"

python3 - "$tmp" <<'PY'
import glob, json, re, sys
tmp = sys.argv[1]
rows = {}
for line in open(tmp + "/times"):
    m = re.match(r"(\w+) ([\d.]+) (\d+)$", line.strip())
    if m:
        rows[m[1]] = (float(m[2]), int(m[3]) / 1024)
km = json.load(open(tmp + "/case.json"))["road_km"]
records = [json.load(open(p)) for p in glob.glob(tmp + "/tiles/tiles/*/tile.json")]
largest = max(records, key=lambda r: r["peak_rss_mb"])
r = json.load(open(tmp + "/tiles/merged/report.json"))
w = r.get("whole_build", {})
b1, b2 = rows["build1"], rows["build2"]
print(f"region {km:.0f} km, {len(records)} tiles of the plan; tiles --jobs 1 {b1[0]:.0f} s "
      f"({km / b1[0]:.1f} road-km per core-second), --jobs 2 {b2[0]:.0f} s ({km / b2[0] / 2:.1f} per core-second, "
      f"speed-up {b1[0] / b2[0]:.2f}x); largest tile {largest['peak_rss_mb']:.0f} MB (tile {largest['x']},{largest['y']}); "
      f"merge {rows['merge'][0]:.0f} s {rows['merge'][1]:.0f} MB; whole build {rows['whole'][0]:.0f} s {rows['whole'][1]:.0f} MB")
print(f"merged: {r['opendrive']['roads']} roads, {r['opendrive']['junctions']} junctions, links over 1 cm "
      f"{r['opendrive']['links_over_1cm']}, failed gates {len(r['failed_gates'])}; against the whole build: "
      f"{w.get('roads', 0) - w.get('unmatched', 0)} of {w.get('roads')} roads, plan {w.get('max_xy_m')} m, "
      f"height {w.get('max_z_m')} m; SUMO {r.get('sumo', {}).get('lanes')} lanes, z max {r.get('sumo', {}).get('z_max_m')} m")
PY
