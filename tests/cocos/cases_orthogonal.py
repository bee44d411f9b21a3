"""Passing and failing models for the CoCos on orthogonal regions (LR0218–LR0220)."""

from __future__ import annotations

from cocos.models import DEVICES, Case, replace

PAIR = """\
package misc;

statechart Pair {
  initial state Both {
    region Left {
      initial state A;
      final state B;
      A -> B tick;
    }
    region Right {
      initial state C;
      final state D;
      C -> D tock;
    }
  }
  final state Done;
  Both -> Done;
}
"""

TWIN = """\
package skills;

import cell.Cell;
import actions.*;

<<skill>> statechart Twin {
  end condition done;
  initial state Both {
    region Near {
      <<import="Move">> initial state Reach(x = 5 mm);
      final state Reached;
      Reach -> Reached;
    }
    region Far {
      <<import="Move">> initial state Reach(x = 9 mm);
      final state Reached;
      Reach -> Reached;
    }
  }
  Both -> done;
}
"""

TWICE = """\
package tasks;

import skills.*;

<<task>> statechart Twice {
  end condition ok;
  initial state Both {
    region One {
      <<import="Pick">> initial state First;
      final state Done1;
      First -> Done1;
    }
    region Two {
      initial state Wait;
      final state Done2;
      Wait -> Done2 tick;
    }
  }
  Both -> ok;
}
"""

ORTHOGONAL_CASES: list[Case] = [
    Case(
        "LR0218",
        ok={"misc/Pair.lr": PAIR},
        bad={"misc/Pair.lr": replace(PAIR, "C -> D tock;", "C -> D tock;\n      C -> @@B tick;")},
        message="'B' is in region 'Left': a transition cannot cross from region 'Right'",
    ),
    Case(
        "LR0219",
        ok={"misc/Pair.lr": PAIR},
        bad={
            "misc/Pair.lr": replace(
                PAIR, "    region Right {", "    @@state E;\n    region Right {"
            )
        },
        message="'E' stands beside the regions of 'Both'",
        hint="move it into one of the regions",
    ),
    Case(
        "LR0219",
        ok={"misc/Pair.lr": PAIR},
        bad={
            "misc/Pair.lr": replace(
                PAIR, "      C -> D tock;", "      C -> D tock;\n      @@entry / { }"
            )
        },
        message="an action cannot stand in region 'Right'",
        variant="inside",
    ),
    Case(
        "LR0220",
        ok={
            "skills/Twin.lr": TWIN,
            "robots/Devices.lrd": replace(DEVICES, "device Arm", "<<concurrent>> device Arm"),
        },
        bad={"skills/Twin.lr": replace(TWIN, "    region Far {", "    @@region Far {")},
        message="regions 'Near' and 'Far' both command 'arm'",
        hint="<<concurrent>>",
    ),
    Case(
        "LR0220",
        ok={"tasks/Twice.lr": TWICE},
        bad={
            "tasks/Twice.lr": replace(
                replace(TWICE, "    region Two {", "    @@region Two {"),
                "      initial state Wait;\n",
                '      <<import="Pick">> initial state Wait;\n',
            ).replace("Wait -> Done2 tick;", "Wait -> Done2;")
        },
        message="regions 'One' and 'Two' both command 'arm'",
        variant="through-skills",
    ),
]
