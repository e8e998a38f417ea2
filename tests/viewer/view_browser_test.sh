#!/usr/bin/env bash
# view.html of a real build in headless Chromium: builds SET (potrero or northeast) from
# ../shared/data into $RELIEF_TMP/SET, then runs view_browser_test.mjs on its view.html, whose
# screenshots stay in $RELIEF_TMP/SET/shots. On potrero also a 60 s co-simulation of 200 routes
# and its replay page ($RELIEF_TMP/potrero-cosim). Exit 77 (skipped) without the data.
set -euo pipefail
set_name=$1
data="$RELIEF_SOURCE_DIR/../shared/data"
case $set_name in
  potrero) inputs=(--osm "$data/sf-potrero/sf-potrero.osm.gz" --dem "$data/sf-potrero/USGS_13_n38w123-subsection-small-potrero.tif")
           road="Carolina Street"
           outputs=(--routes 200) ;;
  northeast) inputs=(--osm "$data/sf-ne/sf_ne_drive_2017.osm.gz" --dem "$data/sf-ne/sf_ne_usgs24k_30m_nad27utm10_m.tif")
             road="Hyde Street"
             outputs=(--outputs view,mesh,sight,html,report) ;;
  *) echo "unknown set $set_name" >&2; exit 2 ;;
esac
[ -f "${inputs[1]}" ] || { echo "skipped: ${inputs[1]} is not there"; exit 77; }
out="$RELIEF_TMP/$set_name"
rm -rf "$out"
mkdir -p "$out"
# The view, its findings (sight, the mesh checks) and the report it links to (potrero: everything,
# with routes for the co-simulation).
"$RELIEF" build "${inputs[@]}" "${outputs[@]}" --mesh-formats glb --out "$out" >"$out.log" 2>&1 ||
  { echo "relief build failed (exit $?): see $out.log"; tail -5 "$out.log"; exit 1; }
grep -q 'href="view.html"' "$out/report.html" || { echo "report.html does not link view.html"; exit 1; }
node "$RELIEF_SOURCE_DIR/tests/viewer/view_browser_test.mjs" --view "$out/view.html" --road "$road" --shots "$out/shots"
if [ "$set_name" = potrero ]; then
  "$RELIEF" cosim --sumocfg "$out"/*.sumocfg --end 60 --out "$out-cosim" >"$out-cosim.log" 2>&1 ||
    { echo "relief cosim failed (exit $?): see $out-cosim.log"; tail -5 "$out-cosim.log"; exit 1; }
  node "$RELIEF_SOURCE_DIR/tests/viewer/view_browser_test.mjs" --view "$out-cosim/view.html" --road "$road" \
    --shots "$out-cosim/shots" --replay 1
fi
