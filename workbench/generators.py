"""The generator registry and the shared machinery of every target.

A generator is found through the ``lightrocks.generators`` entry points. It receives the
checked models and returns the files it wants written, as relative path to text; the
workbench writes them all or nothing. Templates are jinja2 files beside the generator; a
user's template folder is searched first, so one template can be replaced by name without
forking the generator (MontiCore's template path).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from functools import cache
from importlib.metadata import entry_points
from pathlib import Path
from typing import Protocol

import jinja2

from lightrocks.workbench.check import CheckContext
from lightrocks.workbench.files import write_tree


@dataclass
class GenerationRequest:
    """What to generate: the checked models, the files named by the user, and options."""

    context: CheckContext
    files: list[Path]
    options: Mapping[str, str] = field(default_factory=dict)
    templates: Path | None = None


class Generator(Protocol):
    name: str
    description: str

    def generate(self, request: GenerationRequest) -> dict[str, str | bytes]:
        """Files to write: relative path -> text, or bytes for pictures."""
        ...


class GenerationError(Exception):
    """A problem the user can fix (bad option, output folder not writable, …)."""


def generator_names() -> list[str]:
    return sorted(entry.name for entry in entry_points(group="lightrocks.generators"))


@cache
def load_generator(name: str) -> Generator:
    """The generator registered as ``name``; only that one is imported."""
    found = [e for e in entry_points(group="lightrocks.generators") if e.name == name]
    if not found:
        known = ", ".join(generator_names())
        raise GenerationError(f"unknown target '{name}'; known targets: {known}")
    try:
        return found[0].load()
    except (ImportError, AttributeError) as error:
        raise GenerationError(f"target '{name}' cannot be loaded: {error}") from None


def template_environment(builtin: Path, override: Path | None) -> jinja2.Environment:
    """Templates from ``override`` first, then the generator's own folder."""
    folders = [str(override)] if override is not None else []
    folders.append(str(builtin))
    return jinja2.Environment(
        loader=jinja2.FileSystemLoader(folders),
        undefined=jinja2.StrictUndefined,
        keep_trailing_newline=True,
        trim_blocks=True,
        lstrip_blocks=True,
        autoescape=False,
    )


def write_all(output: Path, files: Mapping[str, str | bytes]) -> list[Path]:
    """Write every file or none, even when the process is killed (see
    :func:`workbench.files.write_tree`)."""
    if output.exists() and not output.is_dir():
        raise GenerationError(f"output '{output}' is not a folder")
    try:
        return write_tree(output, files)
    except OSError as error:
        raise GenerationError(f"cannot write to '{output}': {error.strerror}") from None
