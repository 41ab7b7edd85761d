"""Every example in the package's docstrings runs and shows what it claims."""

import doctest
import importlib

import pytest

MODULES = ["", ".errors", ".dimensions", ".variables", ".names", ".functions", ".unicode_input",
           ".latex_input", ".tokens", ".magnitudes", ".parser"]


@pytest.mark.parametrize("module", MODULES)
def test_docstring_examples(module):
    mod = importlib.import_module("grader.expressions" + module)
    result = doctest.testmod(mod, optionflags=doctest.ELLIPSIS)
    assert result.failed == 0
    assert result.attempted > 0 or module == ""
