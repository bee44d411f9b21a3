"""``generate --target dot --option levels=yes`` from the command line, and the page's
document of a diagram: markup in a model's text stays text."""

from __future__ import annotations

import json
import xml.etree.ElementTree as ElementTree
from pathlib import Path

from diagram.models import EXAMPLES
from lightrocks.app.cli import main
from lightrocks.app.diagram import drawn

AHEAD = EXAMPLES / "din_rail_ahead" / "tasks" / "AssembleRailAhead.lr"


def test_the_command_line_writes_every_level_and_its_index(tmp_path: Path, capsys) -> None:
    args = ["generate", str(AHEAD), "--path", str(EXAMPLES), "--target", "dot"]
    assert main([*args, "--option", "levels=yes", "-o", str(tmp_path)]) == 0
    folder = tmp_path / "din_rail_ahead.tasks.AssembleRailAhead"
    index = json.loads((folder / "levels.json").read_text())
    assert index["root"] == "din_rail_ahead.tasks.AssembleRailAhead"
    files = {level["file"] for level in index["levels"]}
    assert "din_rail_ahead.tasks.PlugTerminalAhead/PressOn.svg" in files
    for name in files:
        assert (folder / name).is_file() and (folder / name).with_suffix(".dot").is_file()
    assert main([*args, "--option", "levels=no", "-o", str(tmp_path / "no")]) == 1
    assert "the only value is 'yes'" in capsys.readouterr().err


def test_markup_in_a_model_stays_text_in_the_pages_document(tmp_path: Path) -> None:
    model = tmp_path / "Marked.lr"
    model.write_text(
        'statechart Marked {\n  <<note="</metadata><svg onload=alert(1)>">> initial state A;\n'
        "  final state B;\n  A -> B [1 < 2] go;\n}\n"
    )
    bundle = drawn(model, [tmp_path]).bundle()
    root = ElementTree.fromstring(bundle)  # one well-formed document
    svg = "{http://www.w3.org/2000/svg}"
    assert [e.tag for e in root] == [f"{svg}metadata", f"{svg}svg"]
    assert not [e for e in root.iter() if "onload" in e.attrib]
    texts = "".join(root.itertext())
    assert '«note="</metadata><svg onload=alert(1)>"»' in texts
    assert "go [1 < 2]" in texts
