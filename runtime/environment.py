"""The environment model: named scene objects with a pose and declared attributes.

Guards read it and exit actions (μ) update it; it is the robot program's belief about the
scene, separate from the sensor values an adapter reports.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from lightrocks.runtime.frames import Frame


class SceneObject:
    """One object of the cell; attributes are plain Python attributes (``screw.depth``)."""

    pose: Frame

    def __init__(self, name: str, attributes: Mapping[str, Any]) -> None:
        self.__dict__["_lightrocks_name"] = name
        self.pose = Frame.Identity()
        for attribute, value in attributes.items():
            setattr(self, attribute, value)

    def __getattr__(self, attribute: str) -> Any:
        raise AttributeError(f"scene object {object_name(self)!r} has no attribute {attribute!r}")

    def __repr__(self) -> str:
        return f"SceneObject({object_name(self)!r})"


def object_name(obj: SceneObject) -> str:
    """The name an adapter knows the object by (kept out of the attribute namespace)."""
    return obj.__dict__["_lightrocks_name"]


class Environment:
    """The scene graph: every object of the cell as an attribute (``env.screw``)."""

    def __init__(self, objects: Mapping[str, Mapping[str, Any]]) -> None:
        for name, attributes in objects.items():
            setattr(self, name, SceneObject(name, attributes))

    def objects(self) -> dict[str, SceneObject]:
        return {n: o for n, o in vars(self).items() if isinstance(o, SceneObject)}
