"""Adapters by name, from the ``lightrocks.adapters`` entry points, with the options they
declare."""

from __future__ import annotations

from collections.abc import Callable
from importlib.metadata import entry_points
from typing import Any

from lightrocks.app.errors import RunError, SceneError
from lightrocks.runtime.contract import AdapterOption


def adapter_factory(name: str) -> Callable[..., Any]:
    found = {e.name: e for e in entry_points(group="lightrocks.adapters")}
    if name not in found:
        raise RunError(f"unknown adapter '{name}'; known: {', '.join(sorted(found))}")
    return found[name].load()


def declared_options(name: str) -> dict[str, AdapterOption]:
    """The options the adapter ``name`` declares (``OPTIONS``), by keyword."""
    return {option.name: option for option in getattr(adapter_factory(name), "OPTIONS", ())}


_WITHOUT = {
    "perception_noise": "has no perception noise",
    "video": "cannot record a video",
    "outcomes": "cannot follow a script (the dry run can)",
    "robot": "has no choice of robot; --robot needs one that has: {able}",
}
"""How an adapter without the option is named, where the option has a word of its own."""


def adapter_options(name: str | None, **chosen: Any) -> dict[str, Any]:
    """Keyword arguments for the adapter ``name``: the options its user chose (``None``,
    ``False`` or no noise: not chosen), each checked against what the adapter declares, so
    that nothing it cannot honour (noise, a video, another robot) is silently dropped. A
    script gives ``outcomes`` and ``sensors``."""
    script = chosen.pop("script", None)
    if script is not None:
        chosen.update(script)
    noise = chosen.pop("noise", None)
    if noise is not None and any(noise):
        chosen["perception_noise"] = noise
    chosen = {k: v for k, v in chosen.items() if v is not None and v is not False}
    if name is None:
        if chosen.keys() - {"robot"}:
            raise RunError("perception noise, video and script need an adapter (--adapter)")
        if chosen:
            raise RunError("--robot chooses the robot an adapter simulates: give --adapter")
        return {}
    declared = declared_options(name)
    for key, value in chosen.items():
        option = declared.get(key)
        if option is None:
            able = ", ".join(_taking(key)) or "none"
            without = _WITHOUT.get(key, "has no option {key}; adapters that have it: {able}")
            raise RunError(f"adapter '{name}' " + without.format(key=key, able=able))
        if not isinstance(value, option.kind):
            raise RunError(f"adapter '{name}': {key} must be {_kind(option.kind)}, got {value!r}")
    return chosen


def _kind(kind: type | tuple[type, ...]) -> str:
    kinds = kind if isinstance(kind, tuple) else (kind,)
    return " or ".join(k.__name__ for k in kinds)


def _taking(option: str) -> list[str]:
    """The registered adapters that declare ``option``."""
    names = sorted(e.name for e in entry_points(group="lightrocks.adapters"))
    return [n for n in names if option in declared_options(n)]


def adapter_for(name: str, scene: str | None, seed: int = 0, **options: Any) -> Any:
    """The adapter on the model's scene; adapters reject an unknown scene with ValueError
    (the user's mistake) and a scene that does not load with ``SceneFault`` (its author's).
    The seed only matters to adapters that draw random numbers (they declare it)."""
    factory = adapter_factory(name)
    if "seed" in declared_options(name):
        options = {"seed": seed, **options}
    try:
        return factory(scene=scene, **options)
    except ValueError as error:
        raise RunError(f"adapter '{name}': {error}") from None
    except Exception as error:
        from lightrocks.adapters.scene import SceneFault  # loads MuJoCo: not for the dry run

        if isinstance(error, SceneFault):
            raise SceneError(str(error)) from None
        raise


def scene_of(cls: type) -> str | None:
    return cls.CELL.SCENE if cls.CELL is not None else None
