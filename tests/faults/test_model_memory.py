"""Memory linear in the model with a small constant: a model of about 5 MB made of one
string literal (or of escaped quotes, a block comment, blank space or empty lines) checks
with a traced peak of a few times its size. textX's string rule took about 180 bytes per
character, the skipper of whitespace about 115, a table of line starts up to 36 bytes a
line: a 5 MB literal took 947 MB and 19 s before."""

from __future__ import annotations

import tracemalloc
from pathlib import Path

import pytest

from lightrocks.workbench.check import check

from .fault_runs import write_models

SIZE = 5_000_000
BOUND = 20  # traced peak per byte of the file; measured: 3 to 3.5

HEAD = "package t;\n\nstatechart Big {\n  parameters {\n    String s = "
TAIL = ";\n  }\n  initial state A;\n}\n"
SHAPES = {
    "string literal": HEAD + '"' + "a" * SIZE + '"' + TAIL,
    "escaped quotes": HEAD + '"' + '\\"' * (SIZE // 2) + '"' + TAIL,
    "block comment": HEAD + '"a" /*' + "x" * SIZE + "*/" + TAIL,
    "blank space": HEAD + '"a"' + " " * SIZE + TAIL,
    "empty lines": HEAD + '"a"' + "\n" * SIZE + TAIL,
}


@pytest.fixture(scope="module")
def warm(tmp_path_factory: pytest.TempPathFactory) -> None:
    """The grammar and the checks are built once per process, before anything is measured."""
    root = tmp_path_factory.mktemp("warm")
    write_models(root, {"Big": HEAD + '"a"' + TAIL})
    assert not check([root]).diagnostics.has_errors


@pytest.mark.parametrize("shape", sorted(SHAPES))
def test_a_large_model_checks_in_memory_proportional_to_it(
    tmp_path: Path, warm: None, shape: str
) -> None:
    text = SHAPES[shape]
    write_models(tmp_path, {"Big": text})
    size = (tmp_path / "t" / "Big.lr").stat().st_size
    tracemalloc.start()
    try:
        context = check([tmp_path])
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert not context.diagnostics.has_errors, [str(d) for d in context.diagnostics.items][:3]
    assert peak < BOUND * size, f"{shape}: peak {peak / 1e6:.0f} MB for {size / 1e6:.0f} MB"
