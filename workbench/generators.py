"""The generator registry and the shared machinery of every target.

A generator is found through the ``lightrocks.generators`` entry points. It receives the
checked models and returns the files it wants written, as relative path to text; the
workbench writes them all or nothing. It declares the options it takes (:class:`Option`),
which a front door reads once from the user's ``NAME=VALUE`` words (:func:`parse_options`)
and ``lightrocks list generators`` shows. Templates are jinja2 files beside the generator; a
user's template folder is searched first, so one template can be replaced by name without
forking the generator (MontiCore's template path).
"""

from __future__ import annotations

import traceback
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from functools import cache
from importlib.metadata import entry_points
from pathlib import Path
from typing import Any, Protocol

import jinja2

from lightrocks.metamodel import ast
from lightrocks.workbench.check import CheckContext
from lightrocks.workbench.files import write_tree


class GenerationError(Exception):
    """A problem the user can fix (bad option, output folder not writable, …)."""


class OptionError(GenerationError):
    """An option the target does not declare, or a value its declaration refuses."""


@dataclass(frozen=True)
class Option:
    """An option a generator takes (``--option NAME=VALUE``): its name, its type as the user
    reads it (``kind``), its default and what it does. ``read`` turns the user's text into
    the value, or raises ``ValueError`` with the rest of the message (`` is not …``)."""

    name: str
    kind: str
    default: Any
    doc: str
    read: Callable[[str], Any]

    def value(self, given: Any = None) -> Any:
        """The value of this option: the default when not ``given``, read when given as
        text, else as given (a value already read)."""
        if given is None:
            return self.default
        if not isinstance(given, str):
            return given
        try:
            return self.read(given)
        except ValueError as problem:
            raise OptionError(f"option {self.name}='{given}'{problem}") from None


def whole_number(name: str, default: int, doc: str, minimum: int = 0) -> Option:
    """An option whose value is a whole number ``>= minimum``."""
    bound = ">= 0" if minimum == 0 else f"> {minimum - 1}"

    def read(text: str) -> int:
        if not (text.isascii() and text.isdigit()) or int(text) < minimum:
            raise ValueError(f" is not a whole number {bound}")
        return int(text)

    return Option(name, f"whole number {bound}", default, doc, read)


def one_of(name: str, choices: Sequence[str], doc: str) -> Option:
    """An option that is off (``""``, its default) or one of ``choices``."""

    def read(text: str) -> str:
        if text and text not in choices:
            if len(choices) == 1:
                raise ValueError(f": the only value is '{choices[0]}'")
            raise ValueError(f": choose one of {', '.join(choices)}")
        return text

    return Option(name, "|".join(choices), "", doc, read)


@dataclass
class GenerationRequest:
    """What to generate: the checked models, the files named by the user, and options (by
    name: as :func:`parse_options` read them, or text)."""

    context: CheckContext
    files: list[Path]
    options: Mapping[str, Any] = field(default_factory=dict)
    templates: Path | None = None

    def value(self, option: Option) -> Any:
        """The value of ``option`` in this request (its default where not given)."""
        return option.value(self.options.get(option.name))


class Generator(Protocol):
    name: str
    description: str
    options: Sequence[Option]

    def generate(self, request: GenerationRequest) -> dict[str, str | bytes]:
        """Files to write: relative path -> text, or bytes for pictures."""
        ...


def refuse_extensions(target: str, unit: Any) -> None:
    """Stop at the first node a language extension added, for a target that has no mapping
    for extension syntax: leaving it out would generate something the model does not say."""
    for node in ast.walk(unit):
        if ast.is_extension(node):
            raise GenerationError(
                f"{node.position}: the {target} target does not map '{type(node).__name__}', "
                "which a language extension adds"
            )


def declared_options(generator: Generator) -> tuple[Option, ...]:
    """The options ``generator`` declares (none, for one that declares nothing)."""
    return tuple(getattr(generator, "options", ()))


def parse_options(generator: Generator, given: Mapping[str, str]) -> dict[str, Any]:
    """Every option of ``generator``, read from the user's text where given, else its
    default; an :class:`OptionError` for a name it does not declare or a value it refuses."""
    declared = {option.name: option for option in declared_options(generator)}
    unknown = [name for name in given if name not in declared]
    if unknown:
        takes = f"its options: {', '.join(declared)}" if declared else "it takes no options"
        raise OptionError(f"target '{generator.name}' has no option '{unknown[0]}'; {takes}")
    return {name: option.value(given.get(name)) for name, option in declared.items()}


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
