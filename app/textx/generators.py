"""textX generator registrations, so that ``textx generate model.lr --target sfc|dot`` works.

textX hands over one parsed file; the workbench checks it with its model path (its package
root, ``--path DIR`` and ``LIGHTROCKS_PATH``) and runs the LightRocks generator of the same
name, writing next to the model or to ``output_path``. Every problem is a ``TextXError``,
which textX reports in one line with exit code 1. Options a generator does not take
(``--render`` for ``sfc``) are refused by textX from the parameters declared here.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from textx import TextXError, generator
from textx.registration import GeneratorParam

from lightrocks.app import pipeline
from lightrocks.app.errors import ModelError
from lightrocks.app.specs import generate_spec
from lightrocks.app.textx.check import model_path
from lightrocks.workbench.generators import GenerationError, write_all

PATH = GeneratorParam("path", "model-path folders of imported packages", mandatory=False)
RENDER = GeneratorParam("render", "also draw each .dot file: svg or png", mandatory=False)
DEPTH = GeneratorParam("depth", "draw imported statecharts N levels deep", mandatory=False)


def _run(target: str, model: Any, output_path: str | None, options: dict[str, Any]) -> None:
    file = Path(model._tx_filename).resolve()
    search_path = model_path(str(options.pop("path", "")))
    output = Path(output_path) if output_path else file.parent
    try:
        spec = generate_spec([file], search_path, target, {k: str(v) for k, v in options.items()})
        write_all(output, pipeline.generate(spec))
    except (ModelError, GenerationError) as error:
        raise TextXError(str(error)) from None


@generator("lightrocks", "sfc", [PATH])
def sfc_generator(metamodel, model, output_path, overwrite, debug, **custom_args):
    """IEC 61131-3 textual SFC of a LightRocks task or skill."""
    _run("sfc", model, output_path, custom_args)


@generator("lightrocks", "dot", [PATH, RENDER, DEPTH])
def dot_generator(metamodel, model, output_path, overwrite, debug, **custom_args):
    """Graphviz DOT of a LightRocks statechart (``--render svg|png``, ``--depth N``)."""
    _run("dot", model, output_path, custom_args)
