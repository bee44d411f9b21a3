"""A robot described by a URDF, which both simulators read.

MuJoCo reads the URDF with its own parser (``MjSpec``; fixed joints kept as bodies, visual
meshes dropped, mimic joints off), and what the LightRocks interface needs is added to that
spec: the sites ``tcp`` and ``ft``, a motor on every joint with the URDF's effort limit, the
wrist's force and torque sensors, joint damping and armature, the collision classes of
lwr.xml and one box for the hand, so that MuJoCo's contacts and the twin's (which push the
corners of the hand's and fingers' boxes) are one geometry. The spec is written as MJCF text
(adapters.mjcf_text) that scenes include. Pinocchio reads the URDF natively and gets the same
base placement, frames and armature.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from collections.abc import Callable
from dataclasses import dataclass
from functools import cache
from pathlib import Path

import mujoco
import numpy as np
import pinocchio as pin

from lightrocks.adapters.mjcf_text import mjcf_text
from lightrocks.adapters.robots.common import (
    ARM_DOF,
    FORCE_SENSOR,
    FT_SITE,
    TCP_SITE,
    TORQUE_SENSOR,
)
from lightrocks.adapters.robots.robot import Robot

CONTYPE, CONAFFINITY = 2, 1
"""As in lwr.xml: the robot touches the environment (contype 1) but never itself."""
FINGER_FRICTION = (1.2, 0.01, 0.0001)
FINGER_CONDIM = 4
"""As lwr.xml's finger pads: torsional friction, so that a closed grip does not twist."""


@dataclass(frozen=True)
class UrdfRobot(Robot):
    """A robot from a URDF; the fields say what the URDF lacks."""

    locate: Callable[[], Path]
    """Where the URDF is; raises ``RobotDataMissing`` when the package holding it is not
    installed."""
    base: tuple[float, float, float]
    """Position [m] of the root body in the world (the cell's floor)."""
    tcp: tuple[tuple[float, float, float], tuple[float, float, float, float]]
    """Position [m] and orientation (quaternion w, x, y, z) of the TCP in the hand's frame
    (``ft`` is at the hand's origin, in its axes)."""
    hand_box: tuple[tuple[float, float, float], tuple[float, float, float]]
    """Centre and half sizes [m] of the box, in the hand's frame, that replaces the hand's
    own collision geometry."""
    armature: tuple[float, ...]
    """Reflected rotor inertia [kg m² or kg] of every joint, arm then fingers."""
    damping: tuple[float, ...]
    """Viscous damping [Nm s/rad] of the arm joints (the fingers': ``finger_damping``)."""

    def __post_init__(self) -> None:
        super().__post_init__()
        if len(self.armature) != len(self.joints) or len(self.damping) != ARM_DOF:
            raise ValueError(f"robot {self.device_type}: armature per joint, damping per arm joint")

    def mjcf(self) -> bytes:
        return _mjcf(self)

    def model(self) -> pin.Model:
        """The URDF's model (mimic joints off) on the base placement, with the armature and
        the frames ``ft`` and ``tcp`` added."""
        model = pin.buildModelFromUrdf(str(self.locate()))
        base = pin.SE3(np.eye(3), np.array(self.base))
        for joint in range(1, model.njoints):
            if model.parents[joint] == 0:
                model.jointPlacements[joint] = base * model.jointPlacements[joint]
        for index in range(1, model.nframes):
            frame = model.frames[index]
            if frame.parentJoint == 0:
                frame.placement = base * frame.placement
                model.frames[index] = frame
        model.armature = np.array(self.armature)
        hand = model.getFrameId(self.hand, pin.BODY)
        on = model.frames[hand]
        (x, y, z), (w, *axis) = self.tcp
        tcp = pin.SE3(pin.Quaternion(w, *axis).toRotationMatrix(), np.array([x, y, z]))
        for name, placement in ((FT_SITE, pin.SE3.Identity()), (TCP_SITE, tcp)):
            frame = pin.Frame(name, on.parentJoint, hand, on.placement * placement, pin.OP_FRAME)
            model.addFrame(frame)
        return model

    def spec(self) -> mujoco.MjSpec:
        """MuJoCo's reading of the URDF with the LightRocks interface added."""
        spec = mujoco.MjSpec.from_string(_for_mujoco(self.locate()))
        spec.modelname = self.device_type.lower()
        spec.body(self.root).pos = self.base
        joints = [spec.joint(name) for name in self.joints]
        gripper_damping = (self.finger_damping,) * len(self.finger_joints)
        for joint, armature, damping in zip(
            joints, self.armature, (*self.damping, *gripper_damping), strict=True
        ):
            joint.armature, joint.damping = armature, [damping, 0.0, 0.0]
            spec.add_actuator(
                name=joint.name,
                target=joint.name,
                trntype=mujoco.mjtTrn.mjTRN_JOINT,
                ctrlrange=joint.actfrcrange,
            )
        for geom in spec.geoms:
            geom.contype, geom.conaffinity = CONTYPE, CONAFFINITY
        for finger in self.fingers:
            for geom in spec.body(finger).geoms:
                geom.friction, geom.condim = FINGER_FRICTION, FINGER_CONDIM
        hand = spec.body(self.hand)
        for geom in hand.geoms:  # shown, but the box below touches instead
            geom.contype = geom.conaffinity = 0
        centre, half = self.hand_box
        hand.add_geom(
            name=f"{self.hand}_box",
            type=mujoco.mjtGeom.mjGEOM_BOX,
            pos=centre,
            size=half,
            contype=CONTYPE,
            conaffinity=CONAFFINITY,
            rgba=[0, 0, 0, 0],
        )
        hand.add_site(name=FT_SITE, size=[0.01, 0, 0], rgba=[0, 0, 1, 1])
        position, orientation = self.tcp
        hand.add_site(
            name=TCP_SITE, pos=position, quat=orientation, size=[0.006, 0, 0], rgba=[1, 0, 0, 1]
        )
        sensors = mujoco.mjtSensor.mjSENS_FORCE, mujoco.mjtSensor.mjSENS_TORQUE
        for name, kind in zip((FORCE_SENSOR, TORQUE_SENSOR), sensors, strict=True):
            spec.add_sensor(
                name=name,
                type=kind,
                objtype=mujoco.mjtObj.mjOBJ_SITE,
                objname=FT_SITE,
            )
        return spec


@cache
def _mjcf(robot: UrdfRobot) -> bytes:
    return mjcf_text(robot.spec()).encode()


def _for_mujoco(urdf: Path) -> str:
    """The URDF as MuJoCo should read it: no visuals (MuJoCo reads no COLLADA), no mimic
    joints (the fingers are driven one by one), mesh files by absolute path, fixed joints
    kept as bodies (the hand and its TCP link stay)."""
    root = ET.parse(urdf).getroot()
    for parent in root.iter():
        for child in list(parent):
            if child.tag in ("visual", "mimic"):
                parent.remove(child)
    for mesh in root.iter("mesh"):
        mesh.set("filename", str(_resolve(urdf, mesh.get("filename", ""))))
    options = ET.SubElement(ET.SubElement(root, "mujoco"), "compiler")
    options.attrib.update(fusestatic="false", discardvisual="true", strippath="false")
    return ET.tostring(root, encoding="unicode")


def _resolve(urdf: Path, uri: str) -> Path:
    """A mesh URI of the URDF as a file: ``package://NAME/rest`` in the folder NAME that
    holds the URDF, anything else relative to the URDF's folder."""
    if uri.startswith("package://"):
        package, _, rest = uri.removeprefix("package://").partition("/")
        for folder in urdf.parents:
            if folder.name == package:
                return folder / rest
        raise ValueError(f"{urdf}: no folder {package!r} above it for {uri!r}")
    return urdf.parent / uri
