"""The generator registry and the shared machinery of every target.

A generator is found through the ``lightrocks.generators`` entry points. It receives the
checked models and returns the files it wants written, as relative path to text; the
workbench writes them all or nothing. Templates are jinja2 files beside the generator; a
user's template folder is searched first, so one template can be replaced by name without
forking the generator (MontiCore's template path).
"""

from __future__ import annotations

import traceback
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from functools import cache
from importlib.metadata import entry_points
from pathlib import Path
from typing import Any, Protocol

import jinja2

from lightrocks.metamodel import ast
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


def refuse_extensions(target: str, unit: Any) -> None:
    """Stop at the first node a language extension added, for a target that has no mapping
    for extension syntax: leaving it out would generate something the model does not say."""
    for node in ast.walk(unit):
        if ast.is_extension(node):
            raise GenerationError(
                f"{node.position}: the {target} target does not map '{type(node).__name__}', "
                "which a language extension adds"
            )


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


class TemplateProblem(GenerationError):
    """A template that cannot be read or rendered, named with its file and line."""


def run_generator(generator: Generator, request: GenerationRequest) -> dict[str, str | bytes]:
    """The generator's files; a template that fails is reported with its file and line."""
    try:
        return generator.generate(request)
    except jinja2.TemplateError as error:
        raise TemplateProblem(_template_problem(error)) from None


def _template_problem(error: jinja2.TemplateError) -> str:
    if isinstance(error, jinja2.TemplateSyntaxError):
        where = f"{error.filename or error.name}:{error.lineno}"
    elif isinstance(error, jinja2.TemplateNotFound):
        return f"template '{error.name}' not found"
    else:  # jinja shows the template lines as frames of the traceback
        frames = traceback.extract_tb(error.__traceback__)
        lines = [f"{f.filename}:{f.lineno}" for f in frames if f.filename.endswith(".jinja")]
        where = lines[-1] if lines else "template"
    return f"template {where}: {error.message}"


def template_environment(
    builtin: Path, override: Path | None, additions: Sequence[Path] = ()
) -> jinja2.Environment:
    """Templates from ``override`` first, then the generator's own folder, then the folders
    of language extensions (templates for their elements). The generator's own templates
    are also reachable as ``builtin/<name>``, so an override can ``{% extends %}`` the
    template it replaces and change one block instead of copying it."""
    folders = [str(override)] if override is not None else []
    folders.append(str(builtin))
    folders += [str(folder) for folder in additions]
    loader = jinja2.ChoiceLoader(
        [
            jinja2.FileSystemLoader(folders),
            jinja2.PrefixLoader({"builtin": jinja2.FileSystemLoader(str(builtin))}),
        ]
    )
    return jinja2.Environment(
        loader=loader,
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
