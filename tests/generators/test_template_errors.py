"""A template that fails names its file and line (a usage error: exit 2); nothing is written
and no traceback."""

from __future__ import annotations

from pathlib import Path

import pytest

from lightrocks.app.cli import main

TURNSTILE = Path(__file__).resolve().parents[2] / "examples" / "plain" / "Turnstile.lr"

HEADER = '{% extends "builtin/module.py.jinja" %}\n{% block header %}\n{0}\n{% endblock %}\n'


@pytest.mark.parametrize(
    ("body", "message"),
    [
        ('"""{{ module.nothing }}"""', "module.py.jinja:3: "),
        ("{% if %}", "module.py.jinja:3: Expected an expression"),
        ('{% include "missing.jinja" %}', "template 'missing.jinja' not found"),
    ],
)
def test_template_errors_name_the_place(
    body: str, message: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    templates = tmp_path / "templates"
    templates.mkdir()
    (templates / "module.py.jinja").write_text(HEADER.replace("{0}", body))
    out = tmp_path / "out"
    status = main(
        ["generate", str(TURNSTILE), "--target", "python", "-o", str(out),
         "--templates", str(templates)]
    )  # fmt: skip
    output = "".join(capsys.readouterr())
    assert status == 2
    assert message in output
    assert "internal error" not in output and "Traceback" not in output
    assert not out.exists()


def test_an_override_extends_the_builtin_template(tmp_path: Path) -> None:
    templates = tmp_path / "templates"
    templates.mkdir()
    (templates / "module.py.jinja").write_text(HEADER.replace("{0}", '"""Ours."""'))
    assert main(["generate", str(TURNSTILE), "--target", "python", "-o", str(tmp_path / "o"),
                 "--templates", str(templates)]) == 0  # fmt: skip
    code = (tmp_path / "o" / "plain" / "Turnstile.py").read_text()
    assert code.startswith('"""Ours."""\n')
    assert "class Turnstile(rt.CompositeComponent):" in code
