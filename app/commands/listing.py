"""``lightrocks list``: the registered languages, CoCos, generators, conversions, adapters,
scenes or robots."""

from __future__ import annotations

import argparse
from typing import TYPE_CHECKING

from lightrocks.app.commands.common import EXIT_OK, UsageError, all_cocos, command

if TYPE_CHECKING:
    from lightrocks.workbench.generators import Option


def _configure_list(sub: argparse._SubParsersAction) -> None:
    parser = sub.add_parser(
        "list", help="list languages, CoCos, generators, conversions, adapters, scenes or robots"
    )
    parser.add_argument(
        "what",
        choices=("languages", "cocos", "generators", "conversions", "adapters", "scenes", "robots"),
    )


def _option_row(option: Option) -> tuple[str, ...]:
    """A generator's option, under the generator: how to give it, its type and what it does."""
    default = f", default {option.default}" if option.default != "" else ""
    return (f"    --option {option.name}: {option.kind}{default}; {option.doc}",)


@command(_configure_list)
def cmd_list(args: argparse.Namespace) -> int:
    from importlib.metadata import entry_points

    from lightrocks.app.robots import registered
    from lightrocks.workbench.conversions import ConversionError, conversions
    from lightrocks.workbench.extensions import language_extensions
    from lightrocks.workbench.generators import declared_options as generator_options
    from lightrocks.workbench.generators import load_generator
    from lightrocks.workbench.languages import languages

    if args.what == "languages":
        rows = [(lang.name, " ".join(lang.extensions), lang.description) for lang in languages()]
        rows += [(e.name, f"extends {e.extends}", e.description) for e in language_extensions()]
    elif args.what == "cocos":
        rows = [(c.code, c.severity.value, c.summary) for c in all_cocos()]
    elif args.what == "generators":
        rows = []
        for e in sorted(entry_points(group="lightrocks.generators"), key=str):
            generator = load_generator(e.name)
            rows.append((e.name, e.value, generator.description))
            rows += [_option_row(option) for option in generator_options(generator)]
    elif args.what == "conversions":
        try:
            found = conversions()
        except ConversionError as error:
            raise UsageError(str(error)) from None
        rows = [(c.name, f"{c.source} -> .{c.target}", c.description) for c in found]
    elif args.what == "adapters":
        from lightrocks.app.adapter_factory import declared_options

        rows = []
        for e in sorted(entry_points(group="lightrocks.adapters"), key=str):
            rows.append((e.name, e.value, ""))
            rows += [(f"  {o.name}", o.doc, "") for o in declared_options(e.name).values()]
    elif args.what == "robots":
        rows = [(n, r.device_type, r.description) for n, r in sorted(registered().items())]
    else:
        group = f"lightrocks.{args.what}"
        rows = [(e.name, e.value, "") for e in sorted(entry_points(group=group), key=str)]
    for row in rows:
        print("  ".join(part for part in row if part))
    return EXIT_OK
