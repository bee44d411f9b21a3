"""The models every diagram test draws: each folder of statecharts with its model path."""

from __future__ import annotations

from pathlib import Path

from lightrocks.generators.selection import selected
from lightrocks.languages.lightrocks.model import Component
from lightrocks.workbench.check import check
from lightrocks.workbench.generators import GenerationRequest

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"
FOLDERS = [
    EXAMPLES,
    *sorted(ROOT.glob("extensions/*/models")),
    *sorted(p for p in ROOT.glob("tests/**/models") if p.is_dir() and any(p.rglob("*.lr"))),
]
"""Each one a model path of its own (its packages are its sub-folders) that holds
LightRocks charts (tests/umlp/models holds UML/P charts, which the dot target does not read)."""


def components(folder: Path) -> list[Component]:
    """Every statechart under ``folder``, resolved (findings or not: a model with errors
    is drawn as far as it resolves)."""
    files = sorted(folder.rglob("*.lr"))
    context = check(files, [folder])
    return selected(GenerationRequest(context, [f.resolve() for f in files]))
