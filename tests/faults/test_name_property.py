"""Property: whatever names a model uses — keywords, builtins, dunders, the runtime's
attributes, the generated modules' own names, their NFKC twins or random identifiers —
generating, importing and running it reaches the outcome the model says."""

from __future__ import annotations

import builtins
import itertools
import keyword
from datetime import timedelta
from pathlib import Path

import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

from lightrocks.app.loading import component_class, generated_package
from lightrocks.generators.python import generator
from lightrocks.runtime import ActionComponent, CompositeComponent
from lightrocks.workbench.check import check

from .fault_runs import within

EXAMPLES = 500

LANGUAGE_WORDS = {
    "package", "import", "statechart", "state", "initial", "final", "parameters", "condition",
    "start", "end", "entry", "exit", "do", "true", "false", "invariant",
}  # fmt: skip
"""Words of the LightRocks syntax itself: not names a model can use."""

RUNTIME = {*vars(CompositeComponent()), *vars(ActionComponent()), *dir(CompositeComponent)}
SPECIAL = sorted(
    {*keyword.kwlist, *keyword.softkwlist, *dir(builtins), *RUNTIME}
    | {"_", "__", "__x", "x__", "_domain", "rt", "s", "self", "Any", "ClassVar", "value", "env"}
)
FULLWIDTH = {
    c: chr(ord(c) + 0xFEE0) for c in "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
}


def twin(name: str) -> str:
    """A different spelling that Python's NFKC normalisation turns into ``name``."""
    return "".join(FULLWIDTH.get(c, c) for c in name)


special = st.sampled_from(SPECIAL)
names = st.one_of(
    special,
    special.map(twin),
    st.from_regex(r"[A-Za-z_][A-Za-z0-9_]{0,8}", fullmatch=True),
    st.text(st.characters(categories=("Ll", "Lu", "Lo")), min_size=1, max_size=4),
).filter(lambda n: n.isidentifier() and n not in LANGUAGE_WORDS)

MODEL = """package {package};

statechart {chart} {{
  parameters {{
    Integer {p} = 1;
    Integer {q} = 2;
  }}

  initial state {a} {{
    entry / {{ {p} = {p} + 1; }}
  }}
  state {b};
  final state {f};

  {a} -> {b} [{p} == 2] {e1};
  {b} -> {f} [{q} == 2] {e2} / {{ {q} = {p} + {q}; }};
}}
"""

_folders = itertools.count()


@pytest.fixture(scope="module")
def workspace(tmp_path_factory) -> Path:
    return tmp_path_factory.mktemp("names")


@pytest.fixture(scope="module", autouse=True)
def unformatted():
    """Formatting does not change what the code means; leaving it out keeps 500 runs short."""
    original = generator.ruff_format
    generator.ruff_format = lambda files: files
    yield
    generator.ruff_format = original


@settings(
    max_examples=EXAMPLES,
    deadline=timedelta(seconds=30),
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.function_scoped_fixture],
)
@given(
    package=names,
    chart=names,
    parameters=st.lists(names, min_size=2, max_size=2, unique=True),
    states=st.lists(names, min_size=3, max_size=3, unique=True),
    events=st.lists(names, min_size=2, max_size=2, unique=True),
)
def test_any_names_generate_import_and_run(workspace, package, chart, parameters, states, events):
    (p, q), (a, b, f), (e1, e2) = parameters, states, events
    root = workspace / str(next(_folders))
    (root / package).mkdir(parents=True)
    model = root / package / f"{chart}.lr"
    text = MODEL.format(package=package, chart=chart, p=p, q=q, a=a, b=b, f=f, e1=e1, e2=e2)
    model.write_text(text, encoding="utf-8")
    context = check([model], [root])
    assume(not context.diagnostics.has_errors)  # e.g. a name the grammar reads as a keyword

    def run():
        package_module = generated_package(context, [model.resolve()], root / "cache")
        cls = component_class(package_module, f"{package}.{chart}")
        instance = cls().start()
        instance.send(e1)
        instance.send(e2)
        return cls, instance

    cls, instance = within(run, 25.0)
    assert instance.finished and instance.outcome == f
    assert getattr(instance, cls.PARAMETERS[q]) == 4
    assert instance.path == chart and instance.parent is None
