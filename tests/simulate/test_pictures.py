"""Pictures of a motion: what a reader (or a screen reader) can rely on in the SVG."""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET

import pytest

from grader.simulate.pictures import Drawing, animation_svg, nice_ticks, plot_svg

SVG = "{http://www.w3.org/2000/svg}"


def _pendulum_samples(n=2000):
    return [{"t": i * 0.005, "theta": 0.4 * math.cos(3.1 * i * 0.005), "T": 9.81 + math.sin(6.2 * i * 0.005)}
            for i in range(n)]


@pytest.mark.parametrize("low, high", [(0.0, 1.0), (-3.2, 7.9), (1e-9, 3e-9), (-250.0, -0.5), (0.0, 2e4)])
def test_ticks_are_round_cover_the_range_and_are_evenly_spaced(low, high):
    ticks = nice_ticks(low, high)
    steps = {round(b - a, 15) for a, b in zip(ticks, ticks[1:])}
    assert len(steps) == 1
    step = steps.pop()
    mantissa = step / 10 ** math.floor(math.log10(step))
    assert round(mantissa, 9) in (1.0, 2.0, 5.0)
    assert ticks[0] - step < low <= ticks[0] + 1e-12 and ticks[-1] <= high + 1e-12 < ticks[-1] + step


def test_plot_is_valid_svg_with_title_description_and_a_marker_per_event():
    events = [{"t": 1.25, "effect": "slack", "constraint": "string"}, {"t": 2.5, "effect": "taut", "constraint": "string"}]
    svg = plot_svg(_pendulum_samples(), events, coordinates=["theta"], reactions=["T"], title="Bob <on> a string")
    root = ET.fromstring(svg)
    assert root.find(f"{SVG}title").text == "Bob <on> a string"  # escaped in the text, read back intact
    assert "slack (string) at t = 1.25 s" in root.find(f"{SVG}desc").text
    assert len(root.findall(f".//{SVG}g[@class='event']")) == 2
    assert root.get("role") == "img" and "<script" not in svg and " on" not in svg.lower().replace("one", "")


def test_plot_thins_long_series_but_keeps_the_last_sample():
    samples = _pendulum_samples(5000)
    root = ET.fromstring(plot_svg(samples, [], coordinates=["theta"], reactions=["T"]))
    lines = root.findall(f".//{SVG}polyline")
    assert len(lines) == 2
    for line in lines:
        points = line.get("points").split()
        assert 100 < len(points) <= 601
        assert float(points[-1].split(",")[0]) == pytest.approx(720 - 16, abs=0.1)  # the right edge: t_end


def test_plot_draws_coordinates_above_reactions_and_skips_an_empty_panel():
    both = ET.fromstring(plot_svg(_pendulum_samples(50), [], coordinates=["theta"], reactions=["T"]))
    only = ET.fromstring(plot_svg(_pendulum_samples(50), [], coordinates=["theta"], reactions=[]))
    assert len(both.findall(f"{SVG}rect")) == 3 and len(only.findall(f"{SVG}rect")) == 2  # background + panels


def test_animation_moves_each_point_through_its_positions_with_y_up():
    times = [0.0, 0.5, 1.0]
    drawing = Drawing(times, {"bob": [(0.0, -1.0), (1.0, 0.0), (0.0, 1.0)]}, bars=[((0.0, 0.0), "bob")],
                      circles=[(0.0, 0.0, 0.1)])
    root = ET.fromstring(animation_svg(drawing, title="Loop"))
    bob = root.find(f"{SVG}circle[{SVG}title]")
    cy = [float(v) for v in bob.find(f"{SVG}animate[@attributeName='cy']").get("values").split(";")]
    assert cy[0] > cy[1] > cy[2]  # the bob rises: screen y decreases
    animate = bob.find(f"{SVG}animate[@attributeName='cx']")
    assert animate.get("dur") == "1.000s" and animate.get("keyTimes") == "0.0000;0.5000;1.0000"
    bar = root.find(f"{SVG}line")
    assert {a.get("attributeName") for a in bar.findall(f"{SVG}animate")} == {"x1", "y1", "x2", "y2"}


def test_animation_of_a_single_frame_is_a_still_picture():
    root = ET.fromstring(animation_svg(Drawing([0.0], {"body": [(0.3, 0.4)]})))
    assert root.findall(f".//{SVG}animate") == []
