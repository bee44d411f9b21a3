"""The SCXML target judged by python-statemachine: its own SCXML reader loads the document
generated from every plain chart of ``examples/``, of ``tests/generators/models/plant/``, of
the sismic differential (``statecharts.test_sismic_differential``) and from random charts
(``statecharts.random_charts``), and after the start and after every event or clock step its
active states and parameter values equal those of the LightRocks runtime.

docs/language.md ("Relation to SCXML and python-statemachine") lists where the two differ by
design; of those, only deep history over a region resting in a final state can occur in
these charts (the random charts keep each variable to one region, have no invariants, no
error transitions and no division), and a sequence is counted apart where python-statemachine
entered such a remembered final state. Every other sequence must agree.
test_scxml_differences.py shows each difference on a chart of its own.
"""

from __future__ import annotations

import random
import warnings
from importlib.metadata import version
from pathlib import Path

import pytest
from statecharts.random_charts import TICK, VARIABLES, random_chart
from statecharts.sismic_charts import CHARTS as SISMIC_CHARTS

from interchange.pairs import generated
from interchange.scxml_judge import DEEP_HISTORY_OVER_A_FINAL, documented, run_both, same
from lightrocks.workbench.check import check
from lightrocks.workbench.generators import GenerationError

ROOT = Path(__file__).resolve().parents[2]
PLANT = ROOT / "tests" / "generators" / "models"
EXAMPLES = ROOT / "examples"
STEP = f"+{TICK}"

AGREEMENT = (
    f"SCXML judge (python-statemachine {version('python-statemachine')}): {{agree}} of "
    "{sequences} event sequences on {charts} charts agree with the LightRocks runtime, "
    "{documented} differ by a documented difference ({history} of them deep history over a "
    "region resting in a final state)"
)


def _judge(cls: type, document, variables, seed: object, count: int, length: int, tally) -> None:
    letters = [*sorted(cls().start().events), STEP]
    rng = random.Random(str(seed))
    sequences = [[rng.choice(letters) for _ in range(length)] for _ in range(count)]
    wrong, explained = [], []
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # the reader loads the document without complaint
        for events in sequences:
            mine, theirs, _, machine = run_both(cls, document, variables, events)
            pairs = enumerate(zip(mine, theirs, strict=True))
            step = next((i for i, (a, b) in pairs if not same(a, b)), None)
            if step is None:
                continue
            difference = documented(step, mine, theirs, machine)
            if difference is not None:
                explained.append(difference)
                continue
            wrong.append(
                f"after {events[:step]}:\n  LightRocks {mine[step]}\n  SCXML      "
                f"{theirs[step]}\n{document.text}"
            )
    agree = len(sequences) - len(wrong) - len(explained)
    tally(
        AGREEMENT,
        charts=1,
        sequences=len(sequences),
        agree=agree,
        documented=len(explained),
        history=explained.count(DEEP_HISTORY_OVER_A_FINAL),
    )
    assert not wrong, wrong[0]


# -- the charts of the project --------------------------------------------------------------

REFUSED = {
    "plant.Batch": "takes plain statecharts; Batch is a LightRocks component (<<skill>>)",
    "plant.Oven": "takes plain statecharts; Oven is a LightRocks component (<<task>>)",
    "plant.Stock": "a member access (a scene object's attribute, a sensor)",
}
"""Charts of plant/ the target refuses, with the reason it gives."""


@pytest.fixture(scope="module")
def plant(tmp_path_factory: pytest.TempPathFactory):
    return check([PLANT]), tmp_path_factory.mktemp("plant-cache")


@pytest.fixture(scope="module")
def examples(tmp_path_factory: pytest.TempPathFactory):
    return check([EXAMPLES]), tmp_path_factory.mktemp("examples-cache")


def _plain(folder: Path) -> list[Path]:
    return sorted(
        f
        for f in folder.rglob("*.lr")
        if not any(f"<<{layer}" in f.read_text(encoding="utf-8") for layer in LAYERS)
    )


LAYERS = ("task", "skill", "action")
PLANT_CHARTS = [f.stem for f in sorted((PLANT / "plant").glob("*.lr"))]
EXAMPLE_CHARTS = [str(f.relative_to(EXAMPLES).with_suffix("")) for f in _plain(EXAMPLES)]


def test_the_examples_hold_plain_charts() -> None:
    assert EXAMPLE_CHARTS == ["plain/Turnstile"]


@pytest.mark.parametrize("name", PLANT_CHARTS)
def test_plant_charts_run_alike_in_python_statemachine(name: str, plant, tally) -> None:
    context, cache = plant
    qualified = f"plant.{name}"
    file = PLANT / "plant" / f"{name}.lr"
    if qualified in REFUSED:
        with pytest.raises(GenerationError, match=r"plant/\w+\.lr:\d+:\d+: ") as refused:
            generated(context, file, qualified, cache)
        assert REFUSED[qualified] in str(refused.value)
        return
    cls, document = generated(context, file, qualified, cache)
    _judge(cls, document, list(document.variables), name, 30, 12, tally)


@pytest.mark.parametrize("name", EXAMPLE_CHARTS)
def test_example_charts_run_alike_in_python_statemachine(name: str, examples, tally) -> None:
    context, cache = examples
    qualified = name.replace("/", ".")
    cls, document = generated(context, EXAMPLES / f"{name}.lr", qualified, cache)
    _judge(cls, document, list(document.variables), name, 30, 12, tally)


OWN = Path(__file__).with_name("models")


@pytest.mark.parametrize("name", ["Everything"])
def test_the_chart_of_every_construct_runs_alike(name: str, tmp_path: Path, tally) -> None:
    """tests/interchange/models/d/Everything.lr: what plant/ lacks (the chart's own actions,
    time events and budget, reserved names, strings, abs/min/max, an error transition)."""
    cls, document = generated(check([OWN]), OWN / "d" / f"{name}.lr", f"d.{name}", tmp_path)
    _judge(cls, document, list(document.variables), name, 60, 14, tally)


@pytest.mark.parametrize("name", sorted(SISMIC_CHARTS))
def test_sismic_differential_charts_run_alike(name: str, pair, tally) -> None:
    cls, document = pair(name, SISMIC_CHARTS[name])
    _judge(cls, document, list(document.variables), name, 20, 12, tally)


# -- random charts --------------------------------------------------------------------------

CHARTS = 40
SWEEP = 160


def _random(seed: int, pair, tally) -> None:
    cls, document = pair("R", random_chart(seed))
    _judge(cls, document, VARIABLES, seed, 6, 14, tally)


@pytest.mark.parametrize("seed", range(CHARTS))
def test_random_charts_run_alike(seed: int, pair, tally) -> None:
    _random(seed, pair, tally)


@pytest.mark.slow
@pytest.mark.parametrize("seed", range(CHARTS, CHARTS + SWEEP))
def test_more_random_charts_run_alike(seed: int, pair, tally) -> None:
    _random(seed, pair, tally)
