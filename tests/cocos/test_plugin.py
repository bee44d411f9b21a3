"""A CoCo from a separate package: a language with no file extensions that only adds CoCos.

``docs/cocos.md`` shows this plugin; here it is registered by patching the language list
the checker sees, as the ``lightrocks.languages`` entry point would.
"""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import pytest

import lightrocks.workbench.check as checking
from cocos.models import BASE, materialize
from lightrocks.languages.lightrocks.analysis import analysis
from lightrocks.workbench.check import check
from lightrocks.workbench.cocos import coco
from lightrocks.workbench.diagnostics import Severity
from lightrocks.workbench.languages import Language, languages


@coco("LR9001", Severity.WARNING, "state names start with an upper-case letter")
def capitalised_states(context: checking.CheckContext) -> Iterator[tuple]:
    for component in analysis(context).models.components:
        for region in component.region.regions():
            if region.loaded is not component.loaded:
                continue  # inherited through <<extends>>: checked in its own file
            for name, info in region.states.items():
                if not name[:1].isupper():
                    message = f"state '{name}' should start with an upper-case letter"
                    yield info.state.position, message, f"rename it '{name[:1].upper()}{name[1:]}'"


def _no_files(*_: object) -> object:
    raise NotImplementedError("this language reads no files")


HOUSE_RULES = Language(
    name="house-rules",
    extensions=(),
    parse=_no_files,
    format=_no_files,
    declarations=lambda unit: (),
    cocos=(capitalised_states,),
    description="extra CoCos of our team",
)


def test_plugin_coco_runs_with_the_others(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(checking, "languages", lambda: (*languages(), HOUSE_RULES))
    assert "LR9001" in [c.code for c in checking.all_cocos()]
    pick = BASE["skills/Pick.lr"].replace("Reach", "reach")
    materialize(tmp_path, {**BASE, "skills/Pick.lr": pick})
    findings = check([tmp_path]).diagnostics.items
    assert [(d.code, d.line, d.column, d.severity) for d in findings] == [
        ("LR9001", 10, 3, Severity.WARNING)
    ]
    assert findings[0].hint == "rename it 'Reach'"
