"""The runnable examples in the docstrings of ``grader.simulate`` run and print what they say."""

import doctest
import importlib

import pytest

MODULES = [
    "grader.simulate.lagrangian_numeric",
    "grader.simulate.manifold",
    "grader.simulate.constrained",
    "grader.simulate.scene_numeric",
]


@pytest.mark.parametrize("name", MODULES)
def test_docstring_examples(name):
    result = doctest.testmod(importlib.import_module(name), optionflags=doctest.ELLIPSIS)
    assert result.attempted > 0, f"{name} has no examples"
    assert result.failed == 0
