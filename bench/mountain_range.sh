#!/usr/bin/env bash
# Benchmark (not a test), issue 14 item 8: a generated mountain network of about 410 km
# (relief_write_corpus mountain-range: 18 copies of the corpus mountain side by side, 30 m Int16
# DEM with voids), relief's whole build beside SUMO's netconvert (net + OpenDRIVE from the same
# OSM and the DEM warped to EPSG:4326), interleaved round by round, /usr/bin/time's wall time and
# peak RSS. Prints the medians, the per-round ratios' medians and the memory per km of road.
# Usage: bench/mountain_range.sh [ROUNDS] [COPIES]  (after tools/test.sh; default 3 rounds, 18)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
rounds=${1:-3}
copies=${2:-18}
relief="$root/build/tools/relief"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
export SUMO_HOME=${SUMO_HOME:-/usr/share/sumo}

"$root/build/tests/relief_write_corpus" mountain-range "$copies" 30 "$tmp" >"$tmp/case.json"
osm="$tmp/mountain_range.osm"
dem="$tmp/mountain_range_30m.tif"
gdalwarp -q -t_srs EPSG:4326 -r bilinear "$dem" "$tmp/wgs84.tif"

for r in $(seq "$rounds"); do
  /usr/bin/time -f "$r whole %e %M" -a -o "$tmp/times" "$relief" build --quiet --osm "$osm" --dem "$dem" \
    --out "$tmp/out" >/dev/null 2>&1 || echo "relief exited $? (round $r)"
  /usr/bin/time -f "$r netconvert %e %M" -a -o "$tmp/times" netconvert --osm-files "$osm" \
    --heightmap.geotiff "$tmp/wgs84.tif" -o "$tmp/nc.net.xml" --opendrive-output "$tmp/nc.xodr" \
    --no-warnings >/dev/null 2>&1
  /usr/bin/time -f "$r xodr %e %M" -a -o "$tmp/times" "$relief" build --quiet --outputs xodr --no-compare \
    --osm "$osm" --dem "$dem" --out "$tmp/outx" >/dev/null 2>&1 || true
done

python3 - "$tmp" <<'PY'
import json, re, statistics as st, sys
tmp = sys.argv[1]
rows = {}
for line in open(tmp + "/times"):
    m = re.match(r"(\d+) (\w+) ([\d.]+) (\d+)$", line.strip())
    if m:
        rows.setdefault(m[2], {})[int(m[1])] = (float(m[3]), int(m[4]) / 1024)
w, n, x = rows["whole"], rows["netconvert"], rows["xodr"]
med = lambda d, i: st.median(v[i] for v in d.values())
ratio = lambda a, i: st.median(a[r][i] / n[r][i] for r in a)
report = json.load(open(f"{tmp}/out/report.json"))
km = report["network"]["length_km"]
failed = [k for k, g in report["gates"].items() if not g["passed"]]
print(f"mountain range ({km:.1f} km, gates failed: {failed or 'none'}): whole {med(w, 0):.2f} s {med(w, 1):.0f} MB, "
      f"OpenDRIVE alone {med(x, 0):.2f} s {med(x, 1):.0f} MB, netconvert {med(n, 0):.2f} s {med(n, 1):.0f} MB; "
      f"whole/netconvert {ratio(w, 0):.1f}x {ratio(w, 1):.1f}x, OpenDRIVE alone/netconvert {ratio(x, 0):.2f}x "
      f"{ratio(x, 1):.1f}x; MB per km whole {med(w, 1) / km:.2f}, OpenDRIVE alone {med(x, 1) / km:.2f}")
print("stages of the last whole build (s):", {k: round(v, 2) for k, v in report["timings_s"].items() if v >= 0.2})
PY
