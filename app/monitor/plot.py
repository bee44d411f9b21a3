"""Plots of a recorded trace: force, torque and TCP over time, the spans of skills and
actions shaded, the outcome marked; a PNG, or one HTML file with the figure inlined as SVG."""

from __future__ import annotations

import html
import io
import json
import math
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from lightrocks.app.monitor.traces import read_trace
from lightrocks.workbench.report import printable

FORMATS = (".png", ".html")
LAYERS = ("skill", "action")
LABELS = 40
RESOLUTION = 4000
"""Bands are drawn to 1/4000 of the plotted time, a quarter of a pixel."""
"""A skill is named on top when it spans at least 1/40 of the plotted time."""
SIZE, DPI = (11, 8), 100
"""The figure in inches and the PNG's pixels per inch: 1100 x 800 pixels."""


@dataclass
class Span:
    name: str
    layer: str
    start: float
    end: float


@dataclass
class Recording:
    """What a plot shows, read off the trace."""

    times: list[float] = field(default_factory=list)
    force: list[list[float]] = field(default_factory=list)
    torque: list[list[float]] = field(default_factory=list)
    tcp: list[list[float]] = field(default_factory=list)
    spans: list[Span] = field(default_factory=list)
    outcome: str | None = None
    end: float = 0.0


def recording(records: list[dict[str, Any]]) -> Recording:
    result = Recording()
    entered: dict[str, tuple[str, float]] = {}
    for record in records:
        time, kind = float(record["time"]), record["kind"]
        result.end = max(result.end, time)
        if kind == "sample":
            wrench = next((v for k, v in record.items() if k.endswith(".wrench")), None)
            tcp = next((v for k, v in record.items() if k.endswith(".tcp")), None)
            if wrench is not None and tcp is not None:
                result.times.append(time)
                result.force.append([float(v) for v in wrench["force"]])
                result.torque.append([float(v) for v in wrench["torque"]])
                result.tcp.append([float(v) for v in tcp])
        elif kind == "enter" and record.get("layer") in LAYERS:
            entered[record["state"]] = (record["layer"], time)
        elif kind == "exit" and record["state"] in entered:
            layer, start = entered.pop(record["state"])
            result.spans.append(Span(record["state"], layer, start, time))
        elif kind == "finished":
            result.outcome = record.get("outcome")
    for state, (layer, start) in entered.items():
        result.spans.append(Span(state, layer, start, result.end))
    return result


def figure(rec: Recording, title: str) -> Any:
    """The figure: one row each for force, torque and TCP, sharing the time axis. Text from
    the trace is drawn neutralised: a control character has no glyph, and matplotlib's
    warning about it would echo the character to the terminal."""
    import matplotlib

    matplotlib.use("Agg")
    from matplotlib.figure import Figure

    fig = Figure(figsize=SIZE, layout="constrained")
    axes = fig.subplots(3, 1, sharex=True)
    rows = (
        ("force [N]", rec.force, 1.0),
        ("torque [Nm]", rec.torque, 1.0),
        ("TCP [mm]", rec.tcp, 1000.0),
    )
    colours = matplotlib.colormaps["tab10"]
    skills = [s for s in rec.spans if s.layer == "skill"]
    actions = [s for s in rec.spans if s.layer == "action"]
    start = min([*rec.times[:1], *(s.start for s in rec.spans), rec.end])
    resolution = max(rec.end - start, 1e-9) / RESOLUTION
    for ax, (label, values, scale) in zip(axes, rows, strict=True):
        _bands(ax, skills, (0.0, 1.0), [colours(i) for i in range(10)], 0.12, resolution)
        _bands(ax, actions, (0.0, 0.04), ["0.3", "0.65"], 1.0, resolution)
        for axis, name in enumerate("xyz"):
            ax.plot(rec.times, [v[axis] * scale for v in values], lw=1, label=name)
        ax.set_ylabel(label)
        ax.grid(alpha=0.3)
        ax.legend(loc="upper right", fontsize="small")
        if rec.outcome is not None:
            ax.axvline(rec.end, color="k", ls="--", lw=1)
    if rec.end > start:
        axes[0].set_xlim(start, rec.end)
    for i, span in _labelled(skills, rec.end - start):
        axes[0].annotate(
            printable(span.name.rsplit("/", 1)[-1]),
            ((span.start + span.end) / 2, 1.0),
            xycoords=("data", "axes fraction"),
            ha="center",
            va="bottom",
            fontsize="small",
            color=colours(i % 10),
        )
    if rec.outcome is not None:
        axes[2].annotate(
            f"outcome: {printable(str(rec.outcome))}",
            (rec.end, 0.02),
            xycoords=("data", "axes fraction"),
            ha="right",
            va="bottom",
            fontsize="small",
        )
    axes[-1].set_xlabel("simulated time [s]")
    fig.suptitle(printable(title))
    return fig


def _bands(
    ax: Any,
    spans: list[Span],
    rows: tuple[float, float],
    colours: list,
    alpha: float,
    resolution: float,
) -> None:
    """The spans as bands over the axis' height fraction ``rows``, coloured in turn: one
    path per colour however many spans there are, bands closer than ``resolution`` merged,
    so a long trace costs time in proportion to its length. In an SVG the bands are a
    picture (the curves stay lines)."""
    import numpy as np
    from matplotlib.patches import PathPatch
    from matplotlib.path import Path as Outline

    low, high = rows
    corners = [[0.0, low], [0.0, high], [0.0, high], [0.0, low], [0.0, low]]
    steps = [Outline.MOVETO, Outline.LINETO, Outline.LINETO, Outline.LINETO, Outline.CLOSEPOLY]
    for turn, colour in enumerate(colours):
        chosen = _merged(spans[turn :: len(colours)], resolution)
        if not chosen:
            continue
        vertices = np.tile(np.array(corners), (len(chosen), 1, 1))
        vertices[:, :2, 0] = np.array([start for start, _ in chosen])[:, None]
        vertices[:, 2:4, 0] = np.array([end for _, end in chosen])[:, None]
        vertices[:, 4, 0] = vertices[:, 0, 0]
        outline = Outline(vertices.reshape(-1, 2), np.tile(steps, len(chosen)))
        band = PathPatch(outline, facecolor=colour, alpha=alpha, lw=0)
        band.set_transform(ax.get_xaxis_transform())
        band.set_rasterized(True)
        ax.add_artist(band)


def _merged(spans: list[Span], resolution: float) -> list[tuple[float, float]]:
    """The spans as intervals snapped outwards to multiples of ``resolution`` (a fraction
    of a pixel), overlapping or touching ones merged: what the picture can show apart."""
    snapped = sorted(
        (math.floor(s.start / resolution) * resolution, math.ceil(s.end / resolution) * resolution)
        for s in spans
    )
    merged: list[tuple[float, float]] = []
    for start, end in snapped:
        if merged and start <= merged[-1][1]:
            merged[-1] = (merged[-1][0], max(merged[-1][1], end))
        else:
            merged.append((start, end))
    return merged


def _labelled(skills: list[Span], duration: float) -> list[tuple[int, Span]]:
    """The skills wide enough to carry their name (at most ``LABELS`` of them), with their
    number for the colour."""
    wide = [(i, s) for i, s in enumerate(skills) if s.end - s.start >= duration / LABELS]
    return wide[: 2 * LABELS]


def series(rec: Recording) -> str:
    """The plotted samples as JSON, safe inside a script element, for whoever reads on; a
    number that is not finite is null, as JSON has none."""

    def finite(rows: list[list[float]]) -> list[list[float | None]]:
        return [[v if math.isfinite(v) else None for v in row] for row in rows]

    data = {
        "time": rec.times,
        "force": finite(rec.force),
        "torque": finite(rec.torque),
        "tcp": finite(rec.tcp),
    }
    return json.dumps(data, separators=(",", ":"), allow_nan=False).replace("</", "<\\/")


def page(rec: Recording, title: str, svg: str) -> str:
    """One HTML file: the figure inline, its samples as data and the spans as a table;
    nothing is fetched."""
    rows = "\n".join(
        f"<tr><td>{html.escape(s.layer)}</td><td>{html.escape(s.name)}</td>"
        f"<td>{s.start:.3f}</td><td>{s.end:.3f}</td></tr>"
        for s in rec.spans
    )
    outcome = html.escape(rec.outcome or "unfinished")
    return f"""<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><title>{html.escape(title)}</title>
<style>body{{font-family:sans-serif;margin:1em}}table{{border-collapse:collapse}}
td,th{{border:1px solid #ccc;padding:2px 8px;text-align:left}}</style></head>
<body><h1>{html.escape(title)}</h1>
<p>Outcome: <strong id="outcome">{outcome}</strong> at {rec.end:.3f} s;
{len(rec.times)} samples.</p>
{svg}
<script type="application/json" id="series">{series(rec)}</script>
<table id="spans"><tr><th>layer</th><th>state</th><th>from [s]</th><th>to [s]</th></tr>
{rows}
</table></body></html>
"""


def plot(trace: Path, output: Path, note: Callable[[str], None] = lambda _: None) -> Recording:
    """Write the plot of ``trace`` to ``output`` (PNG or HTML, by its suffix); ``note`` hears
    of a last line cut off."""
    from lightrocks.workbench.files import write_atomic

    rec = recording(read_trace(trace, note))
    title = f"{trace.name}: outcome {rec.outcome or 'unfinished'}"
    fig = figure(rec, title)
    buffer = io.BytesIO() if output.suffix == ".png" else io.StringIO()
    fig.savefig(buffer, format=output.suffix[1:] if output.suffix == ".png" else "svg", dpi=DPI)
    if output.suffix == ".png":
        tmp = output.with_name(f".{output.name}.tmp")
        tmp.write_bytes(buffer.getvalue())
        tmp.replace(output)
    else:
        svg = buffer.getvalue()
        write_atomic(output, page(rec, title, svg[svg.index("<svg") :]))
    return rec
