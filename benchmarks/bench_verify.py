"""Verify time (check, then the model checker) beside check time, on the examples, on a
generated task of 1,000 states and on a retry loop over a counter of range 0..10⁶.

The task chains 1,000 instances of a two-state skill; each instance is retried at most three
times (a counter on a scene object, reset on the way in), so the model checker tracks the
counter exactly along the whole chain. The retry loop counts to a million: the checker keeps
the counter exact within its window and by its side past it, so it proves the loop ends
without enumerating. Goals: the examples verified in under 5 s, the generated task in under
30 s, the retry loop in under 5 s. Times are CPU times of this process, the least of three runs.
Run: .venv/bin/python benchmarks/bench_verify.py
"""

from __future__ import annotations

import shutil
import tempfile
import time
from collections.abc import Callable
from pathlib import Path

from lightrocks.languages.lightrocks.behaviour.verify import verify
from lightrocks.workbench.check import check

ROOT = Path(__file__).resolve().parents[1]
STATES = 1_000
GOAL_EXAMPLES = 5.0
GOAL_GENERATED = 30.0
GOAL_RETRY = 5.0
RETRIES = 10**6

DEVICES = """\
package big;

<<timeout="5 s">> device Arm {
  command move(Length x, Velocity speed = 0.1 m/s in 1 mm/s .. 0.5 m/s);
  sensor Boolean done = false;
  sensor Force force in -100 N .. 100 N;
}

cell Cell {
  arm : Arm;
  object part { Integer tries = 0 in 0 .. 10; }
}
"""

MOVE = """\
package big;

<<action>> statechart Move {
  parameters { Length x = 10 mm; }
  do / arm.move(x = x);
  end condition blocked [arm.force > 20 N];
  end condition done [arm.done];
}
"""

STEP = """\
package big;

<<skill>> statechart Step {
  start condition go;
  end condition ok;
  end condition failed;
  <<import="Move">> state Reach(x = 5 mm);
  <<import="Move">> state Back(x = -5 mm);
  go -> Reach;
  Reach -> Back done;
  Reach -> failed blocked;
  Reach -> failed timeout;
  Back -> ok done;
  Back -> failed blocked;
  Back -> failed timeout;
}
"""


def task(states: int) -> str:
    lines = [
        "package big;",
        "",
        "<<task>> statechart Big {",
        "  start condition go;",
        "  end condition ok;",
        "  end condition failed;",
    ]
    lines += [f'  <<import="Step">> state S{i};' for i in range(states)]
    lines.append("  go -> S0 / { part.tries = 0; };")
    for i in range(states):
        after = f"S{i + 1}" if i + 1 < states else "ok"
        lines.append(f"  S{i} -> {after} ok / {{ part.tries = 0; }};")
        lines.append(
            f"  S{i} -> S{i} [part.tries < 3] failed / {{ part.tries = part.tries + 1; }};"
        )
        lines.append(f"  S{i} -> failed [part.tries >= 3] failed;")
    lines.append("}")
    return "\n".join(lines) + "\n"


RETRY = f"""\
package loop;

import big.Cell;
import big.Move;

<<skill>> statechart Retry {{
  start condition go;
  end condition ok;
  end condition failed;
  property fewTries: always [part.tries <= {RETRIES}];
  <<import="Move">> state Reach(x = 5 mm);
  go -> Reach / {{ part.tries = 0; }};
  Reach -> ok done;
  Reach -> Reach [part.tries < {RETRIES}] blocked / {{ part.tries = part.tries + 1; }};
  Reach -> failed [part.tries >= {RETRIES}] blocked;
  Reach -> failed timeout;
}}
"""


def retry_loop(folder: Path) -> Path:
    """A skill retried up to a million times, the counter ranged 0..10⁶."""
    package = folder / "big"
    package.mkdir(parents=True, exist_ok=True)
    cell = DEVICES.replace("in 0 .. 10;", f"in 0 .. {RETRIES};")
    (package / "Cell.lrd").write_text(cell, encoding="utf-8")
    (package / "Move.lr").write_text(MOVE, encoding="utf-8")
    (folder / "loop").mkdir(exist_ok=True)
    (folder / "loop" / "Retry.lr").write_text(RETRY, encoding="utf-8")
    return folder


def generated(folder: Path, states: int) -> Path:
    package = folder / "big"
    package.mkdir(parents=True, exist_ok=True)
    (package / "Cell.lrd").write_text(DEVICES, encoding="utf-8")
    (package / "Move.lr").write_text(MOVE, encoding="utf-8")
    (package / "Step.lr").write_text(STEP, encoding="utf-8")
    (package / "Big.lr").write_text(task(states), encoding="utf-8")
    return folder


def least(run: Callable[[Path], object], source: Path, scratch: Path, rounds: int = 3) -> float:
    """The least CPU time of ``run`` on fresh copies of ``source`` (a new path each time, so
    that the findings cache of the process answers nothing)."""
    times = []
    for _ in range(rounds):
        copy = scratch / f"run{len(list(scratch.iterdir()))}"
        shutil.copytree(source, copy)
        start = time.process_time()
        run(copy)
        times.append(time.process_time() - start)
    return min(times)


def main() -> None:
    examples = ROOT / "examples"
    check([examples])  # warm-up: grammar construction happens once per process
    with tempfile.TemporaryDirectory() as tmp:
        scratch = Path(tmp) / "runs"
        scratch.mkdir()
        big = generated(Path(tmp) / "big", STATES)
        loop = retry_loop(Path(tmp) / "loop")
        inputs = (
            ("examples", examples),
            (f"generated task, {STATES} states", big),
            ("retry loop, counter 0..10^6", loop),
        )
        rows = []
        for name, folder in inputs:
            checked = least(lambda f: check([f]), folder, scratch)
            verified = least(lambda f: _proved(verify([f])), folder, scratch)
            rows.append((name, checked, verified))
    for name, checked, verified in rows:
        print(f"{name:32} check {checked:6.2f} s   verify {verified:6.2f} s")
    examples_time, generated_time = rows[0][2], rows[1][2]
    print(f"verify examples: {examples_time:.2f} s (goal < {GOAL_EXAMPLES:.0f} s: "
          f"{'met' if examples_time < GOAL_EXAMPLES else 'NOT met'})")  # fmt: skip
    print(f"verify generated task: {generated_time:.2f} s (goal < {GOAL_GENERATED:.0f} s: "
          f"{'met' if generated_time < GOAL_GENERATED else 'NOT met'})")  # fmt: skip
    retry_time = rows[2][2]
    print(f"verify retry loop: {retry_time:.2f} s (goal < {GOAL_RETRY:.0f} s: "
          f"{'met' if retry_time < GOAL_RETRY else 'NOT met'})")  # fmt: skip


def _proved(result) -> None:
    """A benchmark input verifies clean: a time of a failing verification means nothing."""
    if result.diagnostics:
        raise SystemExit(f"not verified clean: {result.diagnostics[0]}")


if __name__ == "__main__":
    main()
