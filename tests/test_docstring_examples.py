"""Every engine module shows how it is used in a runnable example.

The examples themselves run through ``--doctest-modules`` (``pyproject.toml``); this test keeps a
module from passing by having none (an engine module without an example shows nothing).
"""

import doctest
import importlib
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
ENGINE = ["expressions", "mechanics", "simulate", "answers"]
# Modules that only draw pictures to files: an example would have to write one.
DRAWING = {"grader.simulate.plot"}
MODULES = sorted(
    name
    for package in ENGINE
    for path in (ROOT / "grader" / package).glob("*.py")
    if path.name != "__init__.py"
    and (name := ".".join(path.relative_to(ROOT).with_suffix("").parts)) not in DRAWING
)


def _runnable_examples(module) -> int:
    return sum(1 for test in doctest.DocTestFinder().find(module) for example in test.examples
               if not example.options.get(doctest.SKIP))


@pytest.mark.parametrize("name", MODULES)
def test_engine_module_has_a_runnable_example(name):
    assert _runnable_examples(importlib.import_module(name)) > 0, f"{name} has no runnable example"
