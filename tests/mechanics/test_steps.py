"""The derivation's step titles are text with $...$ math: names as the reader writes them, not sympy's."""

import re

import pytest

from grader.mechanics.lagrange import derive
from grader.mechanics.scene import load_scene
from grader.web.student.mathml import unsupported


@pytest.fixture(scope="module")
def steps():
    return derive(load_scene("problems/yoyo.toml")).steps


def test_coordinates_and_the_constraint_force_rule_are_math_in_the_titles(steps):
    titles = [s.title for s in steps]
    assert "Partial derivatives for $\\theta$" in titles and "Partial derivatives for $s$" in titles
    assert any(t.startswith("Generalized constraint forces $Q = \\lambda") for t in titles)
    for title in titles:
        assert "theta" not in re.sub(r"\$[^$]*\$", "", title) and "lambda" not in re.sub(r"\$[^$]*\$", "", title)


def test_every_formula_in_a_title_is_one_the_pages_can_show(steps):
    for title in (s.title for s in steps):
        for tex in re.findall(r"\$([^$]+)\$", title):
            assert unsupported(tex) == [], title
