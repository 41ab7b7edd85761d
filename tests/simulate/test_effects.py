"""Effect keys of a scene file (grader.mechanics.scene reads them, grader.simulate.effects gives
them numbers): what is accepted, what is refused with a message naming the key."""

from __future__ import annotations

import pytest

from grader.mechanics.scene import SceneError, parse_scene
from grader.simulate.effects import declared_effects

HEAD = '''
id = "disk"
[parameters]
m = { dimension = "mass", domain = "positive", value = 1.0 }
g = { dimension = "acceleration", domain = "positive", value = 9.81 }
R = { dimension = "length", domain = "positive", value = 0.2 }
mu = { dimension = "dimensionless", domain = "nonnegative", value = 0.3 }
[coordinates]
s = { dimension = "length" }
theta = { dimension = "angle" }
n = { dimension = "length" }
[energy]
kinetic = "m/2*(sdot^2 + ndot^2) + m*R^2/4*thetadot^2"
potential = "m*g*n"
[[constraints]]
name = "contact"
f = "n"
kind = "unilateral"
'''


def test_rolling_constraint_with_friction_and_a_normal_contact():
    scene = parse_scene(HEAD + '''
[[constraints]]
name = "roll"
f = "s - R*theta"
kind = "rolling"
mu_s = "mu"
mu_k = 0.2
normal = "contact"
''')
    effects = declared_effects(scene, {"m": 1.0, "g": 9.81, "R": 0.2, "mu": 0.45})
    assert [(e.name, e.kind, e.mu_s, e.mu_k, e.normal) for e in effects] == [
        ("contact", "unilateral", 0.0, 0.0, None), ("roll", "rolling", 0.45, 0.2, 0)]


def test_unnamed_constraints_are_called_c1_c2_in_file_order():
    scene = parse_scene(HEAD.replace('name = "contact"\n', '').replace('f = "n"', 'f = "n"\nrestitution = 0.5'))
    assert [(e.name, e.restitution) for e in declared_effects(scene, {"m": 1, "g": 9.81, "R": 0.2, "mu": 0.3})] == [
        ("c1", 0.5)]


@pytest.mark.parametrize("extra, key, message", [
    ('f = "s - R*theta"\nkind = "rolling"\nmu_k = 0.2\nnormal = "contact"', "mu_s", "missing"),
    ('f = "s - R*theta"\nkind = "rolling"\nmu_s = 0.3\nmu_k = 0.2', "normal", "missing"),
    ('f = "s - R*theta"\nkind = "rolling"\nmu_s = 0.3\nmu_k = 0.2\nnormal = "ground"', "normal", "'ground' must name"),
    ('f = "theta - s/R"\nkind = "rolling"\nmu_s = 0.3\nmu_k = 0.2\nnormal = "contact"', "f", "slip of the contact point"),
    ('f = "s - R*theta"\nkind = "rolling"\nmu_s = -0.3\nmu_k = 0.2\nnormal = "contact"', "mu_s", "must be >= 0"),
    ('f = "s - R*theta"\nkind = "rolling"\nmu_s = "R"\nmu_k = 0.2\nnormal = "contact"', "mu_s", "dimensionless"),
    ('f = "s - R*theta"\nkind = "unilateral"\nrestitution = 1.5', "restitution", "[0, 1]"),
    ('f = "s - R*theta"\nrestitution = 0.5', "restitution", "does not apply to a bilateral"),
    ('f = "s - R*theta"\nkind = "unilateral"\nmu_s = 0.5', "mu_s", "does not apply to a unilateral"),
    ('f = "s - R*theta"\nkind = "sliding"', "kind", ""),
])
def test_bad_effect_keys_are_refused_naming_the_key(extra, key, message):
    with pytest.raises(SceneError) as error:
        parse_scene(HEAD + '[[constraints]]\nname = "roll"\n' + extra + "\n", source="disk.toml")
    assert key in error.value.key and message in str(error.value)


def test_a_coefficient_from_a_parameter_follows_the_parameter_value():
    scene = parse_scene(HEAD.replace('kind = "unilateral"', 'kind = "unilateral"\nrestitution = "mu"'))
    assert declared_effects(scene, {"m": 1, "g": 9.81, "R": 0.2, "mu": 0.7})[0].restitution == 0.7
    with pytest.raises(ValueError, match=r"restitution is 1\.5"):
        declared_effects(scene, {"m": 1, "g": 9.81, "R": 0.2, "mu": 1.5})
