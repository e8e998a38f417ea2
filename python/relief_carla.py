"""relief for users of CARLA's own SUMO bridge (CARLA's Co-Simulation/Sumo).

The bridge places every SUMO vehicle in CARLA with BridgeHelper.get_carla_transform
(sumo_integration/bridge_helper.py): SUMO's front-bumper position moved back half a length,
SUMO's z, SUMO's slope as pitch and no roll. On sloped roads and decks the vehicles float or
sink and pitch from lane point to lane point. install() replaces that one static method with
one that sets the vehicle on relief's surface (the .glb of the relief build whose NAME.net.xml
and NAME.xodr CARLA and SUMO run on) by its four wheel contacts: z, pitch and roll from the
surface, plan position and heading as the bridge computes them. Where the surface has no place
for the vehicle (off the built area) the bridge's own transform is kept.

In run_synchronization.py, after `from sumo_integration.bridge_helper import BridgeHelper`:

    import relief, relief_carla
    relief_carla.install(BridgeHelper, relief.Surface("out/NAME.glb"))

Conventions (as the bridge's): SUMO's frame is relief's local frame (relief writes the net with
netOffset = -origin); CARLA's is left-handed (y flipped), yaw = SUMO angle - 90, pitch nose up;
roll is written right side down positive, Unreal's sense (not checked against CARLA here: CARLA
is not installable on this machine).
"""
import math

import relief


def carla_pose(surface, location, rotation, extent, offset=(0.0, 0.0)):
    """The CARLA (x, y, z, pitch, yaw, roll) of a SUMO vehicle (front bumper `location`, SUMO
    `rotation` in degrees, CARLA bounding-box `extent`) set on `surface`, or None."""
    yaw = 90.0 - rotation.yaw  # counter-clockwise from east, degrees
    heading = math.radians(yaw)
    pitch_hint = math.radians(rotation.pitch)
    x = location.x - math.cos(heading) * extent.x
    y = location.y - math.sin(heading) * extent.x
    z_hint = location.z - math.sin(pitch_hint) * extent.x
    pose = surface.place(x, y, heading, length=2.0 * extent.x, width=2.0 * extent.y, z_hint=z_hint,
                         pitch_hint=pitch_hint)
    if pose is None:
        return None
    return (x - offset[0], -(y - offset[1]), pose.z, math.degrees(pose.pitch), rotation.yaw - 90.0,
            math.degrees(pose.roll))


def install(bridge_helper, surface):
    """Replaces bridge_helper.get_carla_transform (CARLA's BridgeHelper) by relief's placement;
    returns the original, which stays the fallback."""
    original = bridge_helper.get_carla_transform

    def get_carla_transform(in_sumo_transform, extent):
        import carla  # pylint: disable=import-error,import-outside-toplevel
        pose = carla_pose(surface, in_sumo_transform.location, in_sumo_transform.rotation, extent,
                          bridge_helper.offset)
        if pose is None:
            return original(in_sumo_transform, extent)
        x, y, z, pitch, yaw, roll = pose
        return carla.Transform(carla.Location(x, y, z), carla.Rotation(pitch, yaw, roll))

    bridge_helper.get_carla_transform = staticmethod(get_carla_transform)
    return original


__all__ = ["carla_pose", "install", "relief"]
