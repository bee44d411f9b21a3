"""Every registered adapter declares the options its constructor takes, so that the front
doors offer and check them without reading signatures."""

from __future__ import annotations

import inspect
from importlib.metadata import entry_points

import pytest

from lightrocks.app.adapter_factory import adapter_factory, adapter_options
from lightrocks.app.errors import RunError

ADAPTERS = sorted(e.name for e in entry_points(group="lightrocks.adapters"))


@pytest.mark.parametrize("name", ADAPTERS)
def test_the_declared_options_are_the_constructors_keywords(name: str) -> None:
    cls = adapter_factory(name)
    keywords = set(inspect.signature(cls).parameters) - {"scene"}
    declared = [option.name for option in cls.OPTIONS]
    assert len(declared) == len(set(declared))
    assert set(declared) == keywords
    assert all(option.doc for option in cls.OPTIONS)


def test_an_option_the_adapter_does_not_declare_is_refused_naming_those_that_do() -> None:
    with pytest.raises(RunError, match="adapter 'dryrun' has no option video_fps"):
        adapter_options("dryrun", video_fps=30)
    with pytest.raises(RunError, match=r"adapter 'mujoco': video must be str, got 3"):
        adapter_options("mujoco", video=3)


def test_options_not_chosen_are_left_to_the_adapters_defaults() -> None:
    assert adapter_options("mujoco", noise=(0.0, 0.0), video=None, robot=None) == {}
    assert adapter_options("mujoco", noise=(0.002, 0.0)) == {"perception_noise": (0.002, 0.0)}
