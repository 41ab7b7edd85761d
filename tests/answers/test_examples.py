"""Every example in the checker's docstrings runs and shows what it claims."""

from __future__ import annotations

import doctest
import importlib

import pytest

MODULES = ["verdict", "evaluate", "sampling", "equivalence", "equations", "feedback", "checker"]


@pytest.mark.parametrize("module", MODULES)
def test_docstring_examples(module):
    mod = importlib.import_module(f"grader.answers.{module}")
    result = doctest.testmod(mod, optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    assert result.failed == 0
