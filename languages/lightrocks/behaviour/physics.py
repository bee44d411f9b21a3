"""Physics of an elemental action from the robot's own model: its kinematics, joint ranges
and joint torque limits, read with Pinocchio from the robot a ``lightrocks.robots`` entry
point registers for the device type (the LWR for ``robot : LWR``).

Goals are computed where the action's parameters (at the values the loaded models give
them), constants and the robot's start pose (its ready pose, where every adapter starts)
determine them; a goal written relative to the arm (``robot.tcp * …``) starts from the start
pose, with the tool pointing as it points there. Each finding is a warning with its numbers
and a fix:

- LR0630: a goal that the arm reaches, from its start pose, with a joint within MARGIN of
  its limit or beyond (a later turn of the tool has no room left that way);
- LR0631: a motion whose direction contradicts an end condition: it waits for a travel
  against the motion, or (moving in the tool frame) for a force the contact cannot have;
- LR0632: an offset in the tool frame (``robot.tcp * transl(…)``) whose end conditions only
  hold if it is read in the base frame (``transl(…) * robot.tcp``): the tool's axis is
  flipped against the base's at the start;
- LR0633: a force (torque) threshold above what the commanded stiffness builds over the
  whole travel (stiffness × travel), so a contact cannot reach it;
- LR0634: a stiffness of zero along an axis the motion moves along or an end condition
  reads a force of: no spring pulls there;
- LR0635: a force (torque) threshold beyond what the joints' torque limits let the arm exert
  at the tool (a unit mixed up: kN for N).
"""

from __future__ import annotations

import itertools
import math
import xml.etree.ElementTree as ElementTree
from collections.abc import Iterator
from dataclasses import dataclass, fields, is_dataclass
from functools import cache
from importlib.metadata import entry_points
from typing import Any

import z3

from lightrocks.languages.domain.types import DeviceT
from lightrocks.languages.lightrocks.behaviour.conditions import Finding, start_of
from lightrocks.languages.lightrocks.behaviour.judge import Judge
from lightrocks.languages.lightrocks.behaviour.parameters import ParameterValues
from lightrocks.languages.lightrocks.behaviour.plausibility import (
    AXES,
    Plausibility,
    dimension_of,
    file_of,
    goal_argument,
    is_number,
    product_factors,
    reads_device,
)
from lightrocks.languages.lightrocks.behaviour.scope import Scope
from lightrocks.languages.lightrocks.behaviour.terms import Terms, exact
from lightrocks.languages.lightrocks.behaviour.variables import unit_of
from lightrocks.languages.lightrocks.model import Component
from lightrocks.languages.lightrocks.typing import Typing
from lightrocks.metamodel import ast
from lightrocks.metamodel.units import FORCE, TORQUE, lookup

MARGIN = math.radians(5.0)
"""A joint this close to its limit at a goal has no room left for what follows."""
INSTANCES = 16
"""At most this many combinations of parameter values are judged; more: the defaults."""
ZERO_STIFFNESS = 1e-6
"""A stiffness below this fraction of the device's typical one is none."""
SINGLE_AXIS = 0.99
"""A motion is along one axis when that axis carries this share of its direction."""
Instance = dict[str, float]


# -- the robot's model ----------------------------------------------------------------------


@dataclass
class Arm:
    """The kinematics of one registered robot, loaded once (module cache)."""

    model: Any
    data: Any
    tcp: int
    joints: tuple[str, ...]
    slots: tuple[int, ...]  # where each arm joint is in q
    ready: Any  # the start configuration, every joint of the model
    effort: tuple[float, ...]  # torque limit per arm joint (inf: not declared)

    def pose(self, q: Any) -> Any:
        import pinocchio as pin

        pin.framesForwardKinematics(self.model, self.data, q)
        return self.data.oMf[self.tcp].copy()

    @property
    def start(self) -> Any:
        return self.pose(self.ready)

    def solve(self, goal: Any) -> Any | None:
        """The configuration the arm reaches at ``goal`` from its start pose, following the
        damped least-squares gradient in small steps (as a compliant arm follows its set
        point), joint limits not enforced; None where it does not get there."""
        import numpy as np
        import pinocchio as pin

        q = self.ready.copy()
        slots = list(self.slots)
        for _ in range(300):
            pin.framesForwardKinematics(self.model, self.data, q)
            error = pin.log6(self.data.oMf[self.tcp].actInv(goal)).vector
            if np.linalg.norm(error[:3]) < 1e-4 and np.linalg.norm(error[3:]) < 1e-3:
                return q
            jacobian = pin.computeFrameJacobian(self.model, self.data, q, self.tcp, pin.LOCAL)
            jacobian = jacobian[:, slots]
            step = jacobian.T @ np.linalg.solve(jacobian @ jacobian.T + 1e-4 * np.eye(6), error)
            largest = np.abs(step).max()
            q[slots] += step * min(1.0, 0.05 / largest) if largest > 0 else 0.0
        return None

    def strength(self, q: Any, axis: int, angular: bool) -> tuple[float, str]:
        """The largest force (torque) the joints' torque limits let the arm exert at its
        tool along (about) world axis ``axis`` in configuration ``q``, and the joint that
        limits it."""
        import pinocchio as pin

        pin.computeJointJacobians(self.model, self.data, q)
        pin.updateFramePlacements(self.model, self.data)
        jacobian = pin.getFrameJacobian(self.model, self.data, self.tcp, pin.LOCAL_WORLD_ALIGNED)
        row = jacobian[3 + axis if angular else axis]
        best, joint = math.inf, ""
        for name, slot, limit in zip(self.joints, self.slots, self.effort, strict=True):
            lever = abs(float(row[slot]))
            if lever > 1e-9 and limit / lever < best:
                best, joint = limit / lever, name
        return best, joint


@cache
def arm(device_type: str) -> Arm | None:
    """The registered robot of a device type (the one named like it first), or None when
    none is registered or its model files are not installed."""
    candidates = sorted(
        entry_points(group="lightrocks.robots"),
        key=lambda e: (e.name != device_type.lower(), e.name),
    )
    for entry in candidates:
        try:
            robot = entry.load()
            if getattr(robot, "device_type", None) != device_type:
                continue
            return _arm(robot)
        except Exception:  # a robot whose data is missing is no model to judge with
            continue
    return None


def _arm(robot: Any) -> Arm:
    import pinocchio as pin

    model = robot.model()
    q = pin.neutral(model)
    slots = tuple(model.joints[model.getJointId(n)].idx_q for n in robot.arm_joints)
    for slot, angle in zip(slots, robot.ready, strict=True):
        q[slot] = angle
    declared = _motor_limits(robot)
    effort = []
    for name in robot.arm_joints:
        joint = model.joints[model.getJointId(name)]
        limit = float(model.effortLimit[joint.idx_v])
        effort.append(limit if math.isfinite(limit) and limit > 0 else declared.get(name, math.inf))
    return Arm(
        model,
        model.createData(),
        model.getFrameId("tcp"),
        tuple(robot.arm_joints),
        slots,
        q,
        tuple(effort),
    )


def _motor_limits(robot: Any) -> dict[str, float]:
    """Joint torque limits an MJCF declares on its motors (``ctrlrange`` × ``gear``), for a
    model whose Pinocchio reading has none."""
    try:
        root = ElementTree.fromstring(robot.mjcf())
    except Exception:
        return {}
    found = {}
    for motor in root.iter("motor"):
        joint, ctrl = motor.get("joint"), motor.get("ctrlrange")
        if not joint or not ctrl:
            continue
        try:
            low, high = (float(v) for v in ctrl.split())
            gear = float((motor.get("gear") or "1").split()[0])
        except ValueError:
            continue
        found[joint] = max(abs(low), abs(high)) * abs(gear)
    return found


# -- goals ----------------------------------------------------------------------------------


@dataclass
class Goal:
    """A goal pose computed on one instance: ``placed`` when its position is known too,
    ``relative`` when it is written relative to where the arm is."""

    pose: Any
    placed: bool
    relative: bool


class Frames:
    """Frame and number expressions evaluated for one instance of an action; the arm's
    own sensors read its start pose."""

    def __init__(self, device: str, start: Any, values: Instance) -> None:
        self.device = device
        self.start = start
        self.values = values

    def goal(self, expression: ast.Expression) -> Goal | None:
        import pinocchio as pin

        pose, placed, relative = pin.SE3.Identity(), True, False
        for factor in product_factors(expression):
            if reads_device(factor, self.device):
                part, known = self.start, True
                relative = True
            else:
                found = self._factor(factor)
                if found is None:
                    return None
                part, known = found
            pose, placed = pose * part, placed and known
        return Goal(pose, placed, relative)

    def _factor(self, factor: ast.Expression) -> tuple[Any, bool] | None:
        import numpy as np
        import pinocchio as pin

        name = factor.function.name if _named_call(factor) else ""
        values = [self.number(a.value) for a in factor.arguments] if name else []
        if name == "transl" and len(values) == 3:
            known = all(v is not None for v in values)
            offset = np.array([v if v is not None else 0.0 for v in values])
            return pin.SE3(np.eye(3), offset), known
        if name in ("rotX", "rotY", "rotZ") and len(values) == 1 and values[0] is not None:
            axis = np.zeros(3)
            axis["XYZ".index(name[3])] = 1.0
            return pin.SE3(pin.exp3(axis * values[0]), np.zeros(3)), True
        return None

    def number(self, expression: ast.Expression) -> float | None:
        """A number in SI, or None where it is not known on this instance."""
        match expression:
            case ast.Quantity(value=value):
                return float(value)
            case ast.Name(name=name):
                return self.values.get(name)
            case ast.Member(target=ast.Member(target=ast.Name(name=d)), name=axis) if (
                d == self.device and axis in AXES
            ):
                return float(self.start.translation[AXES.index(axis)])
            case ast.Unary(operator=sign, operand=operand):
                inner = self.number(operand)
                return None if inner is None else (-inner if sign == "-" else inner)
            case ast.Binary(operator=op, left=left, right=right) if op in "+-*/":
                a, b = self.number(left), self.number(right)
                if a is None or b is None or (op == "/" and b == 0):
                    return None
                return {"+": a + b, "-": a - b, "*": a * b}.get(op, a / b if b else 0.0)
            case ast.Call(function=ast.Name(name=fn), arguments=arguments) if fn in (
                "abs",
                "min",
                "max",
            ):
                parts = [self.number(a.value) for a in arguments]
                if not parts or any(p is None for p in parts):
                    return None
                return abs(parts[0]) if fn == "abs" else (min if fn == "min" else max)(parts)
        return None


def _named_call(expression: ast.Expression) -> bool:
    return isinstance(expression, ast.Call) and isinstance(expression.function, ast.Name)


# -- the judgements ---------------------------------------------------------------------------


class Physics:
    """The findings on one action component written in its own file."""

    def __init__(self, typing: Typing, values: ParameterValues, component: Component) -> None:
        self.typing = typing
        self.values = values
        self.component = component
        self.plausibility = Plausibility(typing, component)
        self.seen: set[tuple[str, ast.Position]] = set()
        self._translated: dict[int, tuple[ast.Condition, Terms, z3.BoolRef]] | None = None

    def translated(self) -> list[tuple[ast.Condition, Terms, z3.BoolRef]]:
        """The end conditions written in the action's file, each translated once."""
        if self._translated is None:
            self._translated = {}
            for condition in self.component.region.end_conditions:
                if condition.expression is None:
                    continue
                if condition.position.file != file_of(self.component):
                    continue
                terms = Terms(self.plausibility.scope)
                term = terms.condition(condition.expression)
                self._translated[id(condition)] = (condition, terms, term)
        return list(self._translated.values())

    def findings(self) -> Iterator[Finding]:
        call = self.plausibility.call()
        if call is None:
            return
        device, command, arguments = call
        declared = Scope(self.typing, self.component.region).env.get(device)
        if not isinstance(declared, DeviceT) or declared.device is None:
            return
        goal = goal_argument(command, arguments)
        if goal is None or not self._judged(goal):
            return
        robot = arm(declared.device.name)
        if robot is None:
            return
        start = robot.start
        for instance in self._instances(goal, arguments):
            frames = Frames(device, start, instance)
            computed = frames.goal(goal)
            if computed is None:
                continue
            judged = Judgement(self, robot, device, command, arguments, goal, instance, computed)
            for finding in judged.findings():
                key = (finding.code, finding.position)
                if key not in self.seen:
                    self.seen.add(key)
                    yield finding

    def _judged(self, goal: ast.Expression) -> bool:
        """Only goals built of transl, rotX/Y/Z and the arm's pose can be computed; asking
        for nothing else keeps the robot's model unloaded where it cannot help."""
        for factor in product_factors(goal):
            if not (_named_call(factor) or isinstance(factor, ast.Member)):
                return False
        return True

    def _instances(
        self, goal: ast.Expression, arguments: dict[str, ast.Expression]
    ) -> list[Instance]:
        """Combinations of the values the action's numeric parameters take in the loaded
        models (those the goal, the arguments and the end conditions read); a parameter
        that may take any value stays out (unknown)."""
        read = set(_names(goal))
        for value in arguments.values():
            read |= _names(value)
        for condition in self.component.region.end_conditions:
            read |= _names(condition.expression)
        choices: list[tuple[str, list[float]]] = []
        for name in sorted(read & set(self.component.region.parameters)):
            taken = self.values.of(self.component, name)
            numbers = sorted(float(v) for v in taken or () if is_number(v))
            if taken is not None and numbers and len(numbers) == len(taken):
                choices.append((name, numbers))
        count = math.prod(len(c[1]) for c in choices)
        if count > INSTANCES:
            defaults = {}
            for name, _ in choices:
                value = self.plausibility.value(self.component.region.parameters[name].default)
                if is_number(value):
                    defaults[name] = float(value)
            return [defaults]
        names = [c[0] for c in choices]
        return [
            dict(zip(names, combo, strict=True))
            for combo in itertools.product(*(c[1] for c in choices))
        ]


class Judgement:
    """The judgements of one action on one instance of its parameters."""

    def __init__(
        self,
        physics: Physics,
        robot: Arm,
        device: str,
        command: ast.Command,
        arguments: dict[str, ast.Expression],
        goal: ast.Expression,
        instance: Instance,
        computed: Goal,
    ) -> None:
        self.physics = physics
        self.plausibility = physics.plausibility
        self.robot = robot
        self.device = device
        self.command = command
        self.arguments = arguments
        self.goal = goal
        self.instance = instance
        self.computed = computed
        self.start = robot.start
        self.configuration: Any | None = None

    def findings(self) -> Iterator[Finding]:
        yield from self._joint_limits()
        motion = self._motion()
        if motion is not None:
            yield from self._directions(*motion)
            yield from self._spring(*motion)
        yield from self._zero_stiffness(motion)
        yield from self._strength()

    def _bound(self) -> str:
        shown = ", ".join(f"{n} = {_show(n, v, self.physics)}" for n, v in self.instance.items())
        return f" (with {shown})" if shown else ""

    # -- LR0630 -----------------------------------------------------------------------------

    def _joint_limits(self) -> Iterator[Finding]:
        if self.computed.relative:
            return  # where a relative goal starts is wherever the action before left the arm
        target = self.computed.pose.copy()
        if not self.computed.placed:
            target.translation = self.start.translation
        q = self.robot.solve(target)
        if q is None:
            return
        self.configuration = q
        model = self.robot.model
        for name, slot in zip(self.robot.joints, self.robot.slots, strict=True):
            angle, low, high = (
                float(q[slot]),
                model.lowerPositionLimit[slot],
                model.upperPositionLimit[slot],
            )
            limit = high if high - angle < angle - low else low
            room = min(high - angle, angle - low)
            if room >= MARGIN:
                continue
            where = "at the start pose's position" if not self.computed.placed else ""
            state = (
                f"{math.degrees(-room):.1f} deg beyond its limit"
                if room < 0
                else f"{math.degrees(room):.1f} deg from its limit"
            )
            yield Finding(
                "LR0630",
                start_of(self.goal),
                f"at this goal{self._bound()} joint {name} of the {self.device} ends at "
                f"{math.degrees(angle):.1f} deg, {state} {math.degrees(limit):g} deg "
                f"(inverse kinematics from the start pose{', ' + where if where else ''}): "
                "a later turn of the tool has no room that way",
                "turn the goal about the tool axis (rotZ) so that the joint keeps room, or "
                "start from a pose nearer to it",
            )
            return

    # -- motions along one axis -------------------------------------------------------------

    def _motion(self) -> tuple[int, int, float, bool, int] | None:
        """A relative goal that moves along one world axis (or turns about one):
        (axis, sign, distance [m or rad], angular, task axis)."""
        import numpy as np
        import pinocchio as pin

        if not (self.computed.relative and self.computed.placed) or self._task_turned():
            return None
        moved = self.computed.pose.translation - self.start.translation
        turned = self.start.rotation @ pin.log3(self.start.rotation.T @ self.computed.pose.rotation)
        linear, angular = float(np.linalg.norm(moved)), float(np.linalg.norm(turned))
        if (linear > 1e-9) == (angular > 1e-9) or (linear > 1e-9 and angular > 1e-6):
            return None
        vector, length = (moved, linear) if linear > 1e-9 else (turned, angular)
        direction = vector / length
        axis = int(np.argmax(np.abs(direction)))
        if abs(direction[axis]) < SINGLE_AXIS:
            return None
        tool = self.start.rotation.T @ np.eye(3)[axis]
        task = int(np.argmax(np.abs(tool)))
        if abs(tool[task]) < SINGLE_AXIS:
            return None
        return axis, 1 if direction[axis] > 0 else -1, length, angular > 1e-9, task

    def _task_turned(self) -> bool:
        """A task frame written with a rotation (its stiffness axes are then not the tool's)."""
        for parameter in self.command.parameters:
            written = self.arguments.get(parameter.name)
            if parameter.name == "task" and written is not None:
                return any(
                    _named_call(f) and f.function.name.startswith("rot")
                    for f in product_factors(written)
                )
        return False

    # -- LR0631, LR0632 ---------------------------------------------------------------------

    def _directions(
        self, axis: int, moving: int, length: float, angular: bool, task: int
    ) -> Iterator[Finding]:
        if angular:
            return
        tool = self._tool_offset()
        way = f"{'+' if moving > 0 else '-'}{AXES[axis]}"
        given = self._facts
        contradicted = list(self.plausibility.against(self.device, axis, moving, given))
        if tool is None:
            for condition, path, kind in contradicted:
                if kind == "travel":
                    yield self._against(condition, path, way, length, "")
            return
        meant = tool if tool != (axis, moving) else None
        pointing = self._pointing(tool[0])
        for condition, path, _ in contradicted:
            base = () if meant is None else self.plausibility.against(self.device, *meant, given)
            if meant is not None and not any(c is condition for c, _, _ in base):
                yield Finding(
                    "LR0632",
                    start_of(self.goal),
                    f"this offset is in the tool frame, whose {AXES[tool[0]]} axis points along "
                    f"{pointing} of the base at the start pose: it moves the arm {way} by "
                    f"{length * 1000:g} mm{self._bound()}, yet end condition "
                    f"'{condition.name}' needs {path} as if it moved "
                    f"{'+' if meant[1] > 0 else '-'}{AXES[meant[0]]}",
                    f"write the offset in the base frame: transl(...) * {self.device}.tcp",
                )
            else:
                yield self._against(condition, path, way, length, " (in the tool frame)")

    def _against(
        self, condition: ast.Condition, path: str, way: str, length: float, frame: str
    ) -> Finding:
        return Finding(
            "LR0631",
            start_of(condition.expression),
            f"end condition '{condition.name}' needs {path} against the motion: the arm "
            f"moves {way}{frame} by {length * 1000:g} mm{self._bound()}, so it cannot hold "
            "on the way",
            "mind the direction of the goal or the sign of the condition",
        )

    def _tool_offset(self) -> tuple[int, int] | None:
        """The tool axis and sign of a goal offset written after the arm's pose
        (``robot.tcp * transl(…)``), or None for one written in the base frame."""
        factors = product_factors(self.goal)
        anchor = next(i for i, f in enumerate(factors) if reads_device(f, self.device))
        frames = Frames(self.device, self.start, self.instance)
        offset = [
            frames.number(a.value)
            for f in factors[anchor + 1 :]
            if _named_call(f) and f.function.name == "transl"
            for a in f.arguments
        ]
        if len(offset) != 3 or any(v is None for v in offset):
            return None
        moved = [i for i, v in enumerate(offset) if v]
        if len(moved) != 1:
            return None
        return moved[0], 1 if offset[moved[0]] > 0 else -1

    def _pointing(self, tool_axis: int) -> str:
        """The base axis (with its sign) a tool axis points along at the start pose."""
        column = self.start.rotation[:, tool_axis]
        world = max(range(3), key=lambda i: abs(column[i]))
        return f"{'+' if column[world] > 0 else '-'}{AXES[world]}"

    # -- LR0633 -----------------------------------------------------------------------------

    def _spring(
        self, axis: int, moving: int, length: float, angular: bool, task: int
    ) -> Iterator[Finding]:
        stiffness = self._stiffness()
        if stiffness is None:
            return
        index = 3 + task if angular else task
        k = stiffness[index][0]
        if k <= 0:
            return
        push = k * length
        dimension = TORQUE if angular else FORCE
        unit, per, travel = (
            ("Nm", "Nm/rad", f"{math.degrees(length):g} deg")
            if angular
            else ("N", "N/m", f"{length * 1000:g} mm")
        )
        for condition, path in self._exceeding(axis, dimension, push):
            yield Finding(
                "LR0633",
                start_of(condition.expression),
                f"end condition '{condition.name}' needs |{path}| above {push:g} {unit}, "
                f"the most the commanded stiffness builds over the whole motion: "
                f"{k:g} {per} × {travel}{self._bound()}",
                "raise the stiffness along that axis or the travel, or lower the threshold",
            )

    # -- LR0634 -----------------------------------------------------------------------------

    def _zero_stiffness(self, motion: tuple | None) -> Iterator[Finding]:
        stiffness = self._stiffness()
        if stiffness is None:
            return
        import numpy as np

        needed: dict[int, str] = {}
        if motion is not None:
            axis, _, _, angular, task = motion
            needed[3 + task if angular else task] = (
                f"the motion {'turns about' if angular else 'moves along'} {AXES[axis]}"
            )
        rotation = self.start.rotation if self.computed.relative else self.computed.pose.rotation
        for condition, path, dimension in self._axis_readings():
            world = AXES.index(path[-1])
            tool = rotation.T @ np.eye(3)[world]
            task = int(np.argmax(np.abs(tool)))
            if abs(tool[task]) >= SINGLE_AXIS:
                index = 3 + task if dimension == TORQUE else task
                needed.setdefault(index, f"end condition '{condition.name}' reads {path}")
        for index, why in sorted(needed.items()):
            k, typical, where = stiffness[index]
            if typical and abs(k) <= ZERO_STIFFNESS * abs(typical):
                name = ("x", "y", "z", "rx", "ry", "rz")[index]
                yield Finding(
                    "LR0634",
                    where,
                    f"the stiffness along {name} (element {index}) is {k:g}, yet {why}: no "
                    "spring pulls the arm there, so it neither moves nor pushes along it",
                    f"give it a stiffness (the device's typical is {typical:g} in SI)",
                )

    # -- LR0635 -----------------------------------------------------------------------------

    def _strength(self) -> Iterator[Finding]:
        configurations = [self.robot.ready]
        if self.configuration is not None:
            configurations.append(self.configuration)
        for condition, path, dimension in self._axis_readings():
            angular = dimension == TORQUE
            axis = AXES.index(path[-1])
            most = [self.robot.strength(q, axis, angular) for q in configurations]
            best, joint = max(most)
            if not math.isfinite(best):
                continue
            for exceeded, _ in self._exceeding(axis, dimension, best, only=condition):
                unit = "Nm" if angular else "N"
                slot = self.robot.joints.index(joint)
                yield Finding(
                    "LR0635",
                    self._threshold_origin(exceeded),
                    f"end condition '{exceeded.name}' needs |{path}| above {best:.0f} {unit}, "
                    f"the most the {self.device}'s joint torque limits let it exert "
                    f"{'about' if angular else 'along'} {AXES[axis]} (joint {joint} at "
                    f"{self.robot.effort[slot]:g} Nm){self._bound()}: it can never be reached",
                    "check the unit of the threshold (N or kN, Nm or Nmm) or lower it",
                )

    def _threshold_origin(self, condition: ast.Condition) -> ast.Position:
        """The parameter default a condition's threshold comes from when nothing binds it
        otherwise (the mistake is written there), else the condition."""
        region = self.physics.component.region
        read = _names(condition.expression) & set(region.parameters)
        if len(read) == 1:
            name = next(iter(read))
            default = region.parameters[name].default
            value = self.plausibility.value(default)
            taken = self.physics.values.of(self.physics.component, name)
            if default is not None and is_number(value) and taken == frozenset({value}):
                return start_of(default)
        return start_of(condition.expression)

    # -- shared -----------------------------------------------------------------------------

    def _facts(self, terms: Terms) -> list[z3.BoolRef]:
        """The action's parameters read so far, each at its value on this instance."""
        facts = []
        for path, (variable, constant) in terms.read.items():
            if variable.kind == "parameter" and path in self.instance:
                facts.append(constant == exact(self.instance[path]))
        return facts

    def _axis_readings(self) -> Iterator[tuple[ast.Condition, str, object]]:
        """Force and torque sensor leaves of the arm along a world axis that each end
        condition reads."""
        for condition, terms, _ in self.physics.translated():
            for path, (variable, _) in terms.read.items():
                dimension = dimension_of(variable.unit)
                if (
                    variable.kind == "sensor"
                    and path.startswith(f"{self.device}.")
                    and path[-2:] in (".x", ".y", ".z")
                    and dimension in (FORCE, TORQUE)
                ):
                    yield condition, path, dimension

    def _exceeding(
        self, axis: int, dimension: object, bound: float, only: ast.Condition | None = None
    ) -> Iterator[tuple[ast.Condition, str]]:
        """End conditions that need a force (torque) along world ``axis`` above ``bound``:
        they cannot hold while it stays within, and can without that bound. A condition
        whose numbers are all below the bound is not asked (it cannot need more)."""
        for condition, terms, term in self.physics.translated():
            if only is not None and condition is not only:
                continue
            if _magnitude(condition.expression, self.device, self.instance)[0] < bound:
                continue
            judge = Judge(terms)
            facts = self._facts(terms)
            for path, (variable, constant) in list(terms.read.items()):
                if (
                    variable.kind != "sensor"
                    or not path.startswith(f"{self.device}.")
                    or not path.endswith(f".{AXES[axis]}")
                    or dimension_of(variable.unit) != dimension
                ):
                    continue
                within = z3.And(constant <= exact(bound), constant >= -exact(bound))
                if judge.never(term, within, *facts) and not judge.never(term, *facts):
                    yield condition, path
                    break

    def _stiffness(self) -> list[tuple[float, float, ast.Position]] | None:
        """The commanded Cartesian stiffness per axis: (value, the device's typical, where
        it is written)."""
        for parameter in self.command.parameters:
            if "Stiffness" not in parameter.type:
                continue
            typical = self.plausibility.value(parameter.default)
            written = self.arguments.get(parameter.name)
            value = self.plausibility.value(written) if written is not None else typical
            if not (isinstance(value, tuple) and isinstance(typical, tuple)):
                continue
            if len(value) != 6 or len(typical) != 6:
                continue
            places = _element_positions(written, self.plausibility, parameter)
            return [(float(v), float(t), p) for v, t, p in zip(value, typical, places, strict=True)]
        return None


def _element_positions(
    written: ast.Expression | None, plausibility: Plausibility, parameter: ast.Parameter
) -> list[ast.Position]:
    """Where each element of a vector is written: in the argument, the default of the
    action's parameter it passes on, or the device's default."""
    source = written
    if isinstance(written, ast.Name) and written.name in plausibility.defaults:
        source = plausibility.defaults[written.name]
    if source is None:
        source = parameter.default
    if isinstance(source, ast.VectorLiteral) and len(source.elements) == 6:
        return [start_of(e) for e in source.elements]
    where = start_of(source)
    return [where] * 6


def _magnitude(
    expression: ast.Expression | None, device: str, instance: Instance
) -> tuple[float, bool]:
    """An upper bound of the size of every number a condition compares a reading of the
    arm with, and whether the expression reads the arm: a reading scaled by a factor, or a
    value not known here, has no bound (inf)."""
    match expression:
        case ast.Quantity(value=value):
            return abs(float(value)), False
        case ast.BooleanLiteral():
            return 0.0, False
        case ast.Name(name=name):
            return (abs(instance[name]), False) if name in instance else (math.inf, False)
        case ast.Member():
            chain = expression
            while isinstance(chain, ast.Member):
                chain = chain.target
            if isinstance(chain, ast.Name) and chain.name == device:
                return 0.0, True
            return math.inf, False
        case ast.Unary(operand=operand):
            return _magnitude(operand, device, instance)
        case ast.Binary(operator=op, left=left, right=right):
            (a, ra), (b, rb) = (
                _magnitude(left, device, instance),
                _magnitude(right, device, instance),
            )
            if op in ("+", "-"):
                return a + b, ra or rb
            if op == "*" and not (ra or rb):
                return a * b, False
            if op in ("*", "/", "%"):
                return math.inf, ra or rb
            return max(a, b), ra or rb
        case ast.Call(function=ast.Name(name=fn), arguments=arguments) if fn in (
            "abs",
            "min",
            "max",
        ):
            parts = [_magnitude(a.value, device, instance) for a in arguments]
            return max((p[0] for p in parts), default=0.0), any(p[1] for p in parts)
    return math.inf, False


def _names(expression: object) -> set[str]:
    """The plain names an expression reads (not the members of a path)."""
    if isinstance(expression, ast.Name):
        return {expression.name}
    if isinstance(expression, tuple):
        return set().union(*(_names(e) for e in expression)) if expression else set()
    if isinstance(expression, ast.Member):
        return _names(expression.target) if not isinstance(expression.target, ast.Name) else set()
    if is_dataclass(expression) and not isinstance(expression, ast.Position):
        found: set[str] = set()
        for f in fields(expression):
            if f.name != "position":
                found |= _names(getattr(expression, f.name))
        return found
    return set()


def _show(name: str, value: float, physics: Physics) -> str:
    """A parameter's value in the unit its default is written in."""
    unit = unit_of(physics.component.region.parameters[name].default)
    return f"{value / lookup(unit).factor:g} {unit}" if unit else f"{value:g}"
