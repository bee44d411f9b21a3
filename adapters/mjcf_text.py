"""A robot's ``mujoco.MjSpec`` as MJCF text at full precision, for scenes to include.

MuJoCo's own ``MjSpec.to_xml`` writes numbers with six significant digits (``0.707107`` for
cos 45°, ``4.97068`` for a mass of 4.970684 kg) and a ``<compiler angle="radian">`` that would
change the including scene's angle unit, so the MuJoCo robot would differ from Pinocchio's
reading of the same source by ~1e-6. This writer covers what a robot's spec holds — meshes,
bodies with their inertials, hinge and slide joints, geoms, sites, motors, force and torque
sensors — and writes every number as Python's shortest round-trip form, hinge ranges in
degrees (MJCF's default unit) and no ``<compiler>``; it refuses anything else in the spec, so
that nothing is dropped in silence.
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from xml.sax.saxutils import quoteattr

import mujoco
import numpy as np

_JOINT_TYPES = {mujoco.mjtJoint.mjJNT_HINGE: "hinge", mujoco.mjtJoint.mjJNT_SLIDE: "slide"}
_GEOM_TYPES = {
    mujoco.mjtGeom.mjGEOM_BOX: "box",
    mujoco.mjtGeom.mjGEOM_MESH: "mesh",
    mujoco.mjtGeom.mjGEOM_CAPSULE: "capsule",
    mujoco.mjtGeom.mjGEOM_CYLINDER: "cylinder",
    mujoco.mjtGeom.mjGEOM_SPHERE: "sphere",
}
_SENSOR_TYPES = {mujoco.mjtSensor.mjSENS_FORCE: "force", mujoco.mjtSensor.mjSENS_TORQUE: "torque"}


def mjcf_text(spec: mujoco.MjSpec) -> str:
    """The MJCF of ``spec`` (a robot: one tree of bodies under the world)."""
    _refuse_the_rest(spec)
    lines = [f"<mujoco model={quoteattr(spec.modelname)}>", "  <asset>"]
    lines += [f"    <mesh{_attrs(name=m.name, file=m.file)}/>" for m in spec.meshes]
    lines += ["  </asset>", "  <worldbody>"]
    for body in spec.worldbody.bodies:
        lines += _body(body, spec.compiler.degree, "    ")
    lines += ["  </worldbody>", "  <actuator>"]
    for a in spec.actuators:
        motor = a.gaintype == mujoco.mjtGain.mjGAIN_FIXED and a.gainprm[0] == 1.0
        motor = motor and a.biastype == mujoco.mjtBias.mjBIAS_NONE and a.gear[0] == 1.0
        if a.trntype != mujoco.mjtTrn.mjTRN_JOINT or not motor:
            raise ValueError(f"actuator {a.name!r} is not a motor on a joint")
        lines.append(f"    <motor{_attrs(name=a.name, joint=a.target, ctrlrange=a.ctrlrange)}/>")
    lines += ["  </actuator>", "  <sensor>"]
    for s in spec.sensors:
        if s.type not in _SENSOR_TYPES:
            raise ValueError(f"sensor {s.name!r} is neither a force nor a torque sensor")
        lines.append(f"    <{_SENSOR_TYPES[s.type]}{_attrs(name=s.name, site=s.objname)}/>")
    lines += ["  </sensor>", "</mujoco>", ""]
    return "\n".join(lines)


def _refuse_the_rest(spec: mujoco.MjSpec) -> None:
    for kind in ("equalities", "tendons", "excludes", "pairs", "flexes", "skins", "cameras"):
        if getattr(spec, kind):
            raise ValueError(f"the robot's spec has {kind}, which this writer does not write")


def _body(body: mujoco.MjsBody, degree: bool, indent: str) -> list[str]:
    lines = [f"{indent}<body{_attrs(name=body.name, pos=body.pos, quat=body.quat)}>"]
    inner = indent + "  "
    if body.explicitinertial and body.mass > 0:
        inertia = {"fullinertia": body.fullinertia}  # in the body's axes: no quat
        if not np.isnan(body.fullinertia[0]) and np.any(body.iquat != [1.0, 0.0, 0.0, 0.0]):
            raise ValueError(f"body {body.name!r}: a full inertia in rotated axes")
        if np.isnan(body.fullinertia[0]):
            inertia = {"quat": body.iquat, "diaginertia": body.inertia}
        attrs = _attrs(pos=body.ipos, mass=body.mass, **inertia)
        lines.append(f"{inner}<inertial{attrs}/>")
    for j in body.joints:
        span = None
        if j.range[0] < j.range[1]:
            hinge = j.type == mujoco.mjtJoint.mjJNT_HINGE
            span = np.degrees(j.range) if hinge and not degree else j.range
        attrs = _attrs(
            name=j.name,
            type=_JOINT_TYPES[j.type],
            pos=j.pos,
            axis=j.axis,
            range=span,
            damping=j.damping[0],
            armature=j.armature,
        )
        lines.append(f"{inner}<joint{attrs}/>")
    for g in body.geoms:
        attrs = _attrs(
            name=g.name or None,
            type=_GEOM_TYPES[g.type],
            pos=g.pos,
            quat=g.quat,
            size=None if g.meshname else g.size,
            mesh=g.meshname or None,
            contype=g.contype,
            conaffinity=g.conaffinity,
            condim=g.condim,
            friction=g.friction,
            rgba=g.rgba,
            group=g.group,
        )
        lines.append(f"{inner}<geom{attrs}/>")
    for s in body.sites:
        attrs = _attrs(name=s.name, pos=s.pos, quat=s.quat, size=s.size, rgba=s.rgba)
        lines.append(f"{inner}<site{attrs}/>")
    for child in body.bodies:
        lines += _body(child, degree, inner)
    lines.append(f"{indent}</body>")
    return lines


def _attrs(**values: object) -> str:
    """`` name="value"`` for every value that is not None, numbers at full precision."""
    return "".join(f" {key}={quoteattr(_text(v))}" for key, v in values.items() if v is not None)


def _text(value: object) -> str:
    if isinstance(value, str):
        return value
    if isinstance(value, Iterable):
        return " ".join(_number(float(x)) for x in value)
    return _number(float(value))  # type: ignore[arg-type]


def _number(x: float) -> str:
    if not math.isfinite(x):
        raise ValueError(f"not a finite number: {x}")
    return repr(int(x) if x.is_integer() and abs(x) < 1e15 else x)
