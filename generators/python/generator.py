"""The python target: one module per statechart, a class per statechart and per state.

An ``<<import>>`` state is an instance of the imported statechart's class, an
``<<extends>>`` statechart or state a subclass of the extended class (with the merged tables
of the derived model). Device types become ``typing.Protocol`` classes and cells
``runtime.Cell`` classes in ``_domain.py``. Output is formatted with ruff when it is
installed, and the same models always give the same bytes.
"""

from __future__ import annotations

import shutil
import subprocess
import sys
from functools import partial
from pathlib import Path

import jinja2

from lightrocks.generators.outputs import distinct
from lightrocks.generators.python import expressions as code
from lightrocks.generators.python.builder import Builder
from lightrocks.generators.python.domain import domain_module
from lightrocks.generators.python.expressions import Scope
from lightrocks.generators.python.names import DOMAIN, identifier, module_path
from lightrocks.languages.lightrocks.analysis import analysis
from lightrocks.metamodel import ast
from lightrocks.workbench.extensions import language_extensions, template_name
from lightrocks.workbench.generators import GenerationRequest, template_environment

TEMPLATES = Path(__file__).with_name("templates")


def _render(environment: jinja2.Environment, node: ast.ExtensionNode, scope: Scope) -> str:
    """Python for a statement or expression of a language extension, from its template:
    ``node`` is the AST node, ``code(e)`` compiles a sub-expression and ``target(e)`` an
    assignable one. Model text reaches the code only through those and ``| literal``."""
    template = environment.get_template(template_name("python", node))
    return template.render(
        node=node,
        code=lambda part: code.expression(part, scope),
        target=lambda part: code.target(part, scope),
    ).strip()


def ruff_format(files: dict[str, str]) -> dict[str, str]:
    """Format with ruff (line length 100) when it is installed; otherwise leave as rendered."""
    ruff = Path(sys.executable).with_name("ruff")
    command = str(ruff) if ruff.exists() else shutil.which("ruff")
    if command is None:
        return files
    formatted = {}
    for path, text in files.items():
        result = subprocess.run(
            [command, "format", "--isolated", "--line-length", "100", "--stdin-filename", path],
            input=text,
            capture_output=True,
            text=True,
            check=False,
        )
        formatted[path] = result.stdout if result.returncode == 0 else text
    return formatted


class PythonGenerator:
    name = "python"
    description = "Python modules on the LightRocks state runtime (one per statechart)"
    options = ()

    def generate(self, request: GenerationRequest) -> dict[str, str]:
        folders = [e.templates for e in language_extensions() if e.templates is not None]
        environment = template_environment(TEMPLATES, request.templates, folders)
        environment.filters["literal"] = repr  # model text as a Python literal, never code
        builder = Builder(analysis(request.context).typing, partial(_render, environment))
        modules = {module_path(c.qualified_name): c for c in builder.components}
        distinct(modules)
        exported = [
            {
                "name": c.qualified_name,
                "module": path.removesuffix(".py").replace("/", "."),
                "cls": identifier(c.qualified_name.rpartition(".")[2]),
            }
            for path, c in sorted(modules.items(), key=lambda item: item[1].qualified_name)
        ]
        package = environment.get_template("package.py.jinja").render(components=exported)
        files: dict[str, str] = {"__init__.py": package}
        for path, component in modules.items():
            view = builder.module(component)
            files[path] = environment.get_template("module.py.jinja").render(module=view)
            parts = path.split("/")[:-1]
            for depth in range(1, len(parts) + 1):
                files.setdefault("/".join([*parts[:depth], "__init__.py"]), "")
        domain = domain_module(builder, environment)
        if domain is not None:
            files[f"{DOMAIN}.py"] = domain
        return ruff_format(files)


GENERATOR = PythonGenerator()
