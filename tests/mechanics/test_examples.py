"""Every example in the engine's docstrings runs (from the repository root) and shows what it claims."""

from __future__ import annotations

import doctest
import importlib
from pathlib import Path

import pytest

MODULES = ["scene", "lagrange", "reduction", "answers", "special_values", "simplification", "steps",
           "report", "references"]


@pytest.mark.parametrize("module", MODULES)
def test_docstring_examples(module, monkeypatch):
    monkeypatch.chdir(Path(__file__).resolve().parents[2])  # examples read problems/*.toml
    mod = importlib.import_module(f"grader.mechanics.{module}")
    result = doctest.testmod(mod, optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    assert result.attempted > 0, f"grader.mechanics.{module} has no runnable example"
    assert result.failed == 0
