"""The data flow is one way (docs/architecture.md): no package imports one that comes after it in
expressions → mechanics → simulate → answers → store → jobs → web → cli/bench."""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

GRADER = Path(__file__).resolve().parents[1] / "grader"
ORDER = {"expressions": 0, "mechanics": 1, "simulate": 2, "answers": 3, "store": 4, "jobs": 5, "web": 6,
         "cli": 7, "bench": 7}
MODULES = sorted(p for p in GRADER.rglob("*.py") if p.relative_to(GRADER).parts[0] in ORDER)


def _grader_imports(path: Path) -> list[tuple[int, str]]:
    found = []
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.ImportFrom) and node.module and node.module.startswith("grader."):
            found.append((node.lineno, node.module))
        elif isinstance(node, ast.Import):
            found += [(node.lineno, a.name) for a in node.names if a.name.startswith("grader.")]
    return found


@pytest.mark.parametrize("path", MODULES, ids=lambda p: str(p.relative_to(GRADER)))
def test_no_module_reaches_back_up_the_data_flow(path):
    package = path.relative_to(GRADER).parts[0]
    later = [f"line {line}: {name}" for line, name in _grader_imports(path)
             if ORDER.get(name.split(".")[1], -1) > ORDER[package]]
    assert later == [], f"{package} must not import a later package"


def test_the_check_sees_every_package():
    assert {p.relative_to(GRADER).parts[0] for p in MODULES} == set(ORDER)
