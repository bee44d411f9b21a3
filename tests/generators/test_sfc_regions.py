"""Orthogonal regions on the SFC and PLCopen targets: simultaneous divergence and
convergence, and the constructs around regions that still end generation with their place."""

from __future__ import annotations

import pytest
from conftest import EXAMPLES, generate

from lightrocks.generators.sfc_iec61131.checker import check_sfc
from lightrocks.workbench.generators import GenerationError

AHEAD = EXAMPLES / "din_rail_ahead" / "tasks" / "AssembleRailAhead.lr"

TOP = """statechart Gate {
  region Left { initial state A; }
  region Right { initial state B; }
}
"""

DEEP = """statechart Gate {
  initial state Idle;
  state Outer {
    initial state Both {
      region Left { initial state A; }
      region Right { initial state B; }
    }
    deep history D;
  }
  Idle -> Outer go;
  Outer -> Idle stop;
  Idle -> Outer.D again;
}
"""

NESTED = """statechart Gate {
  initial state Both {
    region Left {
      initial state Inner {
        region Up { initial state A; }
        region Down { initial state B; }
      }
    }
    region Right { initial state C; }
  }
}
"""


def test_a_task_with_regions_forks_and_joins_once() -> None:
    text = generate("sfc", [AHEAD])["AssembleRailAhead.st"]
    assert not check_sfc(text)
    fork = "FROM PressOn_fork TO (PressOn_Arm_Snap, PressOn_Camera_LookAhead, PressOn_watch)"
    join = "FROM (PressOn_Arm_end, PressOn_Camera_end, PressOn_watched) TO PressOn_left"
    assert text.count(fork) == 1 and text.count(join) == 1
    assert text.count("TO PressOn_fork\n") == 1  # every entry goes through the one fork


@pytest.mark.parametrize(
    ("model", "where", "what"),
    [
        (TOP, "1:1", "regions at the top of a statechart"),
        (NESTED, "4:7", "orthogonal regions inside a region"),
        (DEEP, "8:5", "deep history over orthogonal regions"),
    ],
)
@pytest.mark.parametrize("target", ["sfc", "plcopen"])
def test_unmapped_region_constructs_are_refused_with_their_place(
    tmp_path, target: str, model: str, where: str, what: str
) -> None:
    path = tmp_path / "Gate.lr"
    path.write_text(model)
    with pytest.raises(GenerationError, match=rf"Gate.lr:{where}: Gate: .*{what}"):
        generate(target, [path], search=[tmp_path])
