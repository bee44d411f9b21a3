"""MatIEC as the judge of the SFC target: compile, link, and step a unit against a script.

MatIEC (the Beremiz project's IEC 61131-3 compiler) is found through ``MATIEC=<dir>``, in the
judges' folder that ``make judges`` fills, or at ``/opt/matiec``: ``<dir>/iec2c`` and
``<dir>/lib``. Every file is compiled twice: with MatIEC's defaults and with the options
Beremiz's build passes (``-f -l -p``), under which the names of MatIEC's standard library are
in scope of the user's POUs. The step harness writes a C driver that
emulates the devices of the cell exactly as the Python dry run does (a command settles after
``SETTLE_CYCLES`` scans, or faults, or never ends; sensor values can be pinned), runs the
compiled program scan by scan, and prints every step that becomes active.
"""

from __future__ import annotations

import functools
import os
import re
import resource
import subprocess
from dataclasses import dataclass, field
from pathlib import Path

from judges import JUDGES

from lightrocks.adapters.dryrun import DryRunAdapter
from lightrocks.app.loading import load_component
from lightrocks.app.run import drive
from lightrocks.app.values import parse_delay
from lightrocks.generators.sfc_iec61131 import build_unit
from lightrocks.generators.sfc_iec61131.ir import Block, Unit
from lightrocks.languages.lightrocks.analysis import analysis
from lightrocks.workbench.check import check

PLACES = (JUDGES / "matiec", Path("/opt/matiec"))
BEREMIZ_OPTIONS = ("-f", "-l", "-p")
"""What Beremiz's build passes to iec2c (ProjectController's iec2c_cfg)."""
CYCLE_MS = 1
SETTLE_CYCLES = 100  # the dry run's 0.1 s command duration at 1 ms per scan
MEMORY_LIMIT = 2 << 30


def matiec_home() -> Path | None:
    given = os.environ.get("MATIEC")
    places = [Path(given)] if given else PLACES
    return next((h for h in places if (h / "iec2c").is_file() and (h / "lib").is_dir()), None)


@functools.cache
def beremiz_options(home: Path) -> tuple[str, ...]:
    """Those of Beremiz's options that this iec2c lists in its help."""
    shown = subprocess.run([str(home / "iec2c"), "-h"], capture_output=True, text=True).stdout
    listed = set(re.findall(r"^ (-\w) :", shown, flags=re.MULTILINE))
    return tuple(o for o in BEREMIZ_OPTIONS if o in listed)


def _limited() -> None:
    resource.setrlimit(resource.RLIMIT_AS, (MEMORY_LIMIT, MEMORY_LIMIT))


def iec2c(home: Path, source: Path, out: Path) -> subprocess.CompletedProcess:
    """Compile one ST file into ``out`` with MatIEC's defaults and, into ``out/beremiz``, with
    Beremiz's options: the first run that fails (its output says which), else the first."""
    default = _compile(home, (), source, out)
    if default.returncode != 0:
        return default
    beremiz = _compile(home, beremiz_options(home), source, out / "beremiz")
    return beremiz if beremiz.returncode != 0 else default


def _compile(
    home: Path, options: tuple[str, ...], source: Path, out: Path
) -> subprocess.CompletedProcess:
    """One iec2c run; MatIEC loops on some malformed input, hence time and memory caps."""
    out.mkdir(parents=True, exist_ok=True)
    command = [str(home / "iec2c"), *options, "-I", str(home / "lib"), "-T", str(out), str(source)]
    done = subprocess.run(
        command, capture_output=True, text=True, timeout=120, preexec_fn=_limited, check=False
    )
    done.stdout = f"iec2c {' '.join(options) or 'without options'}: {done.stdout}"
    return done


def _gcc(home: Path, out: Path) -> list[str]:
    return ["gcc", "-w", "-O0", "-I", str(home / "lib" / "C"), "-I", str(out)]


def compile_c(home: Path, out: Path) -> subprocess.CompletedProcess | list[str]:
    """Compile MatIEC's C in ``out`` once (an object beside each file): the objects, or the
    failed compilation."""
    objects = []
    for source in sorted(out.glob("*.c")):
        if source.name in ("POUS.c", "driver.c"):
            continue
        compiled = source.with_suffix(".o")
        if not compiled.exists():
            done = subprocess.run(
                [*_gcc(home, out), "-c", str(source), "-o", str(compiled)],
                capture_output=True, text=True, timeout=300, check=False,
            )  # fmt: skip
            if done.returncode != 0:
                return done
        objects.append(str(compiled))
    return objects


def gcc(home: Path, out: Path, driver: str, exe: Path) -> subprocess.CompletedProcess:
    """Compile and link MatIEC's C with a driver (``main``) into ``exe``. MatIEC's C is
    compiled once per folder (:func:`compile_c`), so that several drivers link against it
    cheaply; the driver is written beside ``exe``, so that programs in folders of their own
    link against one compiled folder at once."""
    objects = compile_c(home, out)
    if isinstance(objects, subprocess.CompletedProcess):
        return objects
    (exe.parent / "driver.c").write_text(driver)
    command = [*_gcc(home, out), str(exe.parent / "driver.c"), *objects, "-lm", "-o", str(exe)]
    return subprocess.run(command, capture_output=True, text=True, timeout=300, check=False)


@dataclass
class Scenario:
    """Scripted device behaviour shared by the dry run and the compiled program.

    ``commands`` scripts each call of a command: None settles normally, ``"error"`` faults,
    ``"timeout"`` never ends; ``sensors`` pins boolean or numeric sensors; ``events`` are sent
    one by one once the chart rests, and an item ``+500ms`` lets that much time pass (a
    script with such items runs a plain chart on the virtual clock, without adapter).
    """

    name: str
    model: Path
    commands: dict[str, list[str | None]] = field(default_factory=dict)
    sensors: dict[str, bool | float] = field(default_factory=dict)
    events: list[str] = field(default_factory=list)


Event = tuple[str, ...]


def steps(events: list[str]) -> list[str | float]:
    """Events and ``+500ms`` clock advances as a run takes them."""
    return [parse_delay(e) if e.startswith("+") else e for e in events]


def sfc_unit(model: Path, search: list[Path]) -> Unit:
    """The SFC unit of ``model``: what the driver emulates and the traces are compared on."""
    context = check([model], search)
    result = analysis(context)
    top = next(c for c in result.models.components if c.loaded.path == model.resolve())
    return build_unit(top, result.typing)


def python_trace(scenario: Scenario, search: list[Path]) -> list[Event]:
    cls = load_component(scenario.model, search)
    timed = any(e.startswith("+") for e in scenario.events)
    adapter = None if timed else DryRunAdapter(outcomes=scenario.commands, sensors=scenario.sensors)
    chart = drive(cls, {}, adapter, steps(scenario.events), None)
    events: list[Event] = []
    for record in chart.trace:
        if record["kind"] == "enter":
            events.append(("enter", record["state"]))
        elif record["kind"] == "outcome" and record["outcome"] != "preempted":
            events.append(("outcome", record["state"], record["outcome"]))
    return events


def comparable(events: list[Event], unit: Unit) -> list[Event]:
    """The events the compiled program can show: entered leaves and instances; outcomes of
    actions (settle steps) and of components (exit steps)."""
    tree = _tree(unit)
    instances = {path for _, path, _ in tree}
    entered = instances | {
        f"{path}/{state}" for _, path, b in tree for state, outcome in b.states.values() if state
    }
    ended = instances | {
        f"{path}/{state}" for _, path, b in tree for state, outcome in b.states.values() if outcome
    }
    return [e for e in events if e[1] in (entered if e[0] == "enter" else ended)]


def streams(events: list[Event], unit: Unit) -> dict[str, list[Event]]:
    """The events of each orthogonal region apart, and the others: regions run side by side,
    so only the order within one stream is the same on every target."""
    prefixes = [f"{path}/{region}" for _, path, b in _tree(unit) for region in b.regions]
    split: dict[str, list[Event]] = {}
    for event in events:
        inside = [p for p in prefixes if event[1] == p or event[1].startswith(f"{p}/")]
        split.setdefault(max(inside, key=len, default=""), []).append(event)
    return split


def _tree(unit: Unit) -> list[tuple[str, str, Block]]:
    """(C expression, LightRocks path, block) of every block instance of the program."""
    blocks = {b.name: b for b in unit.blocks}
    top = unit.program.locals[0]
    found = []

    def visit(expression: str, path: str, block: Block) -> None:
        found.append((expression, path, block))
        for local in block.locals:
            if local.type in blocks:
                hosted = block.instances[local.name]
                visit(f"{expression}.{local.name.upper()}", f"{path}/{hosted}", blocks[local.type])

    visit(f"{unit.resource.upper()}__{unit.instance.upper()}.{top.name.upper()}", unit.top.name,
          blocks[top.type])  # fmt: skip
    return found


def driver_source(unit: Unit, scenario: Scenario, max_cycles: int) -> str:
    """A C ``main`` that emulates the cell's devices and prints every step activation.

    A script that lets time pass (``+500ms``) runs on a virtual clock, as the Python side
    does: time stands still while the program reacts and advances one cycle at a time only
    while a script item lets it pass and the program has rested for a few scans, so every
    reaction to an event or a deadline happens at one instant of that clock. Other scripts
    run on a clock that advances one cycle per scan."""
    tree = _tree(unit)
    cell = unit.configuration.upper()
    devices = {b.name: b for b in unit.devices}
    lines = [
        '#include "iec_std_lib.h"',
        '#include "accessor.h"',
        '#include "POUS.h"',
        "#include <stdio.h>",
        "TIME __CURRENT_TIME;",
        "BOOL __DEBUG;",
        "void config_init__(void);",
        "void config_run__(unsigned long tick);",
        f"extern {unit.program.name.upper()} {unit.resource.upper()}__{unit.instance.upper()};",
    ]
    emulate: list[str] = []
    calls = 0
    variables = {v.name: v for v in unit.globals}
    for name, global_name in unit.cell.items():
        member = variables[global_name]
        if member.type not in devices:
            continue
        block = devices[member.type]
        device = f"{cell}__{member.name.upper()}"
        lines.append(f"extern {block.name.upper()} {device};")
        for command, (flag, _, result) in block.commands.items():
            key = f"{name}.{command}"
            script = scenario.commands.get(key, [])
            codes = [{None: 0, "error": 1, "timeout": 2}[s] for s in script] or [0]
            lines.append(f"static int script{calls}[] = {{{', '.join(map(str, codes))}}};")
            lines.append(f"static int count{calls}, prev{calls}, left{calls}, mode{calls};")
            get = f"{device}.{flag.upper()}.value"
            status = [f"{device}.{block.members[s].upper()}.value = 0;" for s in ("done", "error")]
            status.append(f"{device}.{block.members['busy'].upper()}.value = 1;")
            if "goalReached" in block.members:
                status.append(f"{device}.{block.members['goalReached'].upper()}.value = 0;")
            settle = [f"{device}.{block.members['done'].upper()}.value = 1;"]
            if "goalReached" in block.members:
                settle.append(f"{device}.{block.members['goalReached'].upper()}.value = 1;")
            settle += _effects(block, device, command, result)
            emulate += [
                f"if ({get} && !prev{calls}) {{",
                f"  mode{calls} = count{calls} < {len(codes)} ? script{calls}[count{calls}] : 0;",
                f"  count{calls}++; left{calls} = {SETTLE_CYCLES};",
                *(f"  {s}" for s in status),
                f"  if (mode{calls} == 1) {device}.{block.members['error'].upper()}.value = 1;",
                "}",
                f"if ({get} && mode{calls} == 0 && left{calls} > 0 && --left{calls} == 0) {{",
                *(f"  {s}" for s in settle),
                "}",
                f"if (!{get} && prev{calls}) {device}.{block.members['busy'].upper()}.value = 0;",
                f"prev{calls} = {get};",
            ]
            calls += 1
    for key, value in scenario.sensors.items():
        instance, _, sensor = key.partition(".")
        member = variables[unit.cell[instance]]
        block = devices[member.type]
        number = int(value) if isinstance(value, bool) else value
        target = f"{cell}__{member.name.upper()}.{block.members[sensor].upper()}"
        emulate.append(f"{target}.value = {number};")
    program = f"{unit.resource.upper()}__{unit.instance.upper()}"
    start = unit.program.inputs[0].name.upper()
    event_inputs = {v.comment.removeprefix("event "): v.name for v in unit.program.inputs[1:]}
    inputs = list(event_inputs.values())
    kinds, waits = [], []  # per item: an event input's index, or -1 and the scans to wait
    timed = any(item.startswith("+") for item in scenario.events)
    for item in scenario.events:
        if item.startswith("+"):
            kinds.append(-1)
            waits.append(round(parse_delay(item) * 1000 / CYCLE_MS))
        elif item in event_inputs:
            kinds.append(inputs.index(event_inputs[item]))
            waits.append(0)
    lines += [
        f"static STEP *steps[] = {{{', '.join(f'{e}.__step_list' for e, _, _ in tree)}}};",
        f"static int counts[] = {{{', '.join(str(len(b.steps)) for _, _, b in tree)}}};",
        "static BOOL seen[64][256];",
        "static void emulate(void) {",
        *(f"  {line}" for line in emulate),
        "}",
        "static int report(unsigned long cycle) {",
        "  int changed = 0;",
        f"  for (int b = 0; b < {len(tree)}; b++)",
        "    for (int i = 0; i < counts[b]; i++) {",
        "      BOOL now = steps[b][i].X.value;",
        '      if (now && !seen[b][i]) { printf("%lu %d %d\\n", cycle, b, i); changed = 1; }',
        "      seen[b][i] = now;",
        "    }",
        "  return changed;",
        "}",
        "int main(void) {",
        f"  const int kinds[] = {{{', '.join(map(str, kinds or [0]))}}};",
        f"  const long waits[] = {{{', '.join(map(str, waits or [0]))}}};",
        f"  int pending = {len(kinds)}, sent = 0, quiet = 0, virtual_clock = {int(timed)};",
        "  long waiting = 0;",
        "  config_init__();",
        f"  {program}.{start}.value = 1;",
        f"  for (unsigned long cycle = 0; cycle < {max_cycles}; cycle++) {{",
        "    emulate();",
        *(f"    {program}.{name.upper()}.value = 0;" for name in inputs),
        "    int tick = !virtual_clock;",
        "    if (sent < pending && (waiting > 0 || quiet > 5)) {",
        "      if (kinds[sent] < 0) {",
        "        if (waiting == 0) waiting = waits[sent];",
        "        if (virtual_clock && quiet > 5) { tick = 1; quiet = 0; }",
        "        if (tick && --waiting <= 0) { waiting = 0; sent++; quiet = 0; }",
        "      } else {",
        *(
            f"        if (kinds[sent] == {index}) {program}.{name.upper()}.value = 1;"
            for index, name in enumerate(inputs)
        ),
        "        sent++; quiet = 0;",
        "      }",
        "    }",
        "    config_run__(cycle);",
        "    if (tick) {",
        f"      __CURRENT_TIME.tv_nsec += {CYCLE_MS * 1_000_000};",
        "      if (__CURRENT_TIME.tv_nsec >= 1000000000) {",
        "        __CURRENT_TIME.tv_sec++; __CURRENT_TIME.tv_nsec -= 1000000000; }",
        "    }",
        "    quiet = report(cycle) ? 0 : quiet + 1;",
        f"    if (sent == pending && {tree[0][0]}.{unit.blocks[-1].outcomes['done'].upper()}.value",
        "        && quiet > 5) break;",
        "    if (sent == pending && pending > 0 && quiet > 50) break;",
        "  }",
        "  return 0;",
        "}",
    ]
    return "\n".join(["#include <string.h>", *lines]) + "\n"


def _effects(block: Block, device: str, command: str, result: str) -> list[str]:
    """The idealised end state of a command, as the dry run's ``_settle`` has it."""
    member = block.members.get
    effects = []
    if command == "moveCartesian" and member("tcp"):
        goal = f"{device}.{block.commands[command][1]['goal'].upper()}.value"
        tcp = f"{device}.{member('tcp').upper()}.value"
        if member("travel"):
            travel = f"{device}.{member('travel').upper()}.value"
            effects += [f"{travel}.{a} = {goal}.{a} - {tcp}.{a};" for a in "XYZ"]
        effects.append(f"{tcp} = {goal};")
    elif command in ("close", "open") and member("holding"):
        effects.append(f"{device}.{member('holding').upper()}.value = {int(command == 'close')};")
    if command == "localize" and result:
        frame = f"{device}.{result.upper()}.value"
        effects += [
            f"{frame}.{a} = 0;" for a in ("X", "Y", "Z", "XY", "XZ", "YX", "YZ", "ZX", "ZY")
        ]
        effects += [f"{frame}.{a} = 1;" for a in ("XX", "YY", "ZZ")]
    return effects


def sfc_trace(exe: Path, unit: Unit) -> list[Event]:
    """Run the compiled program and read its step activations as run-time events."""
    output = subprocess.run(
        [str(exe)], capture_output=True, text=True, timeout=300, check=True
    ).stdout
    tree = _tree(unit)
    by_cycle: dict[int, list[tuple[int, Event]]] = {-1: [(0, ("enter", unit.top.name))]}
    for row in output.splitlines():
        cycle, b, i = map(int, row.split())
        _, path, block = tree[b]
        step = block.steps[i].name
        if step not in block.states:
            continue
        state, outcome = block.states[step]
        where = f"{path}/{state}" if state else path
        event: Event = ("outcome", where, outcome) if outcome else ("enter", where)
        by_cycle.setdefault(cycle, []).append((where.count("/"), event))
    events: list[Event] = []
    for cycle in sorted(by_cycle):
        entered = [e for d, e in sorted(by_cycle[cycle], key=lambda x: x[0]) if e[0] == "enter"]
        ended = [e for d, e in sorted(by_cycle[cycle], key=lambda x: -x[0]) if e[0] == "outcome"]
        events += ended + entered
    return events
