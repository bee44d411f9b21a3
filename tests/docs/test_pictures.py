"""The pictures in docs/images are the examples' current DOT: ``make pictures`` draws them,
stamping each PNG with the hash of the DOT it was drawn from."""

from __future__ import annotations

from pathlib import Path

import pytest

from lightrocks.generators.graphviz.rendering import dot_hash, stamped_hash
from lightrocks.workbench.check import check
from lightrocks.workbench.generators import GenerationRequest, load_generator

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"
PICTURES = sorted(  # statechart pictures: drawn from a DOT file beside them
    p for p in (ROOT / "docs" / "images").glob("*.png") if p.with_suffix(".dot").is_file()
)


def current_dot(qualified_name: str) -> str:
    """The DOT the dot generator writes today for the example statechart of that name."""
    model = EXAMPLES.joinpath(*qualified_name.split(".")).with_suffix(".lr")
    context = check([model], [EXAMPLES])
    request = GenerationRequest(context, [model.resolve()])
    return load_generator("dot").generate(request)[f"{qualified_name}.dot"]


def test_the_readme_shows_a_committed_picture() -> None:
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    assert PICTURES and any(f"docs/images/{p.name}" in readme for p in PICTURES)


@pytest.mark.parametrize("picture", PICTURES, ids=lambda p: p.stem)
def test_picture_matches_its_model(picture: Path) -> None:
    dot = current_dot(picture.stem)
    assert stamped_hash(picture.read_bytes()) == dot_hash(dot), (
        f"{picture.name} is stale: run 'make pictures'"
    )
    assert picture.with_suffix(".dot").read_text(encoding="utf-8") == dot


def test_a_changed_model_makes_its_picture_stale() -> None:
    picture = ROOT / "docs" / "images" / "screwing.skills.ScrewIn.png"
    changed = current_dot("screwing.skills.ScrewIn").replace("LetGo", "LetItGo")
    assert stamped_hash(picture.read_bytes()) != dot_hash(changed)
