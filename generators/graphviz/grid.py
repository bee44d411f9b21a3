"""A level laid out in pure Python, for when no Graphviz program can draw it.

Plain but always there: the nodes of each compartment in rows by their distance from the
level's entries, compartments side by side inside the frame, arrows as straight lines with
their labels at the middle. The SVG has Graphviz's structure (``g.node``, ``g.edge`` and
``g.cluster`` groups with a ``title`` and the same classes), so pages treat both alike.
"""

from __future__ import annotations

from dataclasses import dataclass
from html import escape

from lightrocks.generators.graphviz.levels import Edge, Level, Node

FONT = 10.0
CHAR = 0.6 * FONT
"""Average width of a character of the label font."""
LINE = 1.3 * FONT
GAP_X, GAP_Y, MARGIN = 40.0, 80.0, 20.0
BEND = 26.0
"""How far an arrow bows to the right of its direction: arrows both ways between two
states do not lie on one another."""
MARKERS = ("start", "end", "initial", "final")


@dataclass
class Box:
    node: Node
    width: float
    height: float
    x: float = 0.0
    """Centre."""
    y: float = 0.0


def svg(level: Level) -> str:
    boxes = {n.id: _box(n) for n in level.nodes}
    groups = ["", *level.regions]
    top = MARGIN + LINE * (2 + len(level.notes))
    left = MARGIN
    compartments: list[tuple[str, float, float, float, float]] = []
    for region in groups:
        members = [boxes[n.id] for n in level.nodes if n.region == region]
        if not members:
            continue
        x0 = left + (MARGIN if region else 0)
        width, height = _place(members, level.edges, x0, top + LINE)
        compartments.append((region, x0 - MARGIN / 2, top, width + MARGIN, height + LINE))
        left = x0 + width + GAP_X
    right = max([left, MARGIN + len(level.title) * CHAR * 1.2]) + MARGIN
    bottom = max([top + MARGIN] + [c[2] + c[4] for c in compartments]) + MARGIN
    parts = [
        f'<svg width="{right:.0f}px" height="{bottom:.0f}px" viewBox="0 0 {right:.0f} '
        f'{bottom:.0f}" xmlns="http://www.w3.org/2000/svg">',
        f'<g id="graph0" class="graph frame"><title>{escape(level.key)}</title>',
        f'<polygon fill="white" stroke="none" points="0,0 {right},0 {right},{bottom} 0,{bottom}"/>',
        _text([level.title, *level.notes], right / 2, MARGIN),
    ]
    for region, x, y, width, height in compartments:
        if region:
            parts.append(_region(region, x, y, width, height))
    parts += [_edge(e, boxes) for e in level.edges if e.source in boxes and e.target in boxes]
    parts += [_node(box) for box in boxes.values()]
    parts.append("</g>\n</svg>\n")
    return "\n".join(parts)


def _box(node: Node) -> Box:
    if node.kind in MARKERS:
        return Box(node, 12.0, 12.0)
    if node.kind in ("choice", "history"):
        return Box(node, 24.0, 24.0)
    longest = max((len(line) for line in node.lines), default=1)
    return Box(node, longest * CHAR + 16, len(node.lines) * LINE + 10)


def _place(members: list[Box], edges: list[Edge], left: float, top: float) -> tuple[float, float]:
    """Rows by the longest path from the entries along forward arrows; the block's size."""
    ids = [b.node.id for b in members]
    order = {i: n for n, i in enumerate(sorted(ids, key=lambda i: _entry_first(members, i)))}
    row = dict.fromkeys(ids, 0)
    for _ in ids:  # relax: at most one pass per node
        for e in edges:
            if e.source in order and e.target in order and order[e.source] < order[e.target]:
                row[e.target] = max(row[e.target], row[e.source] + 1)
    last = max(row.values()) + 1
    for box in members:  # exits at the bottom
        if box.node.kind in ("end", "final"):
            row[box.node.id] = last
    rows: dict[int, list[Box]] = {}
    for box in sorted(members, key=lambda b: order[b.node.id]):
        rows.setdefault(row[box.node.id], []).append(box)
    width = max(sum(b.width for b in r) + GAP_X * (len(r) - 1) for r in rows.values())
    y = top
    for number in sorted(rows):
        line = rows[number]
        height = max(b.height for b in line)
        x = left + (width - sum(b.width for b in line) - GAP_X * (len(line) - 1)) / 2
        for box in line:
            box.x, box.y = x + box.width / 2, y + height / 2
            x += box.width + GAP_X
        y += height + GAP_Y
    return width, y - GAP_Y - top


def _entry_first(members: list[Box], node_id: str) -> tuple[int, int]:
    kinds = {b.node.id: b.node.kind for b in members}
    position = [b.node.id for b in members].index(node_id)
    return (0 if kinds[node_id] in ("start", "initial") else 1, position)


def _text(lines: list[str], x: float, y: float, anchor: str = "middle") -> str:
    return "".join(
        f'<text text-anchor="{anchor}" x="{x:.1f}" y="{y + i * LINE:.1f}" '
        f'font-family="Helvetica,sans-Serif" font-size="{FONT:.0f}">{escape(line)}</text>'
        for i, line in enumerate(lines)
    )


def _region(name: str, x: float, y: float, w: float, h: float) -> str:
    return (
        f'<g class="cluster region"><title>cluster_{escape(name)}</title>'
        f'<polygon fill="none" stroke="black" stroke-dasharray="5,2" points="{x},{y} '
        f'{x + w},{y} {x + w},{y + h} {x},{y + h}"/>{_text([name], x + w / 2, y + LINE)}</g>'
    )


def _node(box: Box) -> str:
    node, x, y = box.node, box.x, box.y
    classes = node.kind + (" drill" if node.drill else "")
    if node.kind in MARKERS:
        ring = node.kind in ("end", "final")
        shape = f'<ellipse fill="black" stroke="black" cx="{x}" cy="{y}" rx="4" ry="4"/>'
        if ring:
            shape += f'<ellipse fill="none" stroke="black" cx="{x}" cy="{y}" rx="7" ry="7"/>'
        label = _text([node.xlabel], x + 10, y + 4, "start") if node.xlabel else ""
    elif node.kind == "choice":
        shape = (
            f'<polygon fill="white" stroke="black" points="{x},{y - 12} {x + 12},{y} '
            f'{x},{y + 12} {x - 12},{y}"/>'
        )
        label = ""
    elif node.kind == "history":
        shape = f'<ellipse fill="white" stroke="black" cx="{x}" cy="{y}" rx="12" ry="12"/>'
        label = _text(node.lines, x, y + 4)
    else:
        w, h = box.width, box.height
        shape = (
            f'<path fill="white" stroke="black" stroke-width="{1.6 if node.drill else 1}" '
            f'd="M{x - w / 2 + 6},{y - h / 2} h{w - 12} a6,6 0 0 1 6,6 v{h - 12} '
            f'a6,6 0 0 1 -6,6 h{-(w - 12)} a6,6 0 0 1 -6,-6 v{-(h - 12)} a6,6 0 0 1 6,-6 z"/>'
        )
        first = y - h / 2 + 5 + FONT
        label = _text(node.lines, x, first)
    return f'<g class="node {classes}"><title>{escape(node.id)}</title>{shape}{label}</g>'


def _edge(edge: Edge, boxes: dict[str, Box]) -> str:
    """A quadratic curve bowed to the right of its direction; a loop on the box's right."""
    source, target = boxes[edge.source], boxes[edge.target]
    if edge.source == edge.target:
        right = source.x + source.width / 2
        x1, y1, x2, y2 = right, source.y - 6, right, source.y + 6
        cx, cy = right + 3 * BEND, source.y
    else:
        x1, y1 = _border(source, target.x, target.y)
        x2, y2 = _border(target, source.x, source.y)
        length = max(((x2 - x1) ** 2 + (y2 - y1) ** 2) ** 0.5, 1e-6)
        cx = (x1 + x2) / 2 - (y2 - y1) / length * BEND
        cy = (y1 + y2) / 2 + (x2 - x1) / length * BEND
    tangent = max(((x2 - cx) ** 2 + (y2 - cy) ** 2) ** 0.5, 1e-6)
    ux, uy = (x2 - cx) / tangent, (y2 - cy) / tangent
    tip = (
        f"{x2:.1f},{y2:.1f} {x2 - 8 * ux - 3 * uy:.1f},{y2 - 8 * uy + 3 * ux:.1f} "
        f"{x2 - 8 * ux + 3 * uy:.1f},{y2 - 8 * uy - 3 * ux:.1f}"
    )
    label = edge.label.split("\n") if edge.label else []
    if edge.head:
        label.append(f"to {edge.head}")
    middle_x, middle_y = (x1 + 2 * cx + x2) / 4, (y1 + 2 * cy + y2) / 4
    text = _text(label, middle_x + 4, middle_y, "start")
    return (
        f'<g class="edge {edge.kind}"><title>{escape(edge.source)}-&gt;{escape(edge.target)}'
        f'</title><path fill="none" stroke="black" d="M{x1:.1f},{y1:.1f} '
        f'Q{cx:.1f},{cy:.1f} {x2:.1f},{y2:.1f}"/>'
        f'<polygon fill="black" stroke="black" points="{tip}"/>{text}</g>'
    )


def _border(box: Box, towards_x: float, towards_y: float) -> tuple[float, float]:
    """Where the line from the box's centre towards a point leaves the box."""
    dx, dy = towards_x - box.x, towards_y - box.y
    if dx == 0 and dy == 0:
        return box.x, box.y
    factor = min(
        (box.width / 2) / abs(dx) if dx else float("inf"),
        (box.height / 2) / abs(dy) if dy else float("inf"),
    )
    return box.x + dx * factor, box.y + dy * factor
