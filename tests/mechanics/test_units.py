"""The units a scene is written in: its closed forms are the same in metres or kilometres, seconds or ms.

The engine follows the motion numerically to choose roots and extremes; a scan that steps a fraction
of a metre, or a turn of 2π taken for any coordinate's, made the choice depend on the unit of length:
the elastic pendulum's largest stretch printed r0 with its lengths in km, and its extreme was refused
in cm. Each scene below is derived in SI and again with every number of a length (or a time) scaled
as the unit requires, and every printed answer must be the same.
"""

from __future__ import annotations

import re
import tomllib
from pathlib import Path

import pytest

from grader.mechanics.lagrange import derive
from grader.mechanics.scene import parse_scene

SCENES = Path(__file__).resolve().parent / "scenes"


def rescaled(text: str, length: float = 1.0, time: float = 1.0) -> str:
    """``text`` with every number that has a dimension given in another unit: ``length`` units of the new
    kind per metre (100 for cm), ``time`` per second. Parameters' values, random ranges and interval
    domains, coordinates' interval domains and numeric [initial] values are rewritten, line by line."""
    scene = parse_scene(text, "scene.toml")

    def factor(dimension, per_time: int = 0) -> float:
        return length ** float(dimension.length) * time ** float(dimension.time - per_time)

    scales = {name: factor(p.dimension) for name, p in scene.parameters.items()}
    scales.update({name: factor(c.dimension) for name, c in scene.coordinates.items()})
    initial = {}
    for name, value in tomllib.loads(text).get("initial", {}).items():
        base = name[:-3] if name.endswith("dot") and name[:-3] in scene.coordinates else name
        if isinstance(value, (int, float)) and base in scene.coordinates:
            initial[name] = factor(scene.coordinates[base].dimension, per_time=1 if base != name else 0)

    def times(k: float, number: str) -> str:
        return repr(float(number) * k)

    lines, section = [], None
    for line in text.split("\n"):
        if line.startswith("["):
            section = line.strip()
        name = re.match(r"^(\w+)\s*=", line)
        if name and section in ("[parameters]", "[coordinates]") and scales.get(name.group(1), 1.0) != 1.0:
            k = scales[name.group(1)]
            number = r"-?[0-9.]+(?:[eE][-+]?[0-9]+)?"
            line = re.sub(rf"(value|min|max|step)\s*=\s*({number})", lambda m: f"{m[1]} = {times(k, m[2])}", line)
            line = re.sub(rf"domain\s*=\s*\[\s*({number})\s*,\s*({number})\s*\]",
                          lambda m: f"domain = [{times(k, m[1])}, {times(k, m[2])}]", line)
        elif name and section == "[initial]" and name.group(1) in initial:
            line = re.sub(r"=\s*(.+)$", lambda m: f"= {times(initial[name.group(1)], m[1])}", line)
        lines.append(line)
    return "\n".join(lines)


def answers(text: str, name: str) -> dict[str, str]:
    return {k: str(v) for k, v in derive(parse_scene(text, f"{name}.toml")).answers.items()}


@pytest.mark.parametrize("length, time, expected", [
    (0.001, 1.0, {"m": 0.5, "g": 0.00981, "k": 40.0, "l0": 0.0006, "r0": 0.00065}),   # km: k in kg/s² stays
    (1.0, 1000.0, {"m": 0.5, "g": 9.81e-6, "k": 4e-5, "l0": 0.6, "r0": 0.65}),         # ms
])
def test_rescaling_rewrites_the_numbers_with_a_dimension(length, time, expected):
    text = (SCENES / "elastic_pendulum_hanging.toml").read_text(encoding="utf-8")
    parameters = tomllib.loads(rescaled(text, length, time))["parameters"]
    assert {name: spec["value"] for name, spec in parameters.items()} == pytest.approx(expected, rel=1e-12)
    theta = tomllib.loads(rescaled(text, length, time))["coordinates"]["theta"]["domain"]
    assert theta == [-3.1416, 3.1416]  # an angle has no unit to change


# Scenes whose answers are chosen by following the motion: extremes, where-conditions, turning points.
FOLLOWED = ["elastic_pendulum_hanging", "pulley_spring_block", "ladder_wall", "cylinder_in_cylinder",
            "atwood_spring", "bead_rotating_rod", "ball_rolling_loop"]


@pytest.mark.parametrize("length, time", [(100.0, 1.0), (0.001, 1.0), (1.0, 1000.0), (1.0, 0.001)],
                         ids=["cm", "km", "ms", "ks"])
@pytest.mark.parametrize("name", FOLLOWED)
def test_the_closed_forms_do_not_depend_on_the_units(name, length, time):
    text = (SCENES / f"{name}.toml").read_text(encoding="utf-8")
    assert answers(rescaled(text, length, time), name) == answers(text, name)
