"""The drop-in for CARLA's SUMO bridge, against a stand-in `carla` module (CARLA cannot be
installed here) and a stand-in BridgeHelper with the bridge's signature and offset."""
import math
import os
import subprocess
import sys
import types
from pathlib import Path

import pytest

import relief
import relief_carla

RELIEF = os.environ["RELIEF"]
SOURCE = Path(os.environ["RELIEF_SOURCE_DIR"])
TMP = Path(os.environ["RELIEF_TMP"])


class Vec:
    def __init__(self, x=0.0, y=0.0, z=0.0):
        self.x, self.y, self.z = x, y, z


class Rot:
    def __init__(self, pitch=0.0, yaw=0.0, roll=0.0):
        self.pitch, self.yaw, self.roll = pitch, yaw, roll


class Transform:
    def __init__(self, location, rotation):
        self.location, self.rotation = location, rotation


@pytest.fixture(scope="module")
def surface():
    out = TMP / "ramp"
    subprocess.run([RELIEF, "build", "--osm", str(SOURCE / "fixtures/hill/hill.osm"),
                    "--dem", str(SOURCE / "fixtures/hill/hill_dem.asc"), "--out", str(out), "--quiet",
                    "--outputs", "mesh", "--mesh-formats", "glb", "--no-terrain"], check=True)
    return relief.Surface(out / "hill.glb")


@pytest.fixture()
def fake_carla(monkeypatch):
    module = types.ModuleType("carla")
    module.Location, module.Rotation, module.Transform = Vec, Rot, Transform
    monkeypatch.setitem(sys.modules, "carla", module)
    return module


def test_install_replaces_the_bridge_transform_with_the_surface_pose(surface, fake_carla):
    class BridgeHelper:
        offset = (5.0, -3.0)
        calls = []

        @staticmethod
        def get_carla_transform(in_sumo_transform, extent):
            BridgeHelper.calls.append(in_sumo_transform)
            return "the bridge's own"

    original = relief_carla.install(BridgeHelper, surface)
    assert original(None, None) == "the bridge's own"
    BridgeHelper.calls.clear()
    # A road point of the hill: the surface under a vehicle heading north (SUMO angle 0).
    x, y = None, None
    for gx in range(-300, 300, 7):
        for gy in range(-300, 300, 7):
            if surface.place(gx, gy, math.pi / 2, length=4.0, width=1.8, z_hint=0.0, max_gap=1e9) is not None:
                x, y = gx, gy
                break
        if x is not None:
            break
    assert x is not None
    z = surface.height(x, y)
    extent = Vec(2.0, 0.9, 0.8)
    front = Vec(x, y + extent.x, z)  # SUMO's front bumper, heading north
    out = BridgeHelper.get_carla_transform(Transform(front, Rot(0.0, 0.0, 0.0)), extent)
    expected = surface.place(x, y, math.pi / 2, length=4.0, width=1.8, z_hint=z)
    assert out.location.x == pytest.approx(x - 5.0)
    assert out.location.y == pytest.approx(-(y + 3.0))
    assert out.location.z == pytest.approx(expected.z)
    assert out.rotation.pitch == pytest.approx(math.degrees(expected.pitch))
    assert out.rotation.roll == pytest.approx(math.degrees(expected.roll))
    assert out.rotation.yaw == pytest.approx(-90.0)
    assert not BridgeHelper.calls
    # Off the built area the bridge's own transform stays.
    assert BridgeHelper.get_carla_transform(Transform(Vec(1e6, 1e6, 0.0), Rot()), extent) == "the bridge's own"
    assert len(BridgeHelper.calls) == 1
