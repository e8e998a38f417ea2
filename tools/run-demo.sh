#!/usr/bin/env bash
# The main job: installs, builds (Release) and builds the 3D road network of Potrero Hill
# (../shared/data/sf-potrero, the seed paper's 10 m USGS DEM, validated against the 30 m USGS
# quadrangle) into out/: OpenDRIVE, the SUMO scenario (200 random trips), the 3D scene, reports. Without ../shared it builds the synthetic sample in fixtures/hill.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bash "$root/tools/build.sh"
data="$root/../shared/data"
if [ -d "$data/sf-potrero" ]; then
  "$root/build/tools/relief" build \
    --osm "$data/sf-potrero/sf-potrero.osm.gz" \
    --dem "$data/sf-potrero/USGS_13_n38w123-subsection-small-potrero.tif" \
    --reference-dem "$data/sf-dem/sf_north_quad_usgs24k_30m_nad27utm10_m.tif" \
    --routes 200 --out "$root/out" "$@"
else
  echo "relief: ../shared/data not found; building the synthetic sample fixtures/hill" >&2
  "$root/build/tools/relief" build \
    --osm "$root/fixtures/hill/hill.osm" --dem "$root/fixtures/hill/hill_dem.asc" \
    --out "$root/out" "$@"
fi
