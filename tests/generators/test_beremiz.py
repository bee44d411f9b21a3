"""The PLCopen target judged by Beremiz: every generated project (examples, plant models,
models at the target's edges, the worked extension package's models with the package
installed: ``extension_units``) loads in Beremiz's PLCopen loader, its PLCopen-to-IEC
generator turns it into IEC text without a finding, and its headless build compiles that
text with MatIEC (Beremiz's options) and gcc.

Needs Beremiz (``make judges``, see ``beremiz.py``): skipped with the reason where absent,
failed in CI.
"""

from __future__ import annotations

import os
import xml.etree.ElementTree as ET
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import pytest
from beremiz import Beremiz, beremiz, build, load
from edge_models import edge_cases
from extension_units import extension_units
from generation import EXAMPLES, ROOT
from judges import missing

from lightrocks.workbench.check import check
from lightrocks.workbench.generators import GenerationRequest, load_generator

TC6 = "{http://www.plcopen.org/xml/tc6_0201}"

SOURCES = {
    "examples": ([EXAMPLES], [EXAMPLES]),
    "plant": ([ROOT / "tests/generators/models/plant"], [ROOT / "tests/generators/models/plant"]),
}


@pytest.fixture(scope="module")
def judge() -> Beremiz:
    found = beremiz()
    if found is None:
        missing("Beremiz", "`make judges` (../shared/tools/beremiz), or BEREMIZ=DIR")
    return found


@pytest.fixture(scope="module")
def projects(tmp_path_factory: pytest.TempPathFactory) -> list[Path]:
    """Every PLCopen project generated from the examples, the plant models, the models at
    the target's edges (test_matiec_findings) and the extension package's models."""
    out = tmp_path_factory.mktemp("plcopen")
    edges = tmp_path_factory.mktemp("edges")
    edge_cases(edges)
    written = []
    for name, (paths, search) in {**SOURCES, "edges": ([edges], [edges])}.items():
        models = sorted(p for folder in paths for p in folder.rglob("*.lr"))
        context = check(models, search)
        assert not context.diagnostics.has_errors, context.diagnostics.items
        request = GenerationRequest(context, [m.resolve() for m in models], {}, None)
        for file, text in load_generator("plcopen").generate(request).items():
            target = out / name / file
            target.parent.mkdir(parents=True, exist_ok=True)
            target.write_text(text, encoding="utf-8")
            written.append(target)
    return written + list(extension_units(tmp_path_factory).plcopen.values())


def test_every_project_loads_and_generates_iec_in_beremiz(judge, projects, tally) -> None:
    loaded = load(judge, projects)
    assert [Path(r.path) for r in loaded] == projects
    clean = [r for r in loaded if not r.load and not r.errors and not r.warnings and r.text]
    tally("Beremiz loaded {clean}/{files} PLCopen projects into IEC text without a finding",
          clean=len(clean), files=len(projects))  # fmt: skip
    assert len(clean) == len(projects) >= 20, [r for r in loaded if r not in clean]


def _parts(project: Path) -> frozenset[bytes]:
    """The project's data types and its POUs but the program, each as its XML text. The
    program only instantiates the top function block; its shape is the same in every
    project."""
    root = ET.parse(project).getroot()
    pous = [p for p in root.iter(f"{TC6}pou") if p.get("pouType") != "program"]
    return frozenset(ET.tostring(part) for part in [*root.iter(f"{TC6}dataType"), *pous])


def largest(projects: list[Path]) -> list[Path]:
    """The projects whose parts are not all in another project: building these compiles
    every data type and function block of every project (a skill's are all in its task)."""
    parts = {project: _parts(project) for project in projects}
    return [
        project
        for project in projects
        if not any(
            parts[project] < parts[other] or (parts[project] == parts[other] and other < project)
            for other in projects
        )
    ]


def test_every_project_builds_in_beremiz(judge, projects, tmp_path: Path, tally) -> None:
    built_ones = largest(projects)
    assert len(built_ones) >= 10, built_ones
    with ThreadPoolExecutor(max_workers=os.cpu_count() or 1) as pool:
        results = list(pool.map(lambda i: build(judge, built_ones[i], tmp_path / str(i)),
                                range(len(built_ones))))  # fmt: skip
    built = [p for p, (ok, _) in zip(built_ones, results, strict=True) if ok]
    tally("Beremiz built {built}/{files} PLCopen projects headless, which hold every POU of "
          "{projects} projects", built=len(built), files=len(built_ones),
          projects=len(projects))  # fmt: skip
    failed = {
        p.name: said[-1500:] for p, (ok, said) in zip(built_ones, results, strict=True) if not ok
    }
    assert not failed, failed
