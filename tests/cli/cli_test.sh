#!/usr/bin/env bash
# End-to-end checks of the relief CLI: a good build, and every bad input with its documented
# exit code (0 done, 1 internal, 2 usage, 3 bad input, 4 outputs failed quality gates), a message
# that names the file and the
# problem, and no output files left behind (but with exit 4, every output).
set -u
: "${RELIEF:?path of the relief binary}" "${RELIEF_SOURCE_DIR:?}" "${RELIEF_TMP:?}"
rm -rf "$RELIEF_TMP" && mkdir -p "$RELIEF_TMP"
fix="$RELIEF_SOURCE_DIR/fixtures/hill"
failures=0
passed=0

check() {  # check NAME CONDITION-COMMAND...
  local name=$1; shift
  if "$@"; then passed=$((passed + 1)); else echo "FAIL: $name"; failures=$((failures + 1)); fi
}

# run EXPECTED_CODE OUTDIR ARGS... : runs relief, keeps stderr in $RELIEF_TMP/err
run() {
  local expected=$1 out=$2; shift 2
  "$RELIEF" "$@" >"$RELIEF_TMP/stdout" 2>"$RELIEF_TMP/err"
  local code=$?
  if [ "$code" -ne "$expected" ]; then
    echo "exit $code, expected $expected, for: relief $*"; cat "$RELIEF_TMP/err"; return 1
  fi
}
no_outputs() { [ ! -d "$1" ] || [ -z "$(ls -A "$1")" ]; }
stderr_has() { grep -q -- "$1" "$RELIEF_TMP/err" || { echo "stderr lacks '$1':"; cat "$RELIEF_TMP/err"; return 1; }; }

# A good build of the synthetic plane: z rises 6 % east and 10 % north.
out="$RELIEF_TMP/good"
check "fixture builds" run 0 "$out" build --osm "$fix/hill.osm" --dem "$fix/hill_dem.asc" --out "$out" --quiet
check "geojson written" test -s "$out/hill.geojson"
check "report written" test -s "$out/report.json"
check "report figures" python3 - "$out/report.json" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
g = r["gradient"]
assert abs(g["max_percent"] - 10.0) < 0.15, g            # north-south avenues on a 10 % plane
assert abs(g["by_class"]["primary"]["max_percent"] - 6.0) < 0.15, g  # east-west street, 6 %
assert r["junctions"]["max_gap_m"] < 1e-6, r["junctions"]
assert r["elevation"]["vs_dem"]["max_m"] < 1e-3, r["elevation"]
assert r["network"]["roads"] > 0 and r["network"]["bridges"] == 1, r["network"]
assert "OpenStreetMap" in r["attribution"]
PY
check "no temporaries" bash -c "! ls '$out' | grep -q tmp"
check "xodr written" test -s "$out/hill.xodr"
xsd="$(cd "$RELIEF_SOURCE_DIR/.." && pwd)/shared/opendrive-xsd/1.7.0/opendrive_17_core.xsd"
if [ -f "$xsd" ] && command -v xmllint >/dev/null; then
  check "xodr validates (1.7)" xmllint --noout --schema "$xsd" "$out/hill.xodr"
fi
check "report opendrive figures" python3 - "$out/report.json" <<'PY'
import json, sys
o = json.load(open(sys.argv[1]))["opendrive"]
assert o["junctions"] + o["junctions_without_movements"] == json.load(open(sys.argv[1]))["network"]["intersections"], o
assert o["max_link_gap_m"] < 0.01 and o["max_link_step_m"] < 0.01, o
assert o["round_trip_max_xy_m"] < 0.02 and o["round_trip_max_z_m"] < 0.02, o
PY

# Bad usage: exit 2.
check "unknown option" run 2 "" build --osm "$fix/hill.osm" --dem "$fix/hill_dem.asc" --out "$RELIEF_TMP/x" --frobnicate
check "bad --interp" run 2 "" build --osm "$fix/hill.osm" --dem "$fix/hill_dem.asc" --out "$RELIEF_TMP/x" --interp cubic
check "bad --bbox" run 2 "" build --osm "$fix/hill.osm" --dem "$fix/hill_dem.asc" --out "$RELIEF_TMP/x" --bbox 1,2,3
check "no subcommand" run 2 ""
check "--help is exit 0" run 0 "" build --help

# Missing OSM file: exit 3, names the file, no outputs.
out="$RELIEF_TMP/missing"
check "missing osm" run 3 "$out" build --osm "$RELIEF_TMP/nope.osm" --dem "$fix/hill_dem.asc" --out "$out"
check "missing osm message" stderr_has "nope.osm"
check "missing osm no outputs" no_outputs "$out"
check "missing dem" run 3 "$out" build --osm "$fix/hill.osm" --dem "$RELIEF_TMP/nope.tif" --out "$out"
check "missing dem message" stderr_has "nope.tif"
check "missing dem no outputs" no_outputs "$out"

# Truncated OSM (gzip cut in half): exit 3, message, no outputs.
gzip -c "$fix/hill.osm" > "$RELIEF_TMP/full.osm.gz"
head -c $(( $(stat -c %s "$RELIEF_TMP/full.osm.gz") / 2 )) "$RELIEF_TMP/full.osm.gz" > "$RELIEF_TMP/truncated.osm.gz"
out="$RELIEF_TMP/truncated"
check "truncated osm" run 3 "$out" build --osm "$RELIEF_TMP/truncated.osm.gz" --dem "$fix/hill_dem.asc" --out "$out"
check "truncated osm message" stderr_has "truncated.osm.gz"
check "truncated osm no outputs" no_outputs "$out"

# A way whose node is missing: reported and skipped, not fatal.
sed "s|<nd ref='1011'/>|<nd ref='99999'/>|" "$fix/hill.osm" > "$RELIEF_TMP/missing_node.osm"
out="$RELIEF_TMP/missing_node"
check "missing node is not fatal" run 0 "$out" build --osm "$RELIEF_TMP/missing_node.osm" --dem "$fix/hill_dem.asc" --out "$out"
check "missing node reported" stderr_has "osm.missing_node"
check "missing node in report" grep -q '"osm.missing_node"' "$out/report.json"

# A DEM that does not cover the roads (the fixture DEM moved 1 degree west): exit 3.
gdal_translate -q -a_ullr -123.405 37.758 -123.393 37.748 "$fix/hill_dem.asc" "$RELIEF_TMP/elsewhere.tif"
out="$RELIEF_TMP/uncovered"
check "uncovered dem" run 3 "$out" build --osm "$fix/hill.osm" --dem "$RELIEF_TMP/elsewhere.tif" --out "$out"
check "uncovered message" stderr_has "does not cover"
check "uncovered no outputs" no_outputs "$out"

# A DEM that covers only part of the roads: exit 3 unless --allow-partial.
gdal_translate -q -srcwin 0 0 30 50 "$fix/hill_dem.asc" "$RELIEF_TMP/half.tif"
out="$RELIEF_TMP/partial"
check "partial dem refused" run 3 "$out" build --osm "$fix/hill.osm" --dem "$RELIEF_TMP/half.tif" --out "$out"
check "partial dem says how much" stderr_has "%"
check "partial dem no outputs" no_outputs "$out"
check "partial dem allowed" run 0 "$out" build --osm "$fix/hill.osm" --dem "$RELIEF_TMP/half.tif" --out "$out" --allow-partial
check "partial dem reported" grep -q '"elevation.uncovered"' "$out/report.json"

# A DEM that is all nodata: exit 3.
gdal_calc.py --quiet -A "$fix/hill_dem.asc" --calc="A*0-9999" --NoDataValue=-9999 --outfile="$RELIEF_TMP/void.tif" >/dev/null 2>&1 \
  || gdal_translate -q -scale 0 1000 -9999 -9999 -a_nodata -9999 "$fix/hill_dem.asc" "$RELIEF_TMP/void.tif"
out="$RELIEF_TMP/void"
check "all-nodata dem" run 3 "$out" build --osm "$fix/hill.osm" --dem "$RELIEF_TMP/void.tif" --out "$out"
check "all-nodata message" stderr_has "nodata"
check "all-nodata no outputs" no_outputs "$out"

# An unreadable raster (text with a .tif name): exit 3.
echo "not a raster" > "$RELIEF_TMP/text.tif"
out="$RELIEF_TMP/unreadable"
check "unreadable dem" run 3 "$out" build --osm "$fix/hill.osm" --dem "$RELIEF_TMP/text.tif" --out "$out"
check "unreadable message" stderr_has "text.tif"
check "unreadable no outputs" no_outputs "$out"

# A DEM in feet that does not say so: --dem-unit ft gives the same roads as the metre DEM.
gdal_translate -q -ot Float64 -scale 0 1 0 3.280839895 "$fix/hill_dem.asc" "$RELIEF_TMP/feet.tif"
out="$RELIEF_TMP/feet"
check "feet dem with unit" run 0 "$out" build --osm "$fix/hill.osm" --dem "$RELIEF_TMP/feet.tif" --dem-unit ft --out "$out" --quiet
check "feet dem grades" python3 - "$out/report.json" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
assert abs(r["gradient"]["max_percent"] - 10.0) < 0.15, r["gradient"]
assert r["inputs"]["dems"][0]["vertical_unit"] == "ft" and r["inputs"]["dems"][0]["unit_source"] == "user"
PY
out="$RELIEF_TMP/feet_unstated"
# Read as metres, the feet DEM is a plane of 32.8 % north and 19.7 % east, 38 % at its steepest:
# the roads keep their grades (under the 35 % cap) and the junctions are flattened to the cap, so
# that the connecting roads across them stay within it; every gate passes.
check "feet dem without unit" run 0 "$out" build --osm "$fix/hill.osm" --dem "$RELIEF_TMP/feet.tif" --out "$out" --quiet
check "feet dem unstated is 3.28x steeper" python3 - "$out/report.json" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
# 3.28 x the metre DEM's 10 % along the roads, flattened at the junctions (to keep the connecting
# roads within the 35 % cap), so the roads climb up to the cap between them
assert 32.0 < r["gradient"]["max_percent"] <= 35.0 + 1e-3, r["gradient"]
assert all(g["passed"] for g in r["gates"].values()), r["gates"]
assert r["gates"]["connecting_road_grade_over_cap_percent"]["value"] <= 2.0, r["gates"]
# The roads' ends lie across their junctions' planes within --max-cross-slope (12 %), not at
# the plane's 32.8 %; a transition road bending 90 degrees across a node's plane turns its roll
# with its heading, up to sqrt(2) x 12 % half-way (16.95 % measured, on road 21; not bounded yet)
assert r["profiles"]["fit"]["max_cross_slope_percent"] == 12.0, r["profiles"]["fit"]
assert r["model_grades"]["cross_slopes"]["max_percent"] <= 17.5, r["model_grades"]["cross_slopes"]
PY
# Built to fail: the design policy caps these streets at 15 % while a ground road may leave the
# 33 % plane by only 0.5 m. The fit honours the ground first and says where the grades give:
# exit 4, every output written, the gate and its place in the summary and in report.json.
out="$RELIEF_TMP/feet_conflict"
check "conflict exits 4" run 4 "$out" build --osm "$fix/hill.osm" --dem "$RELIEF_TMP/feet.tif" --out "$out" --quiet \
  --grade-policy design --max-ground-departure 0.5
check "conflict gate named" grep -q "GATE FAILED fit_limits_violated: [0-9]* (threshold 0), .* on road [0-9]* (OSM way [0-9]*) at s = " "$RELIEF_TMP/stdout"
check "conflict outputs written" test -s "$out/hill.xodr" -a -s "$out/hill.net.xml" -a -s "$out/hill.glb"
check "conflict report" python3 - "$out/report.json" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
g = r["gates"]["fit_limits_violated"]
assert not g["passed"] and g["value"] > 0 and "OSM way" in g["where"], g
v = r["profiles"]["fit"]["violations"]
# The ground bound outranks every other limit and holds exactly; the grades (and below them the
# junction grades and vertical curves) give way.
assert v and not any(x["limit"] == "ground_departure" for x in v), v[:3]
assert v[0]["limit"] == "grade" and v[0]["osm_way_id"] > 0 and v[0]["value"] > v[0]["bound"] == 15.0, v[:1]
assert r["gates"]["fit_converged"]["passed"], r["gates"]
PY

# Rasters through GDAL's virtual file systems: a VRT mosaic and a zipped DEM.
gdalbuildvrt -q "$RELIEF_TMP/mosaic.vrt" "$fix/hill_dem.asc"
out="$RELIEF_TMP/vrt"
check "vrt dem" run 0 "$out" build --osm "$fix/hill.osm" --dem "$RELIEF_TMP/mosaic.vrt" --out "$out" --quiet --outputs report
(cd "$fix" && zip -q "$RELIEF_TMP/dem.zip" hill_dem.asc hill_dem.prj)
out="$RELIEF_TMP/vsizip"
check "zipped dem" run 0 "$out" build --osm "$fix/hill.osm" --dem "/vsizip/$RELIEF_TMP/dem.zip/hill_dem.asc" --out "$out" --quiet --outputs report

# SUMO: random trips on the fixture give NAME.rou.xml and NAME.sumocfg (20 Hz) that sumo runs.
export SUMO_HOME="${SUMO_HOME:-/usr/share/sumo}"
out="$RELIEF_TMP/routes"
check "sumo routes" run 0 "$out" build --osm "$fix/hill.osm" --dem "$fix/hill_dem.asc" --out "$out" --quiet \
  --outputs xodr,sumo --routes 20
check "sumo net written" test -s "$out/hill.net.xml"
check "sumo routes written" grep -q "<vehicle " "$out/hill.rou.xml"
# The same with an output directory relative to the working directory (SUMO's tools run in it).
check "sumo routes, relative --out" bash -c "cd '$RELIEF_TMP' && '$RELIEF' build --osm '$fix/hill.osm' \
  --dem '$fix/hill_dem.asc' --out routes_relative --quiet --outputs xodr,sumo --routes 20 >/dev/null 2>&1 \
  && grep -q '<vehicle ' routes_relative/hill.rou.xml"
# SUMO splits file options at commas: a comma in --out ("box_9.5,47.1") once cut netconvert's
# paths apart (exit 3). The build now passes bare names; cosim says why it cannot start there.
comma="$RELIEF_TMP/box_9.5,47.1"
check "comma in --out builds" run 0 "$comma" build --osm "$fix/hill.osm" --dem "$fix/hill_dem.asc" --out "$comma" \
  --quiet --outputs xodr,sumo --routes 20
check "comma in --out, routes" grep -q "<vehicle " "$comma/hill.rou.xml"
check "comma in --out, cosim refuses" run 3 "$comma/cosim" cosim --sumocfg "$comma/hill.sumocfg" --out "$comma/cosim" --end 1
check "comma in --out, cosim says why" stderr_has "splits file paths at commas"
check "sumocfg step length" python3 - "$out/hill.sumocfg" <<'PY'
import sys, xml.etree.ElementTree as ET
c = ET.parse(sys.argv[1]).getroot()
assert abs(float(c.find("time/step-length").get("value")) - 0.05) < 1e-9
assert c.find("input/net-file").get("value") == "hill.net.xml"
assert c.find("input/route-files").get("value") == "hill.rou.xml"
PY
check "sumo runs the config" bash -c "cd '$out' && sumo -c hill.sumocfg --end 30 --no-step-log true >'$RELIEF_TMP/sumo.log' 2>&1 \
  || { cat '$RELIEF_TMP/sumo.log'; exit 1; }"
# cosim: SUMO on that configuration, every vehicle set on the road surface at 20 Hz for 30 s (this
# build wrote no scene: the .xodr's roads are lofted, without terrain for a wheel off the road).
cs="$out/cosim"
check "cosim runs" run 0 "$cs" cosim --sumocfg "$out/hill.sumocfg" --out "$cs" --end 30
check "cosim outputs" python3 - "$cs" <<'PY'
import csv, json, sys, xml.etree.ElementTree as ET
d = sys.argv[1]
r = json.load(open(d + "/cosim.json"))
assert r["steps"] == 600 and abs(r["simulated_s"] - 30) < 1e-9, r
assert r["inputs"]["scene"] == "" and r["vehicles"] > 0, r
assert r["unplaced_vehicle_steps"] <= 0.01 * r["vehicle_steps"], r
assert r["z_error_m"]["max"] <= 0.05 and r["sumo_z_error_m"]["max"] <= 0.05, r
rows = list(csv.reader(open(d + "/hill.trajectories.csv")))
assert len(rows) == r["vehicle_steps"] + 1, (len(rows), r["vehicle_steps"])
steps = ET.parse(d + "/hill.fcd.xml").getroot().findall("timestep")
assert len(steps) == 600 and steps[-1].find("vehicle").get("pitch") is not None
print("cosim hill: %d vehicles, z error max %.4f m, SUMO z error max %.4f m" %
      (r["vehicles"], r["z_error_m"]["max"], r["sumo_z_error_m"]["max"]))
PY
check "cosim replay" test -s "$cs/cosim.glb"
# The same run over TraCI, with an ego: SUMO as its own process (--traci), then a SUMO the user
# started with --remote-port (--sumo-port): the same traffic, placements and sync as in process.
check "cosim in process with an ego" run 0 "$cs-ego" cosim --sumocfg "$out/hill.sumocfg" --out "$cs-ego" --end 20 --egos 1
check "cosim over traci" run 0 "$cs-traci" cosim --sumocfg "$out/hill.sumocfg" --out "$cs-traci" --end 20 --egos 1 --traci
port=$((20000 + $$ % 20000))
(cd "$out" && sumo -c hill.sumocfg --step-length 0.05 --remote-port "$port" --no-step-log true \
  >"$RELIEF_TMP/sumo_remote.log" 2>&1 &)
check "cosim attached" run 0 "$cs-attach" cosim --sumocfg "$out/hill.sumocfg" --out "$cs-attach" --end 20 --egos 1 \
  --sumo-port "$port"
check "cosim over traci agrees" python3 - "$cs-ego" "$cs-traci" "$cs-attach" <<'PY'
import json, sys
a, b, c = (json.load(open(d + "/cosim.json")) for d in sys.argv[1:])
assert a["sumo"] == "in process (libsumo)" and b["sumo"] == "TraCI to sumo (launched)", (a["sumo"], b["sumo"])
assert c["sumo"].startswith("TraCI to localhost:"), c["sumo"]
for k in ("steps", "vehicles", "vehicle_steps", "egos", "ego_steps", "resyncs"):
    assert a[k] == b[k] == c[k], (k, a[k], b[k], c[k])
for k in ("z_error_m", "sync_error_m"):
    for q in ("p50", "p99", "max"):
        assert abs(a[k][q] - b[k][q]) <= 1e-9 and abs(a[k][q] - c[k][q]) <= 1e-9, (k, q, a[k], b[k], c[k])
print("cosim hill over TraCI: %d vehicle steps, %d ego steps, sync p99 %.3f m in all three; wall %.2f / %.2f / %.2f s"
      % (a["vehicle_steps"], a["ego_steps"], a["sync_error_m"]["p99"], a["wall_s"], b["wall_s"], c["wall_s"]))
PY
check "cosim attach to nothing" run 3 "$RELIEF_TMP/cosim_nothing" cosim --sumocfg "$out/hill.sumocfg" \
  --out "$RELIEF_TMP/cosim_nothing" --sumo-port 1 --end 1
check "cosim attach to nothing says so" stderr_has "no SUMO answers at localhost:1"
check "cosim attach to nothing no outputs" no_outputs "$RELIEF_TMP/cosim_nothing"
check "cosim traci and port" run 2 "$RELIEF_TMP/cosim_both" cosim --sumocfg "$out/hill.sumocfg" \
  --out "$RELIEF_TMP/cosim_both" --traci --sumo-port 9999
check "cosim without config" run 2 "$RELIEF_TMP/cosim_none" cosim --out "$RELIEF_TMP/cosim_none"
check "cosim missing config" run 3 "$RELIEF_TMP/cosim_missing" cosim --sumocfg "$RELIEF_TMP/nowhere.sumocfg" \
  --out "$RELIEF_TMP/cosim_missing"
check "cosim missing config names it" stderr_has "nowhere.sumocfg"
check "cosim missing config no outputs" no_outputs "$RELIEF_TMP/cosim_missing"
check "cosim bad step" run 2 "$RELIEF_TMP/cosim_step" cosim --sumocfg "$out/hill.sumocfg" --out "$RELIEF_TMP/cosim_step" \
  --step 0
check "cosim bad resync" run 2 "$RELIEF_TMP/cosim_resync" cosim --sumocfg "$out/hill.sumocfg" \
  --out "$RELIEF_TMP/cosim_resync" --egos 1 --resync nan
# demand: the example counts on the hill's net, reproduced by routeSampler (GEH < 5 everywhere),
# and SUMO runs the configuration without SUMO_HOME; bad counts are bad input.
dm="$RELIEF_TMP/demand"
check "demand runs" run 0 "$dm" demand --net "$out/hill.net.xml" --counts "$fix/counts.csv" --out "$dm" --trucks 10
check "demand figures" python3 - "$dm/demand.json" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
print("demand hill: %d rows on %d edges, %d vehicles (%d trucks), GEH < 5 on %.0f %%" %
      (r["count_rows"], r["counted_edges"], r["vehicles"], r["trucks"], 100 * r["geh_ok_share"]))
assert r["count_rows"] == 5 and not r["unmatched_rows"] and r["geh_ok_share"] == 1.0, r
PY
check "sumo runs the demand" bash -c "cd '$dm' && env -u SUMO_HOME sumo -c hill.demand.sumocfg --end 60 \
  --no-step-log true >'$RELIEF_TMP/sumo_demand.log' 2>&1 || { cat '$RELIEF_TMP/sumo_demand.log'; exit 1; }"
check "demand od" run 0 "$RELIEF_TMP/demand_od" demand --net "$out/hill.net.xml" --od "$fix/od.csv" \
  --zones "$fix/zones.geojson" --out "$RELIEF_TMP/demand_od"
check "demand od trips" grep -q '"od_trips": 230' "$RELIEF_TMP/demand_od/demand.json"
check "demand turn counts" run 0 "$RELIEF_TMP/demand_turns" demand --net "$out/hill.net.xml" \
  --turn-counts "$fix/turns.csv" --out "$RELIEF_TMP/demand_turns"
check "demand turn figures" python3 - "$RELIEF_TMP/demand_turns/demand.json" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
print("demand hill turns: %d rows on %d turns, %d vehicles, GEH < 5 on %.0f %%" %
      (r["turn_rows"], r["counted_turns"], r["vehicles"], 100 * r["geh_ok_share"]))
assert r["turn_rows"] == 3 and r["counted_turns"] == 3 and r["geh_ok_share"] == 1.0, r
PY
check "demand od without zones" run 2 "$RELIEF_TMP/demand_od2" demand --net "$out/hill.net.xml" --od "$fix/od.csv" \
  --out "$RELIEF_TMP/demand_od2"
printf 'osm_way,direction,count\n101,up,5\n' >"$RELIEF_TMP/bad_counts.csv"
check "demand bad direction" run 3 "$RELIEF_TMP/demand_bad" demand --net "$out/hill.net.xml" \
  --counts "$RELIEF_TMP/bad_counts.csv" --out "$RELIEF_TMP/demand_bad"
check "demand bad direction says where" stderr_has "line 2: unknown direction 'up'"
check "demand missing counts" run 3 "$RELIEF_TMP/demand_none" demand --net "$out/hill.net.xml" \
  --counts "$RELIEF_TMP/nowhere.csv" --out "$RELIEF_TMP/demand_none"
# --mesh-tile-size: the scene also cut into tiles; a size that is not positive is exit 2.
out="$RELIEF_TMP/tiles"
check "mesh tiles" run 0 "$out" build --osm "$fix/hill.osm" --dem "$fix/hill_dem.asc" --out "$out" --quiet \
  --outputs mesh --mesh-formats glb --mesh-tile-size 50
tile=$(ls "$out"/hill_Tile_*_*.glb 2>/dev/null | head -1)
check "mesh tiles written" test -n "$tile"
check "mesh tile re-reads" run 0 "" mesh-report "${tile:-$out/none.glb}"
check "bad --mesh-tile-size" run 2 "" build --osm "$fix/hill.osm" --dem "$fix/hill_dem.asc" --out "$RELIEF_TMP/x" \
  --mesh-tile-size 0

# --carla-package: NAME.carla.tar.gz, the folder CARLA's `make import` ingests. GNU tar lists
# and extracts it; python3 (tarfile, json) checks the JSON's keys and types as CARLA's
# documentation and Import.py have them, every file it names, and the tiled form's whole grid.
carla_check() {  # carla_check PACKAGE OUTDIR NAME TILE_SIZE(0: standard map)
  python3 - "$@" <<'PY'
import json, os, re, sys, tarfile
package, out, name, tile_size = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4])
with tarfile.open(package, "r:gz") as t:
    members = {m.name: m for m in t.getmembers()}
    doc = json.load(t.extractfile(members[f"{name}/{name}.json"]))
    data = {n: t.extractfile(m).read() for n, m in members.items() if m.isfile()}
assert set(doc) == {"maps", "props"} and doc["props"] == [], doc
assert len(doc["maps"]) == 1, doc
m = doc["maps"][0]
assert m["name"] == name and m["use_carla_materials"] is True, m
root = name + "/"
def member(path):
    assert path.startswith("./"), path
    assert root + path[2:] in data, (path, sorted(data))
    return data[root + path[2:]]
assert os.path.basename(m["xodr"]) == name + ".xodr", m
assert member(m["xodr"]) == open(os.path.join(out, name + ".xodr"), "rb").read()
if tile_size == 0:
    assert set(m) == {"name", "source", "use_carla_materials", "xodr"}, m
    assert os.path.basename(m["source"]) == name + ".fbx", m
    assert member(m["source"]) == open(os.path.join(out, name + ".fbx"), "rb").read()
    print("carla package: %d entries, %s" % (len(members), m["source"]))
else:
    assert set(m) == {"name", "xodr", "use_carla_materials", "tile_size", "tiles"}, m
    assert m["tile_size"] == tile_size and isinstance(m["tile_size"], int), m
    tiles = set()
    for path in m["tiles"]:
        x, y = map(int, re.fullmatch(r"\./" + re.escape(name) + r"_Tile_(\d+)_(\d+)\.fbx", path).groups())
        tiles.add((x, y))
        written = os.path.join(out, os.path.basename(path))
        if os.path.exists(written):
            assert member(path) == open(written, "rb").read(), path
        else:
            assert b"Placeholder" in member(path), path
    nx, ny = max(x for x, _ in tiles) + 1, max(y for _, y in tiles) + 1
    assert tiles == {(x, y) for x in range(nx) for y in range(ny)}, sorted(tiles)
    print("carla large map: %d x %d tiles of %d m" % (nx, ny, tile_size))
PY
}
out="$RELIEF_TMP/carla"
check "carla package" run 0 "$out" build --osm "$fix/hill.osm" --dem "$fix/hill_dem.asc" --out "$out" --quiet \
  --outputs xodr,mesh,report --mesh-formats fbx --carla-package
check "carla package lists with tar" bash -c "tar -tzf '$out/hill.carla.tar.gz' >/dev/null"
check "carla package extracts with tar" tar -xzf "$out/hill.carla.tar.gz" -C "$out"
check "carla package extracted" cmp "$out/hill/hill/hill.fbx" "$out/hill.fbx"
check "carla package checks" carla_check "$out/hill.carla.tar.gz" "$out" hill 0
out="$RELIEF_TMP/carla_tiles"
check "carla large map" run 0 "$out" build --osm "$fix/hill.osm" --dem "$fix/hill_dem.asc" --out "$out" --quiet \
  --outputs xodr,mesh --mesh-formats fbx,glb --mesh-tile-size 50 --carla-package
check "carla large map checks" carla_check "$out/hill.carla.tar.gz" "$out" hill 50
check "carla package without fbx" run 2 "$RELIEF_TMP/carla_bad" build --osm "$fix/hill.osm" --dem "$fix/hill_dem.asc" \
  --out "$RELIEF_TMP/carla_bad" --mesh-formats glb --carla-package
check "carla package without fbx says why" stderr_has "needs the xodr and mesh outputs and the fbx mesh format"
check "carla package without fbx no outputs" no_outputs "$RELIEF_TMP/carla_bad"
check "carla tile over 2000 m" run 2 "" build --osm "$fix/hill.osm" --dem "$fix/hill_dem.asc" \
  --out "$RELIEF_TMP/carla_bad" --mesh-tile-size 2500 --carla-package

check "bad --vclass-max-grade" run 2 "" build --osm "$fix/hill.osm" --dem "$fix/hill_dem.asc" --out "$RELIEF_TMP/x" \
  --vclass-max-grade truck=abc

# No netconvert (not on PATH, SUMO_HOME empty): exit 3, names the tool, no outputs and no
# scratch directory left behind.
mkdir -p "$RELIEF_TMP/nosumo/bin" "$RELIEF_TMP/nosumo/home"
ln -sf "$(command -v cat)" "$RELIEF_TMP/nosumo/bin/cat"
run_without_sumo() { PATH="$RELIEF_TMP/nosumo/bin" SUMO_HOME="$RELIEF_TMP/nosumo/home" run "$@"; }
out="$RELIEF_TMP/nosumo/out"
check "no netconvert" run_without_sumo 3 "$out" build --osm "$fix/hill.osm" --dem "$fix/hill_dem.asc" --out "$out" \
  --outputs xodr,sumo,report
check "no netconvert message" stderr_has "netconvert"
check "no netconvert no outputs" no_outputs "$out"

# mesh-report: the scene of the good build in every format; bad mesh files exit 3.
good="$RELIEF_TMP/good"
for ext in glb obj fbx; do
  check "mesh-report $ext" run 0 "" mesh-report "$good/hill.$ext"
  check "mesh-report $ext names Road_Road" grep -q "Road_Road" "$RELIEF_TMP/stdout"
done
check "mesh-report --json -" run 0 "" mesh-report "$good/hill.glb" --json -
check "mesh-report --json - is JSON" python3 -m json.tool "$RELIEF_TMP/stdout" /dev/null
check "mesh-report --json - names Road_Road" grep -q "Road_Road" "$RELIEF_TMP/stdout"
check "mesh-report missing file" run 3 "" mesh-report "$RELIEF_TMP/nope.glb"
check "mesh-report missing file message" stderr_has "nope.glb"
echo "not a mesh" > "$RELIEF_TMP/x.glb"
check "mesh-report text as .glb" run 3 "" mesh-report "$RELIEF_TMP/x.glb"
check "mesh-report text as .glb message" stderr_has "x.glb"

# sight: the good build's sight distances from its files match the build's own (on the plane,
# nothing hides a lane: every lane-km checked, none short); a missing scene is exit 3.
check "sight" run 0 "" sight --xodr "$good/hill.xodr" --out "$RELIEF_TMP/sight"
check "sight files" test -s "$RELIEF_TMP/sight/hill.sight.geojson" -a -s "$RELIEF_TMP/sight/sight.json"
check "sight agrees with the build" python3 - "$RELIEF_TMP/sight/sight.json" "$good/report.json" "$good/hill.sight.geojson" <<'PY'
import json, sys
alone, built = json.load(open(sys.argv[1])), json.load(open(sys.argv[2]))["sight"]
assert built["file"] == "hill.sight.geojson", built
assert alone["km_checked"] == built["km_checked"] > 0.5, (alone, built)
assert alone["km_short"] == built["km_short"] == 0.0, (alone, built)
assert json.load(open(sys.argv[3]))["features"] == []
PY
check "sight without a scene" run 3 "" sight --xodr "$good/hill.xodr" --scene "$RELIEF_TMP/nope.glb" --out "$RELIEF_TMP/sight2"
check "sight without a scene message" stderr_has "nope.glb"
check "sight without a scene writes nothing" no_outputs "$RELIEF_TMP/sight2"
check "sight bad step" run 2 "" sight --xodr "$good/hill.xodr" --out "$RELIEF_TMP/sight2" --step 0

# lidar: one HDL-32E turn from 2 m over the good build's plane: every return within 0.05 m (its
# noise) of the plane's height under it, Open3D reads both files with every point; a point off
# the scene is exit 3.
check "lidar" run 0 "" lidar --scene "$good/hill.glb" --at 100,100 --height 2 --preset hdl-32e --out "$RELIEF_TMP/lidar"
check "lidar files open in Open3D" /usr/bin/python3 - "$RELIEF_TMP/lidar" <<'PY'
import sys, open3d as o3d
d = sys.argv[1]
header = open(d + "/lidar.pcd", "rb").read(400).decode("ascii", "replace")
n = int(header.split("POINTS ")[1].split()[0])
assert n > 10000, n
for f in ("lidar.pcd", "lidar.ply"):
    pc = o3d.io.read_point_cloud(d + "/" + f)
    assert len(pc.points) == n, (f, len(pc.points), n)
PY
check "lidar off the scene" run 3 "" lidar --scene "$good/hill.glb" --at 1e6,1e6 --out "$RELIEF_TMP/lidar2"
check "lidar off the scene message" stderr_has "--at X,Y,Z"

# info: describes without writing.
check "info" run 0 "" info --osm "$fix/hill.osm" --dem "$fix/hill_dem.asc"
check "info coverage" grep -q "100.00 % with height" "$RELIEF_TMP/stdout"

# A spacing whose samples would exhaust the machine: refused (bad usage) right after reading the
# roads, naming the estimate and the spacing that fits, nothing written. Not a number > 0: exit 2.
out="$RELIEF_TMP/tiny_spacing"
start=$SECONDS
check "tiny spacing refused" run 2 "$out" build --osm "$fix/hill.osm" --dem "$fix/hill_dem.asc" --out "$out" --spacing 1e-6
check "tiny spacing is refused at once" test $((SECONDS - start)) -le 10
check "tiny spacing message" stderr_has "sample spacing 1e-06 m would take 3.8e+09 elevation samples"
check "tiny spacing says what fits" stderr_has "use a spacing of at least"
check "tiny spacing no outputs" no_outputs "$out"
for bad in nan inf 0 -1; do
  check "--spacing $bad" run 2 "" build --osm "$fix/hill.osm" --dem "$fix/hill_dem.asc" --out "$RELIEF_TMP/x" --spacing="$bad"
  check "--spacing $bad message" stderr_has "not a finite number > 0"
done
# --fit-trace: the fit solver's progress in a file; a file that cannot be written is bad usage.
out="$RELIEF_TMP/fit_trace"
check "fit trace" run 0 "$out" build --osm "$fix/hill.osm" --dem "$fix/hill_dem.asc" --out "$out" --outputs report --fit-trace "$RELIEF_TMP/fit_trace.txt"
check "fit trace has the iterations" grep -q "^iteration 0 rows" "$RELIEF_TMP/fit_trace.txt"
check "fit trace unwritable" run 2 "" build --osm "$fix/hill.osm" --dem "$fix/hill_dem.asc" --out "$RELIEF_TMP/x" --fit-trace /nonexistent/dir/trace.txt
check "fit trace unwritable message" stderr_has "--fit-trace: cannot write"
for bad in "ground_holes=nan" "ground_holes" "no_such_gate=1"; do
  check "--gate $bad" run 2 "" build --osm "$fix/hill.osm" --dem "$fix/hill_dem.asc" --out "$RELIEF_TMP/x" --gate "$bad"
done
# Every numeric option refuses what is not a finite number in its range (CLI11's own
# PositiveNumber let nan and inf through).
for opt in --spacing --max-grade --highway-max-grade --clearance --smoothing-wavelength --max-curvature \
    --routes --route-end --seed --step-length --mesh-tolerance --terrain-tolerance --mesh-tile-size \
    --max-ground-departure --ground-filter; do
  for bad in nan inf -inf -1; do
    check "$opt $bad" run 2 "" build --osm "$fix/hill.osm" --dem "$fix/hill_dem.asc" --out "$RELIEF_TMP/x" "$opt=$bad"
    check "$opt $bad message" stderr_has "$opt: '$bad' is not a finite number"
  done
done
# Values the library parses (enums, lists, CLASS=PERCENT, NAME=VALUE, boxes): a bad one is bad
# usage, and the message names the option and the value.
while read -r opt bad named; do
  check "$opt $bad" run 2 "" build --osm "$fix/hill.osm" --dem "$fix/hill_dem.asc" --out "$RELIEF_TMP/x" "$opt=$bad"
  check "$opt $bad message" stderr_has "$opt: '$named' is not"
done <<'LIST'
--interp cubic cubic
--dem-unit yards yards
--reference-dem-unit yards yards
--nodata-fill zero zero
--profiles spline spline
--grade-policy strict strict
--outputs xodr,pdf pdf
--mesh-formats glb,stl stl
--bbox 1,2,3 1,2,3
LIST
check "--grade-limits bad class" run 2 "" build --osm "$fix/hill.osm" --dem "$fix/hill_dem.asc" --out "$RELIEF_TMP/x" \
  --grade-limits boulevard=5
check "--grade-limits message" stderr_has "--grade-limits: grade limit 'boulevard=5'"
check "--vclass-max-grade inf" run 2 "" build --osm "$fix/hill.osm" --dem "$fix/hill_dem.asc" --out "$RELIEF_TMP/x" \
  --vclass-max-grade truck=inf
check "--vclass-max-grade message" stderr_has "--vclass-max-grade: 'truck=inf': the grade must be a percent > 0"
check "--gate message" run 2 "" build --osm "$fix/hill.osm" --dem "$fix/hill_dem.asc" --out "$RELIEF_TMP/x" \
  --gate no_such_gate=1
check "--gate message names the gate" stderr_has "--gate: 'no_such_gate' is not a quality gate"
check "info --interp cubic" run 2 "" info --osm "$fix/hill.osm" --dem "$fix/hill_dem.asc" --interp cubic
# --help shows the library's defaults (bound to BuildOptions, not a copy in the CLI).
check "help shows library defaults" run 0 "" build --help
for shown in "--max-grade FLOAT:FINITE > 0=35" "--interp TEXT=bilinear" "--outputs TEXT=all" \
    "--mesh-formats TEXT=glb,obj,fbx" "--mesh-tolerance FLOAT:FINITE > 0=0.02" "defaults bus=20 coach=15 trailer=10 truck=15"; do
  check "help shows $shown" grep -q -- "$shown" "$RELIEF_TMP/stdout"
done

# Real data with hostile cells: the Potrero DEM copied with one cell under 24th Street set to
# 1e30 (an unflagged fill value) and one under Carolina Street to 160 m (a spike ~110 m above
# its neighbours). Both become voids, filled along the roads; without the checks the road RMSE
# vs DEM was 3.7e26 m.
shared="${RELIEF_SHARED_DATA:-$(cd "$RELIEF_SOURCE_DIR/.." && pwd)/shared/data}"
potrero="$shared/sf-potrero"
if [ -d "$potrero" ] && command -v gdal_rasterize >/dev/null; then
  spiked="$RELIEF_TMP/potrero_spiked.tif"
  gdal_translate -q "$potrero/USGS_13_n38w123-subsection-small-potrero.tif" "$spiked"
  point() {  # point FILE LON LAT: a GeoJSON point
    echo "{\"type\":\"FeatureCollection\",\"features\":[{\"type\":\"Feature\",\"properties\":{},\"geometry\":{\"type\":\"Point\",\"coordinates\":[$2,$3]}}]}" > "$1"
  }
  point "$RELIEF_TMP/fill.geojson" -122.4014972 37.7532932     # an OSM node of 24th Street
  point "$RELIEF_TMP/spike.geojson" -122.3995141 37.7537644    # an OSM node of Carolina Street
  gdal_rasterize -q -burn 1e30 "$RELIEF_TMP/fill.geojson" "$spiked"
  gdal_rasterize -q -burn 160 "$RELIEF_TMP/spike.geojson" "$spiked"
  out="$RELIEF_TMP/spiked"
  check "spiked potrero builds" run 0 "$out" build --osm "$potrero/sf-potrero.osm.gz" --dem "$spiked" --out "$out" \
    --outputs report
  check "spiked potrero fill reported" stderr_has "dem.implausible_height"
  check "spiked potrero spike reported" stderr_has "dem.spike"
  check "spiked potrero figures" python3 - "$out/report.json" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
print("spiked potrero: RMSE vs DEM %.4f m, max grade %.2f %%, diagnostics %s"
      % (r["elevation"]["vs_dem"]["rmse_m"], r["gradient"]["max_percent"], r["diagnostics"]["counts"]))
assert r["elevation"]["vs_dem"]["rmse_m"] < 1.0, r["elevation"]
assert r["gradient"]["max_percent"] <= 35.0, r["gradient"]
counts = r["diagnostics"]["counts"]
assert counts.get("dem.implausible_height") == 1 and counts.get("dem.spike") == 1, counts
dem = r["inputs"]["dems"][0]
assert dem["implausible_cells"] == 1 and dem["spike_cells"] == 1, dem
PY
  # Bilinear fills around a lone void from its valid corners; the nearest cell leaves the road
  # samples inside both cells without a height: filled along the roads that meet there, reported.
  out="$RELIEF_TMP/spiked_nearest"
  check "spiked potrero nearest builds" run 0 "$out" build --osm "$potrero/sf-potrero.osm.gz" --dem "$spiked" \
    --out "$out" --quiet --outputs report --interp nearest
  check "spiked potrero nearest figures" python3 - "$out/report.json" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
assert r["elevation"]["vs_dem"]["rmse_m"] < 1.0 and r["gradient"]["max_percent"] <= 35.0, r["elevation"]
assert r["diagnostics"]["counts"].get("elevation.void", 0) >= 2, r["diagnostics"]["counts"]
assert r["elevation"]["void_samples"] >= 2, r["elevation"]
PY
fi

# cosim on Potrero's hills: relief's own random trips, 120 s at 20 Hz. Every vehicle on the
# scene (no wheel off every surface), SUMO's lane heights on the OpenDRIVE surface; on the roads
# the vehicles' heights within the mesh's 0.02 m of it (p99). In junctions the patch spans its
# outline and the connecting roads disagree where they overlap: measured and printed, not yet
# within 0.02 m (README, co-simulation).
if [ -d "$potrero" ]; then
  out="$RELIEF_TMP/potrero_cosim"
  check "potrero build with routes" run 0 "$out" build --osm "$potrero/sf-potrero.osm.gz" \
    --dem "$potrero/USGS_13_n38w123-subsection-small-potrero.tif" --out "$out" --quiet --outputs xodr,sumo,mesh \
    --mesh-formats glb --routes 200
  check "potrero cosim" run 0 "$out/cosim" cosim --sumocfg "$out/sf-potrero.sumocfg" --out "$out/cosim" --end 120 \
    --egos 5
  check "potrero cosim figures" python3 - "$out/cosim/cosim.json" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
print("cosim potrero: %d vehicles, %d placements; z vs OpenDRIVE on roads p99 %.4f max %.4f m, in junctions p99 %.4f "
      "max %.4f m; SUMO z max %.4f m; pitch vs slope p99 %.3f deg; wheels under %d; %.1fx real time" %
      (r["vehicles"], r["vehicle_steps"], r["z_error_on_roads_m"]["p99"], r["z_error_on_roads_m"]["max"],
       r["z_error_in_junctions_m"]["p99"], r["z_error_in_junctions_m"]["max"], r["sumo_z_error_m"]["max"],
       r["pitch_error_deg"]["p99"], r["wheels_under_road"], r["real_time_factor"]))
assert r["inputs"]["scene"].endswith("sf-potrero.glb"), r["inputs"]
assert r["vehicles"] >= 40 and r["unplaced_vehicle_steps"] == 0, r
assert r["sumo_z_error_m"]["max"] <= 0.05, r["sumo_z_error_m"]
assert r["z_error_on_roads_m"]["p99"] <= 0.03, r["z_error_on_roads_m"]
assert r["unmapped_vehicle_steps"] <= 0.05 * r["vehicle_steps"], r["unmapped_vehicle_steps"]
# The first 5 vehicles driven by the physics (Bullet) on the hills, their poses back to SUMO.
print("cosim potrero egos: %d, %d ego steps; sync error p50 %.3f p99 %.3f max %.3f m; %d resyncs" %
      (r["egos"], r["ego_steps"], r["sync_error_m"]["p50"], r["sync_error_m"]["p99"], r["sync_error_m"]["max"],
       r["resyncs"]))
assert r["egos"] == 5 and r["ego_steps"] >= 500, r["ego_steps"]
assert r["sync_error_m"]["p99"] <= 0.5, r["sync_error_m"]
assert r["resyncs"] == len(r["resync_log"]) or len(r["resync_log"]) == 100, r["resync_log"]
PY
  # The replay and the scene it carries: 0 errors in the Khronos glTF validator (npm; skipped,
  # and said so, where node/npm or the registry is missing).
  "$RELIEF_SOURCE_DIR/tools/gltf-validate.sh" "$out/cosim/cosim.glb" "$out/sf-potrero.glb" >"$RELIEF_TMP/gltf.log" 2>&1
  code=$?
  cat "$RELIEF_TMP/gltf.log"
  if [ "$code" -eq 77 ]; then
    echo "SKIP: glTF validator not available"
  else
    check "potrero replay valid glTF" test "$code" -eq 0
    check "potrero replay animated" grep -q '"animations":1' "$RELIEF_TMP/gltf.log"
  fi
fi

# Reproducible: two builds of Potrero with SOURCE_DATE_EPOCH set give byte-identical outputs
# (report.json apart from its stage timings; the terrain TIN once varied with the memory layout).
if [ -d "$potrero" ]; then
  for i in 1 2; do
    check "reproducible build $i" env SOURCE_DATE_EPOCH=1700000000 "$RELIEF" build --osm "$potrero/sf-potrero.osm.gz" \
      --dem "$potrero/USGS_13_n38w123-subsection-small-potrero.tif" --out "$RELIEF_TMP/repro$i" --quiet \
      --carla-package
  done
  check "reproducible outputs" python3 - "$RELIEF_TMP/repro1" "$RELIEF_TMP/repro2" <<'PY'
import filecmp, json, os, sys
a, b = sys.argv[1], sys.argv[2]
names = sorted(os.listdir(a))
assert names == sorted(os.listdir(b)), (names, os.listdir(b))
assert any(n.endswith(".xodr") for n in names) and any(n.endswith(".glb") for n in names), names
assert any(n.endswith(".carla.tar.gz") for n in names), names
def untimed(x):
    if isinstance(x, dict):
        return {k: untimed(v) for k, v in x.items() if k not in ("seconds", "timings_s")}
    return [untimed(v) for v in x] if isinstance(x, list) else x
# The 3D view's folder: file by file.
names = [n for n in names if n != "view"] + ["view/" + n for n in sorted(os.listdir(os.path.join(a, "view")))]
assert sorted(os.listdir(os.path.join(a, "view"))) == sorted(os.listdir(os.path.join(b, "view")))
assert "view/index.js" in names and "view.html" in names, names
for n in names:
    if n == "report.html":
        continue  # holds the timings table
    if n == "report.json":
        ra, rb = (untimed(json.load(open(os.path.join(d, n)))) for d in (a, b))
        assert ra == rb, n
        assert ra["created_utc"] == "2023-11-14T22:13:20Z", ra["created_utc"]
    else:
        assert filecmp.cmp(os.path.join(a, n), os.path.join(b, n), shallow=False), n
print("reproducible: %d files identical" % len(names))
PY
  export SOURCE_DATE_EPOCH=yesterday
  check "bad SOURCE_DATE_EPOCH" run 3 "$RELIEF_TMP/epoch" build --osm "$fix/hill.osm" --dem "$fix/hill_dem.asc" \
    --out "$RELIEF_TMP/epoch"
  unset SOURCE_DATE_EPOCH
  check "bad SOURCE_DATE_EPOCH message" stderr_has "SOURCE_DATE_EPOCH='yesterday'"
  check "bad SOURCE_DATE_EPOCH no outputs" no_outputs "$RELIEF_TMP/epoch"
fi

# relief tiles: Potrero in 250 m tiles, built two at a time, merged, and measured against a
# whole build in the plan's frame: the same roads and junctions, the plan to the bit, heights
# within 1 mm, the tiles' Road_Road one surface without self-intersections.
if [ -d "$potrero" ]; then
  t="$RELIEF_TMP/tiles"
  pdem="$potrero/USGS_13_n38w123-subsection-small-potrero.tif"
  # Planned with paths relative to another directory: the plan records its inputs absolute, so
  # the tiles build from here (as on a cluster's workers).
  check "tiles plan" bash -c "cd '$potrero' && '$RELIEF' tiles plan --osm sf-potrero.osm.gz \
    --dem '$(basename "$pdem")' --tile-size 250 --out '$t' --no-compare >'$RELIEF_TMP/stdout' 2>'$RELIEF_TMP/err'"
  check "tiles plan records absolute inputs" python3 - "$t/manifest.json" "$pdem" <<'PY'
import json, os, sys
m = json.load(open(sys.argv[1]))
assert all(os.path.isabs(i["path"]) and os.path.isfile(i["path"]) for i in m["inputs"]), m["inputs"]
dem = m["build_args"][m["build_args"].index("--dem") + 1]
assert os.path.samefile(dem, sys.argv[2]), dem
PY
  check "tiles merge before the build" run 3 "$t" tiles merge "$t"
  check "tiles merge before the build message" stderr_has "is not built: run relief tiles build"
  check "tiles unknown tile" run 2 "$t" tiles build "$t" --tile 99,99
  check "tiles build all" run 0 "$t" tiles build "$t" --all --jobs 2
  check "tiles up to date" run 0 "$t" tiles build "$t" --all
  check "tiles up to date says so" grep -q "skipped" "$RELIEF_TMP/err"
  origin=$(python3 -c "import json,sys; print('%.12f,%.12f' % tuple(json.load(open(sys.argv[1]))['frame']['centre_lon_lat']))" "$t/manifest.json")
  check "tiles whole build" run 0 "$t/whole" build --osm "$potrero/sf-potrero.osm.gz" --dem "$pdem" --origin "$origin" \
    --out "$t/whole" --outputs xodr,sumo,mesh,report --mesh-formats glb --no-compare --quiet
  check "tiles merge" run 0 "$t" tiles merge "$t" --compare "$t/whole/sf-potrero.xodr"
  check "tiles merged like the whole build" python3 - "$t" <<'PY'
import json, os, sys
t = sys.argv[1]
r = json.load(open(os.path.join(t, "merged", "report.json")))
m = json.load(open(os.path.join(t, "manifest.json")))
w = r["whole_build"]
print("tiles potrero: %d tiles, %d roads, %d junctions; against the whole build: %d of %d roads, plan %.2g m, "
      "height %.2g m; seams: %d shared vertices, %d welded (%.2g m); Road_Road %d triangles, %d self-intersections"
      % (len(r["tiles"]), r["opendrive"]["roads"], r["opendrive"]["junctions"], w["roads"] - w["unmatched"], w["roads"],
         w["max_xy_m"], w["max_z_m"], r["seams"]["shared_vertices"], r["seams"]["welded"], r["seams"]["max_dz_m"],
         r["joined"]["Road_Road"]["triangles"], r["joined"]["Road_Road"]["self_intersecting_pairs"]))
assert len(r["tiles"]) == len(m["tiles"]) >= 6, len(r["tiles"])
assert r["opendrive"]["links_unresolved"] == 0, r["opendrive"]
assert w["unmatched"] == 0 and r["opendrive"]["roads"] == w["roads"], w
assert w["max_xy_m"] <= 1e-9 and w["max_z_m"] <= 1e-3, w
assert r["seams"]["shared_vertices"] > 0 and r["seams"]["max_dz_m"] <= 1e-3, r["seams"]
assert r["joined"]["Road_Road"]["self_intersecting_pairs"] == 0, r["joined"]
# The region's SUMO network: the whole build's, with every lane on the merged surface.
s, ws = r["sumo"], json.load(open(os.path.join(t, "whole", "report.json")))["sumo"]
for key in ("edges", "lanes", "internal_lanes", "junctions", "traffic_lights", "connections"):
    assert s[key] == ws[key], (key, s[key], ws[key])
assert s["lanes_without_z"] == 0 and s["height_steps"] == 0 and s["z_max_m"] <= 0.05, s
assert os.path.isfile(os.path.join(t, "merged", "sf-potrero.sumo_mapping.json"))
# CARLA's large map: the grid's rectangle of FBX tiles (placeholders where a tile is empty).
c = r["carla"]
entries = c["entries"]
fbx = sorted(e for e in entries if e.endswith(".fbx"))
nx = 1 + max(int(e.rsplit("_", 2)[1]) for e in fbx)
ny = 1 + max(int(e.rsplit("_", 1)[1][:-4]) for e in fbx)
assert len(fbx) == nx * ny == c["tiles"] + len(c["placeholder_tiles"]), (len(fbx), nx, ny, c)
assert "sf-potrero/sf-potrero.xodr" in entries and c["tile_size_m"] == 250, c
ts = json.load(open(os.path.join(t, "merged", "tileset.json")))
assert ts["asset"]["version"] == "1.1" and len(ts["root"]["transform"]) == 16, ts["asset"]
kids = ts["root"]["children"]
assert len(kids) == r["scene_tiles"] > 0, len(kids)
# Each tile: its coarse level (refined by replacement) over the full tile (error 0).
lod = {x["tile"]: x for x in r["lod1"]["tiles"]}
for k in kids:
    assert k["refine"] == "REPLACE" and k["content"]["uri"].endswith("_lod1.glb"), k
    (full,) = k["children"]
    assert full["geometricError"] == 0 and full["content"]["uri"] == k["content"]["uri"][:-9] + ".glb", full
    x = lod[full["content"]["uri"][:-4]]
    assert k["geometricError"] == x["geometric_error_m"] > 0, (k["geometricError"], x)
    assert x["coarse_triangles"] < x["full_triangles"], x
    for c in (k, full):
        assert os.path.isfile(os.path.join(t, "merged", c["content"]["uri"])), c
        assert len(c["boundingVolume"]["box"]) == 12, c
assert ts["root"]["geometricError"] >= max(k["geometricError"] for k in kids)
# Potrero in 250 m tiles, 7.8 m cells: the coarse level has under a third of the triangles, errors
# of metres (10.0 m at 7081d85), not tens.
l = r["lod1"]
print("tiles potrero lod1: %d of %d triangles, geometric error up to %.2f m"
      % (l["coarse_triangles"], l["full_triangles"], l["max_geometric_error_m"]))
assert l["coarse_triangles"] * 3 < l["full_triangles"], l
assert 0.5 < l["max_geometric_error_m"] < 15.0, l
PY
  # The tileset against the 3D Tiles 1.1 schema, its boxes and errors (no network), then the
  # real validators (npm; skipped, and said so, where node/npm or the registry lacks them):
  # CesiumGS's 3D Tiles validator on the tileset, the Khronos glTF validator on every glb.
  check "tiles tileset schema and boxes" python3 "$RELIEF_SOURCE_DIR/tools/tileset_check.py" "$t/merged/tileset.json"
  "$RELIEF_SOURCE_DIR/tools/3d-tiles-validate.sh" "$t/merged/tileset.json" >"$RELIEF_TMP/3dtiles.log" 2>&1
  code=$?
  cat "$RELIEF_TMP/3dtiles.log"
  if [ "$code" -eq 77 ]; then
    echo "SKIP: 3D Tiles validator not available"
  else
    check "tiles tileset valid 3D Tiles" test "$code" -eq 0
  fi
  glbs=("$t"/merged/*.glb)
  check "tiles glb full and coarse" test "${#glbs[@]}" -ge 12
  "$RELIEF_SOURCE_DIR/tools/gltf-validate.sh" "${glbs[@]}" >"$RELIEF_TMP/gltf.log" 2>&1
  code=$?
  cat "$RELIEF_TMP/gltf.log"
  if [ "$code" -eq 77 ]; then
    echo "SKIP: glTF validator not available"
  else
    check "tiles glb valid glTF" test "$code" -eq 0
    check "tiles glb all validated" test "$(grep -c '"errors":0,' "$RELIEF_TMP/gltf.log")" -eq "${#glbs[@]}"
  fi
  if [ -f "$xsd" ] && command -v xmllint >/dev/null; then
    check "tiles merged xodr validates (1.7)" xmllint --noout --schema "$xsd" "$t/merged/sf-potrero.xodr"
  fi
fi

echo "$passed passed, $failures failed"
[ "$failures" -eq 0 ]
