#!/usr/bin/env bash
# Benchmark (not a test): relief's whole build and its OpenDRIVE alone beside SUMO's netconvert
# (net + OpenDRIVE from the same OSM and DEM) on the NE quadrant, Liechtenstein and central
# Portland, interleaved round by round, with /usr/bin/time's wall time and peak RSS. Prints the
# medians, the per-round ratios' medians and the memory per km of road (the README's "Beside
# netconvert" table). netconvert gets the PBFs as XML (osmium cat) and the DEMs warped to
# EPSG:4326 for --heightmap.geotiff; the conversions are not timed.
# Usage: bench/bench_regions.sh [ROUNDS]  (after tools/build.sh; default 3 rounds, about 5 min each)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
rounds=${1:-3}
data="$root/../shared/data"
relief="$root/build/tools/relief"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
export SUMO_HOME=${SUMO_HOME:-/usr/share/sumo}

ne_dem="$data/sf-ne/sf_ne_usgs24k_30m_nad27utm10_m.tif"
li_dem="/vsizip/$data/liechtenstein/N47E009.hgt.zip/N47E009.hgt"
pdx_dem="$data/portland/portland-ned.tif"
osmium cat "$data/liechtenstein/liechtenstein-latest.osm.pbf" -o "$tmp/li.osm" -f osm
osmium cat "$data/portland/portland-central-filtered.osm.pbf" -o "$tmp/pdx.osm" -f osm
for set in ne li pdx; do
  dem_var="${set}_dem"
  gdalwarp -q -t_srs EPSG:4326 -r bilinear "${!dem_var}" "$tmp/${set}_wgs84.tif"
done

args() {  # relief's inputs of a set
  case $1 in
    ne) echo "--osm $data/sf-ne/sf_ne_drive_2017.osm.gz --dem $ne_dem" ;;
    li) echo "--osm $data/liechtenstein/liechtenstein-latest.osm.pbf --dem $li_dem" ;;
    pdx) echo "--osm $data/portland/portland-central-filtered.osm.pbf --dem $pdx_dem --allow-partial" ;;
  esac
}
osm_of() { [ "$1" = ne ] && echo "$data/sf-ne/sf_ne_drive_2017.osm.gz" || echo "$tmp/$1.osm"; }

for r in $(seq "$rounds"); do
  for set in ne li pdx; do
    # shellcheck disable=SC2046  # the inputs are words
    /usr/bin/time -f "$set $r whole %e %M" -a -o "$tmp/times" "$relief" build --quiet $(args $set) \
      --out "$tmp/out-$set" >/dev/null 2>&1 || true  # Portland exits 4 (its known failing gate)
    /usr/bin/time -f "$set $r netconvert %e %M" -a -o "$tmp/times" netconvert --osm-files "$(osm_of $set)" \
      --heightmap.geotiff "$tmp/${set}_wgs84.tif" -o "$tmp/$set.net.xml" --opendrive-output "$tmp/$set.xodr" \
      --no-warnings >/dev/null 2>&1 || true
    # shellcheck disable=SC2046
    /usr/bin/time -f "$set $r xodr %e %M" -a -o "$tmp/times" "$relief" build --quiet --outputs xodr --no-compare \
      $(args $set) --out "$tmp/outx-$set" >/dev/null 2>&1 || true
  done
done

python3 - "$tmp" <<'PY'
import json, re, statistics as st, sys
tmp = sys.argv[1]
rows = {}
for line in open(tmp + "/times"):
    m = re.match(r"(\w+) (\d+) (\w+) ([\d.]+) (\d+)$", line.strip())
    if m:
        rows.setdefault((m[1], m[3]), {})[int(m[2])] = (float(m[4]), int(m[5]) / 1024)
for s, name in (("ne", "NE"), ("li", "Liechtenstein"), ("pdx", "Portland")):
    w, n, x = rows[(s, "whole")], rows[(s, "netconvert")], rows[(s, "xodr")]
    med = lambda d, i: st.median(v[i] for v in d.values())
    ratio = lambda a, i: st.median(a[r][i] / n[r][i] for r in a)
    km = json.load(open(f"{tmp}/out-{s}/report.json"))["network"]["length_km"]
    print(f"{name} ({km:.1f} km): whole {med(w, 0):.2f} s {med(w, 1):.0f} MB, OpenDRIVE alone {med(x, 0):.2f} s "
          f"{med(x, 1):.0f} MB, netconvert {med(n, 0):.2f} s {med(n, 1):.0f} MB; whole/netconvert "
          f"{ratio(w, 0):.1f}x {ratio(w, 1):.1f}x, OpenDRIVE alone/netconvert {ratio(x, 0):.2f}x {ratio(x, 1):.1f}x; "
          f"MB per km whole {med(w, 1) / km:.2f}, OpenDRIVE alone {med(x, 1) / km:.2f}")
PY
