"""The requests the front doors hand to the pipeline, parsed and checked once.

A front door (the command line, a sweep, a test, the studio) reads its user's input once into
a :class:`GenerateSpec` or a :class:`RunSpec`: values typed and unit-checked by the language's
literal entry point, adapter options checked against the adapter's signature, events and
clock advances told apart. Specs are plain data, so ``--seeds`` and ``sweep`` pickle them to
worker processes, which run them without reading any user text again.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

from lightrocks.app.adapter_factory import adapter_options
from lightrocks.app.robots import RobotChoice
from lightrocks.app.run import success_outcome
from lightrocks.app.script import Script
from lightrocks.app.values import Noise, parameters, parse_delay
from lightrocks.workbench.generators import GenerationError, load_generator, parse_options
from lightrocks.workbench.languages import language_for


@dataclass(frozen=True)
class GenerateSpec:
    """Generate ``target`` from the models (files or folders) found on ``search_path``."""

    models: tuple[Path, ...]
    search_path: tuple[Path, ...]
    target: str
    options: Mapping[str, Any] = field(default_factory=dict)
    """Every option the target declares, read (``workbench.generators.parse_options``)."""
    templates: Path | None = None


GENERATED_LANGUAGES = ("lightrocks", "domain")
"""The languages whose files the generators read: statecharts and their domain interfaces."""


def generate_spec(
    models: Sequence[Path],
    search_path: Sequence[Path],
    target: str,
    options: Mapping[str, str] | None = None,
    templates: Path | None = None,
) -> GenerateSpec:
    """A generation request; an unknown target, an option it does not declare or a bad value
    (an ``OptionError``), or a model file of a language the generators do not read (a UML/P
    ``.sc`` chart: convert it first), is a ``GenerationError`` before anything is checked."""
    read = parse_options(load_generator(target), options or {})
    for model in models:
        language = language_for(model.suffix) if model.is_file() else None
        if language is not None and language.name not in GENERATED_LANGUAGES:
            raise GenerationError(
                f"{model}: the generators read LightRocks statecharts (.lr) and domain files "
                f"(.lrd), not {language.name} ({model.suffix}); convert it first: "
                f"lightrocks convert {model} --to lr"
            )
    return GenerateSpec(tuple(models), tuple(search_path), target, read, templates)


@dataclass(frozen=True)
class RunSpec:
    """One run of the statechart in ``model``."""

    model: Path
    search_path: tuple[Path, ...]
    params: Mapping[str, Any] = field(default_factory=dict)
    """Attribute name of the generated class -> typed value in SI units."""
    adapter: str | None = None
    adapter_options: Mapping[str, Any] = field(default_factory=dict)
    """The options chosen for the adapter (noise, video, script, robot, …), checked against
    what it declares; the seed is given to it where it declares one."""
    seed: int = 0
    trace: Path | None = None
    events: tuple[str | float, ...] = ()
    """Events to send once the chart rests, and clock advances in seconds."""
    success: str | None = None
    """The outcome that counts as success, checked: the one chosen, else the chart's first
    end condition; ``None`` for a plain chart, which succeeds by resting without error."""
    robot: RobotChoice | None = None
    """The robot in the cell's robot slot, where the user chose one (``--robot``); the
    class of ``model`` is loaded for it, and the adapter simulates it."""

    def for_seed(self, seed: int) -> RunSpec:
        """The same run with another seed, tracing to ``run.seed3.jsonl`` where it traces."""
        return replace(self, seed=seed, trace=seed_trace(self.trace, seed))

    @property
    def header(self) -> dict[str, Any]:
        """The first record of a trace file: the model it ran, so that a replay can draw it,
        and the robot chosen for it."""
        header: dict[str, Any] = {
            "model": str(self.model.resolve()),
            "path": [str(p.resolve()) for p in self.search_path],
        }
        if self.robot is not None:
            header["robot"] = self.robot.name
        return header


def run_spec(
    cls: type,
    model: Path,
    search_path: Sequence[Path],
    params: Sequence[str] = (),
    adapter: str | None = None,
    *,
    seed: int = 0,
    noise: Noise = (0.0, 0.0),
    video: str | None = None,
    script: Script | None = None,
    trace: Path | None = None,
    events: Sequence[str] = (),
    success: str | None = None,
    robot: RobotChoice | None = None,
    robot_ip: str | None = None,
    confirm: bool = False,
) -> RunSpec:
    """A run of the loaded class ``cls`` of ``model`` from its user's words: ``name=value``
    parameters, ``+500ms`` clock advances among the events; a ``RunError`` says what is
    wrong before anything starts. With ``robot``, ``cls`` is the class loaded for it;
    ``robot_ip`` and ``confirm`` are for an adapter of a real arm (``franka``)."""
    robot_name = robot.name if robot is not None else None
    return RunSpec(
        model=model,
        search_path=tuple(search_path),
        params=parameters(cls, params),
        adapter=adapter,
        adapter_options=adapter_options(
            adapter,
            noise=noise,
            video=video,
            script=script,
            robot=robot_name,
            robot_ip=robot_ip,
            confirm=confirm or None,
        ),
        seed=seed,
        trace=trace,
        events=tuple(parse_delay(e) if e.startswith("+") else e for e in events),
        success=success_outcome(cls, success),
        robot=robot,
    )


def seed_trace(trace: Path | None, seed: int) -> Path | None:
    """``run.jsonl`` -> ``run.seed3.jsonl``: one trace per seed."""
    return None if trace is None else trace.with_name(f"{trace.stem}.seed{seed}{trace.suffix}")
