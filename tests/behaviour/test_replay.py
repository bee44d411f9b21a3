"""A refuted property's counterexample, written as a dry-run script, replays to the same end
with the generated Python code and the dry-run adapter (``lightrocks run --script``)."""

from __future__ import annotations

import pytest

from behaviour.broken_models import broken
from lightrocks.app.cli import main
from lightrocks.languages.lightrocks.behaviour.script import script_text
from lightrocks.languages.lightrocks.behaviour.verify import verify


@pytest.mark.parametrize("case", ["41-LR0701-ScrewTask", "43-LR0701-CarryScrew"])
def test_a_counterexample_replays_to_its_end(
    case: str, tmp_path, capsys: pytest.CaptureFixture[str]
) -> None:
    root, file, expect = broken(case, tmp_path)
    result = verify([file], [root])
    diagnostic, counterexample = next(
        (d, c) for d, c in result.counterexamples if d.code == expect["code"]
    )
    assert counterexample.end, diagnostic
    cex = tmp_path / "cex.json"
    cex.write_text(script_text(counterexample), encoding="utf-8")
    argv = ["run", str(file), "--path", str(root), "--adapter", "dryrun", "--script", str(cex)]
    code = main(argv)
    out = capsys.readouterr().out
    assert f"outcome: {counterexample.end} after" in out, out
    assert code == 1  # the success outcome is what the property says cannot be reached
