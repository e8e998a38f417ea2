#!/usr/bin/env bash
# Benchmark (not a test): times `relief build` on the NE San Francisco set and prints the
# median wall time of each stage over N runs (default 5), and relief's OpenDRIVE alone
# (--outputs xodr --no-compare) beside SUMO's netconvert building its .net.xml and .xodr from
# the same OSM and DEM (warped to WGS84 for it), the three interleaved round by round.
# Usage: bench/bench_build.sh [N]  (after tools/build.sh)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
runs=${1:-5}
data="$root/../shared/data/sf-ne"
relief="$root/build/tools/relief"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

has_netconvert=0
if command -v netconvert >/dev/null; then
  has_netconvert=1
  export SUMO_HOME=${SUMO_HOME:-/usr/share/sumo}
  # netconvert wants the DEM in WGS84.
  gdalwarp -q -t_srs EPSG:4326 -r bilinear "$data/sf_ne_usgs24k_30m_nad27utm10_m.tif" "$tmp/dem_wgs84.tif"
fi

# Interleaved rounds (relief build, relief --outputs xodr, netconvert): a noisy machine slows
# all three of a round alike, and the ratios are taken per round.
for i in $(seq "$runs"); do
  /usr/bin/time -f "%e %M" -o "$tmp/time.$i" "$relief" build --quiet \
    --osm "$data/sf_ne_drive_2017.osm.gz" --dem "$data/sf_ne_usgs24k_30m_nad27utm10_m.tif" \
    --out "$tmp/out" >/dev/null
  cp "$tmp/out/report.json" "$tmp/report.$i.json"
  /usr/bin/time -f "%e" -o "$tmp/xodr.$i" "$relief" build --quiet --outputs xodr --no-compare \
    --osm "$data/sf_ne_drive_2017.osm.gz" --dem "$data/sf_ne_usgs24k_30m_nad27utm10_m.tif" \
    --out "$tmp/out-xodr" >/dev/null
  if [ "$has_netconvert" = 1 ]; then
    /usr/bin/time -f "%e" -o "$tmp/nc.$i" netconvert --osm-files "$data/sf_ne_drive_2017.osm.gz" \
      --heightmap.geotiff "$tmp/dem_wgs84.tif" -o "$tmp/ne.net.xml" --opendrive-output "$tmp/ne.xodr" \
      --no-warnings >/dev/null 2>&1 || true
  fi
done

python3 - "$tmp" "$runs" <<'PY'
import json, os, statistics, sys
tmp, runs = sys.argv[1], int(sys.argv[2])
rounds = range(1, runs + 1)
def times(prefix):
    return [float(open(f"{tmp}/{prefix}.{i}").read().split()[0]) for i in rounds]
reports = [json.load(open(f"{tmp}/report.{i}.json")) for i in rounds]
wall, xodr = times("time"), times("xodr")
rss = [int(open(f"{tmp}/time.{i}").read().split()[1]) for i in rounds]
n = reports[0]["network"]
print(f"relief build, NE set: {n['roads']} roads, {n['intersections']} intersections, "
      f"{n['length_km']:.1f} km, {reports[0]['elevation']['samples']} samples; median of {runs} runs")
for stage in reports[0]["timings_s"]:
    print(f"  {stage:22s} {statistics.median(r['timings_s'][stage] for r in reports):8.3f} s")
print(f"  {'process wall time':22s} {statistics.median(wall):8.3f} s (min {min(wall):.3f}), peak RSS {max(rss) / 1024:.0f} MiB")
print(f"  relief, OpenDRIVE only (--outputs xodr --no-compare): median {statistics.median(xodr):.3f} s (min {min(xodr):.3f})")
if os.path.exists(f"{tmp}/nc.1"):
    nc = times("nc")
    whole = [w / c for w, c in zip(wall, nc)]
    alone = [x / c for x, c in zip(xodr, nc)]
    print(f"  netconvert, .net.xml + .xodr from the same OSM + DEM: median {statistics.median(nc):.3f} s (min {min(nc):.3f})")
    print(f"  whole relief build / netconvert, per round: median {statistics.median(whole):.2f}x "
          f"(range {min(whole):.2f}-{max(whole):.2f}x)")
    print(f"  relief OpenDRIVE only / netconvert, per round: median {statistics.median(alone):.2f}x "
          f"(range {min(alone):.2f}-{max(alone):.2f}x)")
PY
