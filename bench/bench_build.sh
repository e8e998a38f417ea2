#!/usr/bin/env bash
# Benchmark (not a test): times `relief build` on the NE San Francisco set and prints the
# median wall time of each stage over N runs (default 5), beside SUMO's netconvert reading the
# same OSM and DEM when it is installed. Usage: bench/bench_build.sh [N]  (after tools/build.sh)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
runs=${1:-5}
data="$root/../shared/data/sf-ne"
relief="$root/build/tools/relief"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

for i in $(seq "$runs"); do
  /usr/bin/time -f "%e %M" -o "$tmp/time.$i" "$relief" build --quiet \
    --osm "$data/sf_ne_drive_2017.osm.gz" --dem "$data/sf_ne_usgs24k_30m_nad27utm10_m.tif" \
    --out "$tmp/out" >/dev/null
  cp "$tmp/out/report.json" "$tmp/report.$i.json"
done
python3 - "$tmp" "$runs" <<'PY'
import json, statistics, sys
tmp, runs = sys.argv[1], int(sys.argv[2])
reports = [json.load(open(f"{tmp}/report.{i}.json")) for i in range(1, runs + 1)]
wall = [float(open(f"{tmp}/time.{i}").read().split()[0]) for i in range(1, runs + 1)]
rss = [int(open(f"{tmp}/time.{i}").read().split()[1]) for i in range(1, runs + 1)]
n = reports[0]["network"]
print(f"relief build, NE set: {n['roads']} roads, {n['intersections']} intersections, "
      f"{n['length_km']:.1f} km, {reports[0]['elevation']['samples']} samples; median of {runs} runs")
for stage in reports[0]["timings_s"]:
    print(f"  {stage:22s} {statistics.median(r['timings_s'][stage] for r in reports):8.3f} s")
print(f"  {'process wall time':22s} {statistics.median(wall):8.3f} s, peak RSS {max(rss) / 1024:.0f} MiB")
PY

if command -v netconvert >/dev/null; then
  export SUMO_HOME=${SUMO_HOME:-/usr/share/sumo}
  # netconvert wants the DEM in WGS84.
  gdalwarp -q -t_srs EPSG:4326 -r bilinear "$data/sf_ne_usgs24k_30m_nad27utm10_m.tif" "$tmp/dem_wgs84.tif"
  best=""
  for i in $(seq "$runs"); do
    /usr/bin/time -f "%e" -o "$tmp/nc.$i" netconvert --osm-files "$data/sf_ne_drive_2017.osm.gz" \
      --heightmap.geotiff "$tmp/dem_wgs84.tif" -o "$tmp/ne.net.xml" --no-warnings >/dev/null 2>&1 || true
  done
  python3 - "$tmp" "$runs" <<'PY'
import statistics, sys
tmp, runs = sys.argv[1], int(sys.argv[2])
t = [float(open(f"{tmp}/nc.{i}").read().split()[0]) for i in range(1, runs + 1)]
print(f"  netconvert (same OSM + DEM, writes .net.xml): median {statistics.median(t):.3f} s")
PY
fi
