#!/usr/bin/env bash
# An attack on real data (not a test): relief build on N random clip boxes of SIZE degrees
# (SIZE x 0.7 SIZE) over one of the shared sets, as a user or a tile cuts a region out of a
# larger extract, and the gates each box fails. Boxes are drawn from a fixed seed, so a run is
# reproducible; boxes with no road inside exit 3 ("no roads inside the clip box").
#   bench/clip_boxes.sh pdx|ne|li N SIZE      (after tools/build.sh; outputs in $TMPDIR)
# Example, the table in the README: bench/clip_boxes.sh pdx 12 0.013
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
data="$root/../shared/data"
set_name=$1 n=$2 size=$3
case $set_name in
  pdx) inputs=(--osm "$data/portland/portland-central-filtered.osm.pbf" --dem "$data/portland/portland-ned.tif" --allow-partial)
       area="-122.74 45.47 -122.62 45.55" ;;
  ne) inputs=(--osm "$data/sf-ne/sf_ne_drive_2017.osm.gz" --dem "$data/sf-ne/sf_ne_usgs24k_30m_nad27utm10_m.tif")
      area="-122.43 37.77 -122.39 37.81" ;;
  li) inputs=(--osm "$data/liechtenstein/liechtenstein-latest.osm.pbf"
              --dem "/vsizip/$data/liechtenstein/N47E009.hgt.zip/N47E009.hgt")
      area="9.48 47.05 9.62 47.25" ;;
  *) echo "usage: $0 pdx|ne|li N SIZE" >&2; exit 2 ;;
esac
tmp=$(mktemp -d)
for i in $(seq 1 "$n"); do
  box=$(python3 -c "
import random
random.seed($i * 7919 + len('$set_name') + int($size * 1e4))
x0, y0, x1, y1 = map(float, '$area'.split())
s = $size
x = random.uniform(x0, x1 - s); y = random.uniform(y0, y1 - s * 0.7)
print(f'{x:.5f},{y:.5f},{x + s:.5f},{y + s * 0.7:.5f}')")
  rc=0
  "$root/build/tools/relief" build "${inputs[@]}" --bbox "$box" --out "$tmp/$i" >"$tmp/$i.log" 2>&1 || rc=$?
  failed=$(python3 -c "
import json, sys
try: r = json.load(open('$tmp/$i/report.json'))
except OSError: sys.exit()
print(round(r['network']['length_km'], 1), 'km', [k for k, v in r['gates'].items() if not v['passed']])")
  echo "$set_name$i bbox $box exit $rc $failed"
done
echo "logs and outputs in $tmp"
