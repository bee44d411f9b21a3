"""Safe ranges at run time: every element of a scalar or vector value is held to its bound,
NaN is never safe, and the refusal names device, command, element and range."""

from __future__ import annotations

import numpy as np
import pytest

from lightrocks.runtime.safety import Bound, SafeRange, refusal

MM = 0.001
STIFFNESS = SafeRange(
    "robot",
    "moveCartesian",
    "stiffness",
    (Bound(0.0, 5000.0, "N/m"), Bound(0.0, 5000.0, "N/m"), Bound(0.0, 300.0, "Nm/rad")),
)
DEPTH = SafeRange("arm", "move", "x", (Bound(0.0, 50 * MM, "mm", MM),))
FORCE = SafeRange("arm", "move", "force", (Bound(None, 50.0, "N"),))


@pytest.mark.parametrize(
    ("safe", "value", "message"),
    [
        (DEPTH, 0.06, "arm.move(x) = 60 mm is outside its safe range 0 mm .. 50 mm"),
        (DEPTH, float("nan"), "arm.move(x) = nan mm is outside"),
        (DEPTH, np.float64(-0.001), "arm.move(x) = -1 mm"),
        (FORCE, 51, "arm.move(force) = 51 N is outside its safe range -inf .. 50 N"),
        (STIFFNESS, (1e9, 0.0, 0.0), "robot.moveCartesian(stiffness[0]) = 1e+09 N/m"),
        (STIFFNESS, np.array([1.0, 1.0, 301.0]), "(stiffness[2]) = 301 Nm/rad is outside"),
    ],
)
def test_an_unsafe_value_is_named(safe: SafeRange, value: object, message: str) -> None:
    assert message in safe.breach(value)


@pytest.mark.parametrize(
    ("safe", "value"),
    [(DEPTH, 0.05), (DEPTH, 0), (FORCE, -1e9), (STIFFNESS, [5000.0, 0.0, 300.0]), (DEPTH, "x")],
)
def test_a_safe_value_passes(safe: SafeRange, value: object) -> None:
    assert safe.breach(value) is None


def test_refusal_looks_at_the_ranged_arguments_only() -> None:
    ranges = {"x": DEPTH, "force": FORCE}
    assert refusal(ranges, {"x": 0.01, "goal": object()}) is None
    assert refusal(ranges, {"x": 0.01, "force": 80.0}).startswith("refused: arm.move(force)")
