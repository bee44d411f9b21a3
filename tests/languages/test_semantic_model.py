"""The language's facts are defined once, in the semantic model
(``languages/lightrocks/model.py``): the layers and which may use which, the known
stereotypes and where each takes effect, the built-in outcomes, and the default command
budget.

How a second definition is found: every module of the package is parsed with Python's
``ast`` and every literal collection in it (tuple, list, set, and the keys of a dict) whose
elements are string constants is compared with the model's facts. It is a second definition
when it

- holds every layer name (a layer tuple, or a may-use table keyed by layer);
- holds exactly the built-in outcomes;
- holds two or more stereotype names, not all of them layers (a table of known stereotypes,
  of where they take effect, or of the references among them);

and a budget default is an assignment or keyword whose name speaks of a budget (or of a
default timeout) and whose value is the number of the default. The model itself is exempt,
and the number may stand in ``runtime/__init__.py`` alone: the runtime contract names it for
generated code, which never imports the workbench, and the model takes it from there.
"""

from __future__ import annotations

import ast
import re
from pathlib import Path

import pytest

from lightrocks.languages.lightrocks.model import (
    BUILTIN_OUTCOMES,
    DEFAULT_BUDGET,
    LAYERS,
    STEREOTYPES,
)

ROOT = Path(__file__).resolve().parents[2]
FOLDERS = ("metamodel", "languages", "workbench", "generators", "runtime", "adapters", "app")
MODEL = ROOT / "languages" / "lightrocks" / "model.py"
BUDGET_HOME = ROOT / "runtime" / "__init__.py"
BUDGET_NAME = re.compile(r"budget|default.*timeout|timeout.*default", re.IGNORECASE)


def _strings(node: ast.AST) -> list[str] | None:
    """The string constants of a literal collection, or None for any other node."""
    if isinstance(node, ast.Dict):
        elements = [k for k in node.keys if k is not None]
    elif isinstance(node, ast.Tuple | ast.List | ast.Set):
        elements = node.elts
    else:
        return None
    return [e.value for e in elements if isinstance(e, ast.Constant) and isinstance(e.value, str)]


def _fact(strings: list[str]) -> str | None:
    """Which of the model's facts a literal collection defines again, if any."""
    found = set(strings)
    if found >= set(LAYERS):
        return "the layers"
    if found == set(BUILTIN_OUTCOMES):
        return "the built-in outcomes"
    if len(found) >= 2 and found <= set(STEREOTYPES) and not found <= set(LAYERS):
        return "stereotypes"
    return None


def _budget_default(node: ast.AST) -> bool:
    """An assignment or keyword naming a budget (or a default timeout) with the default's
    number."""
    if isinstance(node, ast.Assign | ast.AnnAssign):
        targets = node.targets if isinstance(node, ast.Assign) else [node.target]
        names = [getattr(t, "id", getattr(t, "attr", "")) for t in targets]
        value = node.value
    elif isinstance(node, ast.keyword):
        names, value = [node.arg or ""], node.value
    else:
        return False
    number = isinstance(value, ast.Constant) and type(value.value) in (int, float)
    return (
        number and value.value == DEFAULT_BUDGET and any(BUDGET_NAME.search(name) for name in names)
    )


def definitions(source: str, budget_allowed: bool = False) -> list[str]:
    """``line: what`` for every fact of the semantic model that ``source`` defines again."""
    found = []
    for node in ast.walk(ast.parse(source)):
        strings = _strings(node)
        fact = _fact(strings) if strings else None
        if fact is not None:
            found.append((node.lineno, f"{fact} {sorted(set(strings))}"))
        if not budget_allowed and _budget_default(node):
            found.append((node.lineno, f"the default budget {DEFAULT_BUDGET:g} s"))
    return [f"{line}: {what}" for line, what in sorted(found)]


MODULES = sorted(p for folder in FOLDERS for p in (ROOT / folder).rglob("*.py") if p != MODEL)


@pytest.mark.parametrize("path", MODULES, ids=lambda p: str(p.relative_to(ROOT)))
def test_no_module_defines_a_fact_of_the_semantic_model(path: Path) -> None:
    found = definitions(path.read_text(encoding="utf-8"), budget_allowed=path == BUDGET_HOME)
    assert not found, f"{path.relative_to(ROOT)} defines again what model.py defines: {found}"


def test_the_scan_sees_each_kind_of_second_definition() -> None:
    source = (
        'LAYERS = ("task", "skill", "action")\n'
        'USES = {"task": ("skill",), "skill": (), "action": ()}\n'
        'OUTCOMES = {"error", "timeout", "preempted"}\n'
        'KNOWN = ["import", "extends"]\n'
        "DEFAULT_TIMEOUT = 30.0\n"
        "def f(budget=None):\n"
        "    return g(budget=30)\n"
    )
    found = [line.split(":")[0] for line in definitions(source)]
    assert found == ["1", "2", "3", "4", "5", "7"]


def test_the_scan_leaves_other_collections_alone() -> None:
    source = (
        'SPANS = ("skill", "action")\n'
        'REAL = ("error", "timeout")\n'
        'KEYWORDS = {"state", "error", "timeout", "preempted"}\n'
        "FPS = 30.0\n"
        "START_TIMEOUT = 30.0\n"
    )
    assert definitions(source) == []


def test_the_model_answers_the_facts() -> None:
    from lightrocks.languages.lightrocks.model import may_use, takes_effect

    assert may_use("task", "skill") and may_use("skill", "action") and may_use(None, None)
    assert not may_use("skill", "task") and not may_use("action", "action")
    assert not may_use(None, "skill") and not may_use("task", None)
    assert takes_effect("timeout", "device") and takes_effect("scene", "cell")
    assert not takes_effect("timeout", "state") and not takes_effect("unknown", "statechart")


def test_an_action_budget_is_its_own_else_its_device_s_else_the_default() -> None:
    from dataclasses import replace

    from lightrocks.languages.lightrocks.analysis import analysis
    from lightrocks.workbench.check import check

    examples = ROOT / "examples"
    context = check([examples / "screwing" / "actions"], [examples])
    components = {c.name: c for c in analysis(context).models.components}
    gripper = context.workspace.lookup("lightrocks.robots.ParallelGripper").node
    own = components["Approach"].command_budget(gripper)
    assert (own.seconds, own.stereotype.value) == (10.0, "10 s")
    device = components["CloseGripper"].command_budget(gripper)
    assert (device.seconds, device.stereotype.value) == (5.0, "5 s")
    default = components["CloseGripper"].command_budget(replace(gripper, stereotypes=()))
    assert (default.seconds, default.stereotype) == (DEFAULT_BUDGET, None)
