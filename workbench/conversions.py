"""The conversion registry: models from another statechart language into LightRocks, or out
of it (``lightrocks convert``).

A conversion is found through the ``lightrocks.conversions`` entry points, as a generator is
found through ``lightrocks.generators``, so a separate package can add one. Its entry is
named ``<source>-to-<target>`` (``sc-to-lr``: a ``.sc`` file to ``.lr``), so that a convert
imports only the conversion it uses; the descriptor it points to says the same, and one that
disagrees with its name is refused when loaded.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from importlib.metadata import entry_points
from pathlib import Path

from lightrocks.workbench.diagnostics import Diagnostic

GROUP = "lightrocks.conversions"


@dataclass
class Converted:
    """The result of converting one file: the target's file name and text (``None`` when an
    error refuses the conversion), the findings, and the converted syntax tree (``unit``)."""

    name: str
    text: str | None
    findings: list[Diagnostic] = field(default_factory=list)
    unit: object = None


Convert = Callable[[Path, str, str], Converted]
"""``(path, text, shown) -> Converted``: ``shown`` names the file in findings. A source that
does not parse raises ``metamodel.grammar.SyntaxProblem``."""


@dataclass(frozen=True)
class Conversion:
    """A conversion from files with the suffix ``source`` (``.sc``) to the language
    ``target`` (``lr``)."""

    source: str
    target: str
    description: str
    convert: Convert

    @property
    def name(self) -> str:
        """The name it is registered under."""
        return entry_name(self.source, self.target)


class ConversionError(Exception):
    """No conversion for that pair, or one that cannot be loaded."""


def entry_name(source: str, target: str) -> str:
    """The entry-point name of the conversion from the suffix ``source`` to ``target``."""
    return f"{source.lstrip('.')}-to-{target.lstrip('.')}"


def _pair(name: str) -> tuple[str, str]:
    source, _, target = name.partition("-to-")
    return f".{source}", target


def conversion_pairs() -> list[tuple[str, str]]:
    """(source suffix, target) of every registered conversion, read from the entry names
    alone (nothing is imported)."""
    return sorted(_pair(entry.name) for entry in entry_points(group=GROUP))


def load_conversion(source: str, target: str) -> Conversion:
    """The conversion from files with the suffix ``source`` to ``target``; only that one is
    imported."""
    name = entry_name(source, target)
    found = [entry for entry in entry_points(group=GROUP) if entry.name == name]
    if not found:
        known = ", ".join(f"{s} -> .{t}" for s, t in conversion_pairs())
        what = source or "a file without suffix"
        raise ConversionError(f"no conversion from {what} to .{target.lstrip('.')}; known: {known}")
    try:
        conversion = found[0].load()
    except (ImportError, AttributeError) as error:
        raise ConversionError(f"conversion '{name}' cannot be loaded: {error}") from None
    if not isinstance(conversion, Conversion) or conversion.name != name:
        raise ConversionError(f"conversion '{name}' ({found[0].value}) is not a {name} Conversion")
    return conversion


def conversions() -> list[Conversion]:
    """Every registered conversion, loaded, in the order of their pairs."""
    return [load_conversion(source, target) for source, target in conversion_pairs()]
