"""The twelfth engine red team (2026-11-28): scenes from the constraints chapters of the textbooks.

3. A coordinate named d has the acceleration ddot, a parameter named ln is a function: both crashed the
   scene reader with a traceback (ValueError); they are refused naming the name to change.

Each answer is derived by hand (in the comment above it); the values were also checked against a
numerical integration of the Cartesian equations with Lagrange multipliers.
"""

from __future__ import annotations

import math

import pytest
import sympy
from scipy.optimize import brentq

from grader.expressions import parse_expression
from grader.mechanics.lagrange import derive
from grader.mechanics.scene import SceneError, parse_scene
from tests.mechanics.test_red_team_scenes_7 import at

# -- 3. names the expression grammar reads as functions --------------------------------------------------
_NAMED = '''
id = "named"
title = "A block on a spring"
[parameters]
m = { dimension = "mass", domain = "positive", value = 0.5 }
PARAM = { dimension = "stiffness", domain = "positive", value = 5.0 }
[coordinates]
COORD = { dimension = "length" }
[energy]
kinetic = "m/2*COORDdot^2"
potential = "PARAM/2*COORD^2"
'''


@pytest.mark.parametrize("coordinate, parameter, named", [
    ("d", "k", "'d'"),      # its acceleration would be ddot
    ("x", "ln", "'ln'"),    # a function
    ("x", "sin", "'sin'"),
])
def test_a_name_read_as_a_function_is_refused_with_the_name(coordinate, parameter, named):
    text = _NAMED.replace("COORD", coordinate).replace("PARAM", parameter)
    with pytest.raises(SceneError, match=named):
        parse_scene(text, source="named.toml")


def test_a_name_that_is_no_function_still_loads():
    text = _NAMED.replace("COORD", "s").replace("PARAM", "k")
    derivation = derive(parse_scene(text + '[[answers]]\nname = "a"\nprompt = "a"\nexpr = "sddot"\n'
                                           'in_terms_of = ["m", "k", "s"]\n', source="named.toml"))
    assert sympy.simplify(derivation.answers["a"] - sympy.sympify("-k*s/m", locals={
        n: derivation.scene.namespace.symbol(n) for n in ("k", "s", "m")})) == 0
