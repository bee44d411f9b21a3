"""The SFC and PLCopen targets refuse orthogonal regions with their place."""

from __future__ import annotations

import pytest
from conftest import EXAMPLES, generate

from lightrocks.workbench.generators import GenerationError

AHEAD = EXAMPLES / "din_rail_ahead" / "tasks" / "AssembleRailAhead.lr"

GATE = """statechart Gate {
  initial state Both {
    region Left { initial state A; }
    region Right { initial state B; }
  }
}
"""


@pytest.mark.parametrize("target", ["sfc", "plcopen"])
def test_regions_are_refused_with_their_place(tmp_path, target: str) -> None:
    model = tmp_path / "Gate.lr"
    model.write_text(GATE)
    with pytest.raises(GenerationError, match=r"Gate.lr:3:5: Gate: .*orthogonal regions yet"):
        generate(target, [model], search=[tmp_path])


def test_a_task_that_imports_regions_is_refused_at_the_region() -> None:
    with pytest.raises(GenerationError, match=r"PlugTerminalAhead.lr:\d+:\d+: .*region 'Arm'"):
        generate("sfc", [AHEAD])
