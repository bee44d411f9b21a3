"""The frame type and its functions, shared by every IEC 61131-3 rendering (ST and PLCopen).

A frame is a position (x y z) and the rows of a rotation matrix (xx xy xz, yx yy yz,
zx zy zz); ``FRAME_MUL`` composes two frames, ``TRANSL`` and ``ROT_*`` build them.
"""

from __future__ import annotations

from dataclasses import dataclass

AXES = ("x", "y", "z")
ROTATION = tuple(f"{row}{column}" for row in AXES for column in AXES)
FRAME_FIELDS: tuple[tuple[str, str], ...] = tuple((a, "") for a in AXES) + tuple(
    (r, "1.0" if r[0] == r[1] else "") for r in ROTATION
)


@dataclass(frozen=True)
class Function:
    name: str
    inputs: tuple[tuple[str, str], ...]
    body: tuple[str, ...]
    returns: str = "Frame"


def _product() -> tuple[str, ...]:
    lines = [
        f"FRAME_MUL.{p} := a.{p} + " + " + ".join(f"a.{p}{q} * b.{q}" for q in AXES) + ";"
        for p in AXES
    ]
    lines += [
        f"FRAME_MUL.{r}{c} := " + " + ".join(f"a.{r}{k} * b.{k}{c}" for k in AXES) + ";"
        for r in AXES
        for c in AXES
    ]
    return tuple(lines)


def _rotation(axis: str) -> Function:
    a, b = [other for other in AXES if other != axis]
    f = f"ROT_{axis.upper()}"
    upper, lower = ("-", "") if axis != "y" else ("", "-")
    return Function(
        f,
        (("angle", "REAL"),),
        (
            f"{f}.{axis}{axis} := 1.0;",
            f"{f}.{a}{a} := COS(angle); {f}.{a}{b} := {upper}SIN(angle);",
            f"{f}.{b}{a} := {lower}SIN(angle); {f}.{b}{b} := COS(angle);",
        ),
    )


FUNCTIONS: tuple[Function, ...] = (
    Function("FRAME_MUL", (("a", "Frame"), ("b", "Frame")), _product()),
    Function(
        "TRANSL",
        tuple((a, "REAL") for a in AXES),
        (
            "TRANSL.x := x; TRANSL.y := y; TRANSL.z := z;",
            "TRANSL.xx := 1.0; TRANSL.yy := 1.0; TRANSL.zz := 1.0;",
        ),
    ),
    *(_rotation(a) for a in AXES),
)
