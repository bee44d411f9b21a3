"""MatIEC judges the SFC units of the worked extension package (``extension_units``): each
compiles with MatIEC's defaults and with Beremiz's ``-f -l -p``, and its C links with gcc
and runs. Their syntax the package adds is there in ST: ``clamp`` as ``LIMIT``, ``count``
as an increment, requirements in the comment of their chart's block.

The step harness of ``test_matiec`` needs the unit's blocks in this process, where the
package is not installed; the package's behaviour is the dry run's business
(``tests/extensions``). Needs MatIEC and gcc (see ``conftest.home``).
"""

from __future__ import annotations

import subprocess
from pathlib import Path

import pytest
from extension_units import ExtensionUnits, extension_units
from plc import gcc, iec2c

DRIVER = """#include "iec_std_lib.h"
TIME __CURRENT_TIME;
BOOL __DEBUG;
void config_init__(void);
void config_run__(unsigned long tick);
int main(void) {
  config_init__();
  for (unsigned long tick = 0; tick < 100; tick++) config_run__(tick);
  return 0;
}
"""
"""Initialises the configuration and runs 100 scans with nothing started: every POU links."""


@pytest.fixture(scope="module")
def units(tmp_path_factory: pytest.TempPathFactory) -> ExtensionUnits:
    return extension_units(tmp_path_factory)


def _judged(home: Path, source: Path, out: Path) -> str:
    """Empty when both iec2c runs accept ``source`` and the C links and runs; else why not."""
    compiled = iec2c(home, source, out)
    if compiled.returncode != 0:
        return f"iec2c: {compiled.stdout}{compiled.stderr}"
    built = gcc(home, out, DRIVER, out / "program")
    if built.returncode != 0:
        return f"gcc: {built.stderr}"
    ran = subprocess.run([str(out / "program")], capture_output=True, timeout=60, check=False)
    return "" if ran.returncode == 0 else f"run: exit {ran.returncode}"


@pytest.mark.slow
def test_every_unit_of_the_extension_compiles_links_and_runs(
    home: Path, units: ExtensionUnits, tmp_path: Path, tally
) -> None:
    failures = {name: _judged(home, source, tmp_path / name) for name, source in units.sfc.items()}
    accepted = sum(not f.startswith("iec2c") for f in failures.values())
    tally(
        "MatIEC accepted {accepted}/{files} SFC units of the extension (defaults and -f -l -p), "
        "gcc linked and ran {linked}",
        accepted=accepted,
        linked=list(failures.values()).count(""),
        files=len(failures),
    )
    assert not any(failures.values()), {n: f for n, f in failures.items() if f}


def test_the_extensions_syntax_is_in_the_st(units: ExtensionUnits) -> None:
    insert = units.sfc["InsertPeg"].read_text()
    assert "Hover_height := (LIMIT(0.05, grip + 0.04, 0.15));" in insert  # clamp(…)
    assert "jams := jams + 1;" in insert  # count jams;
    assert "requirement I1: the peg goes 30 mm deep without a jam" in insert
    task = units.sfc["PegInHole"].read_text()
    assert "requirement T2: a missed grasp or a jam ends the task (verified by" in task
