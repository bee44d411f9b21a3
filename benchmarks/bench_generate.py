"""Generation time of every target on the two case studies' tasks, beside the time to
check the same models (the baseline, measured in the same process).

A target's generation starts from the checked models, so the ratio says how much a
`lightrocks generate` adds to the `lightrocks check` it needs anyway. The SFC target
checks its own text with its structural checker, which is timed here too. Times are CPU
times of this process, the least of three runs. A target that refuses the tasks (SCXML
takes plain charts only) is listed as refused.
Run: .venv/bin/python benchmarks/bench_generate.py
"""

from __future__ import annotations

import shutil
import tempfile
import time
from collections.abc import Callable
from pathlib import Path

from lightrocks.generators.sfc_iec61131.checker import check_sfc
from lightrocks.workbench.check import check
from lightrocks.workbench.generators import (
    GenerationError,
    GenerationRequest,
    generator_names,
    load_generator,
)

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = ROOT / "examples"
TASKS = ["screwing/tasks/ScrewTask.lr", "din_rail/tasks/AssembleRail.lr"]


def least(run: Callable[[], object], rounds: int = 3) -> float:
    """The least CPU time of ``run`` over ``rounds`` runs."""
    times = []
    for _ in range(rounds):
        start = time.process_time()
        run()
        times.append(time.process_time() - start)
    return min(times)


def check_time(scratch: Path, rounds: int = 3) -> float:
    """The least CPU time of checking the tasks, each time in a fresh copy of the examples
    (made before the clock starts), so that the findings cache of the process answers
    nothing."""
    times = []
    for round_ in range(rounds):
        copy = scratch / f"examples{round_}"
        shutil.copytree(EXAMPLES, copy)
        times.append(least(lambda c=copy: check([c / t for t in TASKS], [c]), rounds=1))
    return min(times)


def main() -> None:
    tasks = [EXAMPLES / t for t in TASKS]
    context = check(tasks, [EXAMPLES])  # also the warm-up: the grammar is built once
    with tempfile.TemporaryDirectory() as scratch:
        checked = check_time(Path(scratch))
    request = GenerationRequest(context, [t.resolve() for t in tasks], {}, None)
    print(f"{'check (baseline)':22} {checked:7.3f} s")
    for name in generator_names():
        generator = load_generator(name)
        try:
            files = generator.generate(request)
        except GenerationError as error:
            print(f"{name:22} refused: {str(error).splitlines()[0][:70]}")
            continue
        spent = least(lambda g=generator: g.generate(request))
        size = sum(len(text) for text in files.values()) / 1000
        print(f"{name:22} {spent:7.3f} s  {spent / checked:5.2f} x check  ({size:,.0f} kB)")
        if name == "sfc":
            units = [text for file, text in files.items() if file.endswith(".st")]
            checker = least(lambda u=units: [check_sfc(text) for text in u])
            print(f"{'  its checker':22} {checker:7.3f} s  {checker / checked:5.2f} x check")


if __name__ == "__main__":
    main()
