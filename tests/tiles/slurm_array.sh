#!/usr/bin/env bash
# relief tiles on a batch system without Dask: a Slurm job array, one array task per tile of
# the plan. An example (documentation, not run by the tests: `bash -n` checks it).
#
# DIR must be on a filesystem that every compute node sees at the same path, and relief must be
# installed there too (RELIEF below). Each task runs the per-tile command
#
#     relief tiles build DIR --tile X,Y
#
# which exits 0 (built, or already up to date: "skipped"), 4 (built, but a quality gate failed:
# still a finished tile) or anything else (failed: no DIR/tiles/X_Y/tile.json is left).
#
# The tiles are built in four phases (the manifest's "phase"): a tile holds the heights its
# neighbours of earlier phases fitted where their roads meet its own, so each phase's array waits
# for the one before (afterany: a failed tile is recorded by the tiles after it, not fatal).
# Submit:
#     relief tiles plan --osm REGION.osm.pbf --dem DEM.tif --tile-size 2000 --out /shared/region
#     dep=""
#     for phase in 0 1 2 3; do
#       N=$(/usr/bin/python3 -c 'import json,sys; print(sum(t["phase"] == int(sys.argv[2])
#             for t in json.load(open(sys.argv[1]))["tiles"]))' /shared/region/manifest.json $phase)
#       [[ $N -gt 0 ]] || continue
#       dep=$(sbatch --parsable ${dep:+--dependency=afterany:$dep} --array=0-$((N - 1))%200 \
#               --export=ALL,DIR=/shared/region,PHASE=$phase tests/tiles/slurm_array.sh)
#     done
# then merge once every array task has ended (whatever their exit; the merge names missing tiles):
#     sbatch --dependency=afterany:$dep --wrap 'relief tiles merge /shared/region'
# Failed tiles: submit their phase's array again (tiles already built are skipped in a fraction
# of a second; a tile whose neighbour was built since is built again), or build them on one
# machine with
#     relief tiles build /shared/region --all --jobs 8
#
#SBATCH --job-name=relief-tiles
#SBATCH --cpus-per-task=1
#SBATCH --mem=4G
#SBATCH --time=00:30:00
#SBATCH --requeue
#SBATCH --output=relief-tiles-%A_%a.log
set -euo pipefail

: "${DIR:?set DIR to the tiles folder (relief tiles plan --out DIR), e.g. sbatch --export=ALL,DIR=...}"
: "${SLURM_ARRAY_TASK_ID:?run this as a Slurm array job: sbatch --array=0-N ...}"
: "${PHASE:?set PHASE to the phase this array builds (0 to 3), e.g. sbatch --export=ALL,DIR=...,PHASE=0}"
RELIEF=${RELIEF:-relief}

# Array index -> tile X,Y: the manifest's tiles of this phase in their order.
TILE=$(/usr/bin/python3 -c '
import json, sys
tiles = [t for t in json.load(open(sys.argv[1] + "/manifest.json"))["tiles"] if t["phase"] == int(sys.argv[3])]
i = int(sys.argv[2])
if not 0 <= i < len(tiles):
    sys.exit("array index %d: phase %s has %d tiles (0..%d)" % (i, sys.argv[3], len(tiles), len(tiles) - 1))
print("%d,%d" % (tiles[i]["x"], tiles[i]["y"]))
' "$DIR" "$SLURM_ARRAY_TASK_ID" "$PHASE")

echo "relief-tiles: array task $SLURM_ARRAY_TASK_ID -> tile $TILE on $(hostname)"
rc=0
"$RELIEF" tiles build "$DIR" --tile "$TILE" || rc=$?
if [[ $rc -eq 4 ]]; then
  echo "relief-tiles: tile $TILE built, but a quality gate failed (see $DIR/tiles/${TILE/,/_}/tile.json)"
  exit 0  # a finished tile: the merge reports the gate
fi
exit "$rc"
