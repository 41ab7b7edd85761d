"""The motion drawn at registration for the problem pages: what it holds, and when it cannot be drawn."""

from __future__ import annotations

import xml.etree.ElementTree as ET

from grader.mechanics.scene import load_scene, parse_scene
from grader.simulate.motion import DEFAULT_T_END_S, motion_of

SVG = "{http://www.w3.org/2000/svg}"

FALL = '''
id = "fall"
[parameters]
m = { dimension = "mass", domain = "positive", value = 1.0 }
g = { dimension = "acceleration", domain = "positive", %s }
[coordinates]
z = { dimension = "length" }
[energy]
kinetic = "m/2*zdot^2"
potential = "m*g*z"
[initial]
z = 0
zdot = 0
'''


def test_a_scene_with_geometry_gets_a_plot_an_animation_and_its_events():
    motion = motion_of(load_scene("problems/vertical_circle.toml"))
    assert ET.fromstring(motion["plot"]).get("class") == "motion-plot"
    assert ET.fromstring(motion["animation"]).find(f".//{SVG}animate") is not None
    assert motion["events"] and {"t", "effect", "constraint", "state"} <= set(motion["events"][0])


def test_the_scene_sets_the_duration_and_whether_students_see_it():
    yoyo = motion_of(load_scene("problems/yoyo.toml"))
    assert (yoyo["t_end"], yoyo["show_students"]) == (0.5, True)
    fall = motion_of(parse_scene(FALL % "value = 9.81"))
    assert (fall["t_end"], fall["show_students"], fall["animation"]) == (DEFAULT_T_END_S, False, None)


def test_a_falling_body_is_plotted_falling():
    fall = ET.fromstring(motion_of(parse_scene(FALL % "value = 9.81"))["plot"])
    line = fall.find(f".//{SVG}polyline")
    heights = [float(p.split(",")[1]) for p in line.get("points").split()]
    assert heights == sorted(heights) and heights[-1] > heights[0]  # z falls: screen y grows


def test_a_scene_that_cannot_be_simulated_says_why_instead_of_failing():
    motion = motion_of(parse_scene(FALL.replace(", %s }", " }")))  # g has no value
    assert motion["unavailable"].startswith("no simulation:") and "g" in motion["unavailable"]
    assert "plot" not in motion


def test_the_page_names_the_first_six_events_and_counts_the_rest():
    # A bouncing ball has 33 events in 3 s; the page's sentence listed every one.
    import re
    from pathlib import Path

    import jinja2

    from tests.simulate.test_trajectory import BALL

    motion = motion_of(BALL)
    assert len(motion["events"]) > 6
    templates = Path(__file__).resolve().parents[2] / "grader" / "web" / "templates"
    page = jinja2.Environment(loader=jinja2.FileSystemLoader(templates)).get_template("motion.html").render(
        version=type("Version", (), {"derivation": {"motion": motion}})())
    text = re.sub(r"\s+", " ", page)
    assert text.count("bounce of floor at t =") == 6
    assert f"and {len(motion['events']) - 6} more (marked in the plot)." in text
