"""A corpus of deliberately broken copies of the example models: each folder holds one
changed model file and ``expect.json``, the finding it must cause (code and position). The
checker must find at least 90 % of them."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

from lightrocks.languages.lightrocks.behaviour.verify import verify
from lightrocks.workbench.check import check
from lightrocks.workbench.diagnostics import Diagnostic

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"
CORPUS = Path(__file__).with_name("corpus")
KINDS = {
    "LR0112", "LR0209", "LR0221", "LR0601", "LR0602", "LR0603", "LR0604", "LR0605", "LR0606",
    "LR0607", "LR0608", "LR0609", "LR0610", "LR0701", "LR0702", "LR0703",
}  # fmt: skip


def _cases() -> list[Path]:
    return sorted(p for p in CORPUS.iterdir() if (p / "expect.json").is_file())


def _expect(case: Path) -> dict:
    return json.loads((case / "expect.json").read_text(encoding="utf-8"))


def _findings(case: Path, root: Path) -> list[Diagnostic]:
    """The findings on the examples with the case's file replaced."""
    shutil.copytree(EXAMPLES, root)
    expect = _expect(case)
    shutil.copyfile(case / expect["file"], root / expect["file"])
    file = root / expect["file"]
    if expect["stage"] == "verify":
        return verify([file], [root]).diagnostics
    return check([file], [root]).diagnostics.items


def _found(case: Path, root: Path) -> bool:
    expect = _expect(case)
    wanted = (root / expect["file"]).resolve()
    return any(
        d.code == expect["code"]
        and Path(d.file).resolve() == wanted
        and (d.line, d.column) == (expect["line"], expect["column"])
        for d in _findings(case, root)
    )


def test_the_corpus_covers_every_kind_several_times() -> None:
    cases = _cases()
    assert len(cases) >= 40
    codes = [_expect(c)["code"] for c in cases]
    assert set(codes) == KINDS
    assert all(codes.count(code) >= 2 for code in KINDS)
    charts = {(_expect(c)["code"], _expect(c)["file"]) for c in cases}
    assert len(charts) == len(cases), "each instance of a kind breaks another chart"


def test_at_least_nine_in_ten_broken_models_are_found(tmp_path: Path) -> None:
    missed = [c.name for i, c in enumerate(_cases()) if not _found(c, tmp_path / str(i))]
    found = 1 - len(missed) / len(_cases())
    print(f"found {found:.0%} of {len(_cases())}; missed: {missed}")
    assert found >= 0.9, missed
