"""The Python module against the C++ figures: relief.run_cosim runs 10 steps of SUMO on a relief
build of the hill fixture, and relief.Surface.place gives back every placement it wrote."""
import csv
import json
import math
import os
import subprocess
from pathlib import Path

import pytest

import relief

RELIEF = os.environ["RELIEF"]
SOURCE = Path(os.environ["RELIEF_SOURCE_DIR"])
TMP = Path(os.environ["RELIEF_TMP"])


@pytest.fixture(scope="module")
def hill():
    out = TMP / "hill"
    subprocess.run([RELIEF, "build", "--osm", str(SOURCE / "fixtures/hill/hill.osm"),
                    "--dem", str(SOURCE / "fixtures/hill/hill_dem.asc"), "--out", str(out), "--quiet",
                    "--outputs", "xodr,sumo,mesh", "--mesh-formats", "glb", "--routes", "20"], check=True)
    return out


def test_wheel_base_follows_the_vehicle_size():
    assert relief.wheel_base(5.0, 1.8) == pytest.approx((3.0, 1.4))
    with pytest.raises(ValueError):
        relief.wheel_base(0.0, 1.8)


def test_a_missing_scene_is_an_os_error(tmp_path):
    with pytest.raises(OSError, match="nowhere.glb"):
        relief.Surface(tmp_path / "nowhere.glb")


def test_ten_steps_from_python_match_the_surface_query(hill):
    figures = relief.run_cosim(hill / "hill.sumocfg", hill / "cosim", end=0.5, replay_period=0.0)
    assert figures["steps"] == 10
    assert figures["vehicles"] >= 1
    assert figures["unplaced_vehicle_steps"] == 0
    report = json.loads((hill / "cosim" / "cosim.json").read_text())
    assert report["steps"] == 10 and report["vehicle_steps"] == figures["vehicle_steps"]
    assert not (hill / "cosim" / "cosim.glb").exists()

    surface = relief.Surface(hill / "hill.glb")
    assert surface.triangles > 1000
    rows = list(csv.DictReader(open(hill / "cosim" / "hill.trajectories.csv")))
    assert len(rows) == figures["vehicle_steps"]
    for row in rows:
        x, y, z = float(row["x_m"]), float(row["y_m"]), float(row["z_m"])
        heading = math.radians(90.0 - float(row["angle_deg"]))
        # SUMO's default vehicle type: 5 m x 1.8 m.
        pose = surface.place(x, y, heading, length=5.0, width=1.8, z_hint=z,
                             pitch_hint=math.radians(float(row["pitch_deg"])))
        assert pose is not None
        assert pose.z == pytest.approx(z, abs=2e-3)
        assert math.degrees(pose.pitch) == pytest.approx(float(row["pitch_deg"]), abs=2e-3)
        assert math.degrees(pose.roll) == pytest.approx(float(row["roll_deg"]), abs=2e-3)
        assert surface.nearest(x, y, z) == pytest.approx(z, abs=0.05)
    # Far from every surface: nothing.
    assert surface.height(1e6, 1e6) is None
    assert surface.place(1e6, 1e6, 0.0) is None


def test_egos_from_python_are_driven_and_measured(hill):
    figures = relief.run_cosim(hill / "hill.sumocfg", hill / "cosim_egos", end=20.0, replay_period=0.0,
                               ego_count=2)
    assert figures["egos"] == 2
    assert figures["ego_steps"] > 100
    assert figures["sync_error_m"]["p50"] < 0.1
    assert figures["resync_m"] == 0.5
    with pytest.raises(ValueError):
        relief.run_cosim(hill / "hill.sumocfg", hill / "cosim_bad", end=1.0, resync=0.0)


def test_sumo_over_traci_from_python_runs_the_same_traffic(hill):
    in_process = relief.run_cosim(hill / "hill.sumocfg", hill / "cosim_in", end=5.0, replay_period=0.0,
                                  ego_count=1)
    launched = relief.run_cosim(hill / "hill.sumocfg", hill / "cosim_traci", end=5.0, replay_period=0.0,
                                ego_count=1, sumo="sumo")
    assert in_process["sumo"] == "in process (libsumo)"
    assert launched["sumo"] == "TraCI to sumo (launched)"
    for key in ("steps", "vehicles", "vehicle_steps", "ego_steps", "resyncs"):
        assert launched[key] == in_process[key], key
    assert launched["z_error_m"]["max"] == pytest.approx(in_process["z_error_m"]["max"], abs=1e-9)
    assert launched["sync_error_m"]["p99"] == pytest.approx(in_process["sync_error_m"]["p99"], abs=1e-9)
