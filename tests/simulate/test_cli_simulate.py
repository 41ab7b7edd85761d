"""``grader simulate``: the JSON contract, CSV, the picture, and one-line errors with exit code 2."""

from __future__ import annotations

import csv
import io
import json
import math
from pathlib import Path

import pytest
from click.testing import CliRunner

from grader.cli import main

ROOT = Path(__file__).resolve().parents[2]
CIRCLE = str(ROOT / "problems" / "vertical_circle.toml")
SPHERE = str(ROOT / "problems" / "sphere.toml")


def run(*args: str):
    return CliRunner().invoke(main, ["simulate", *args])


def test_json_reports_events_with_the_full_state_and_samples_with_reactions():
    result = run(CIRCLE, "--t-end", "2", "--samples", "5", "--json")
    assert result.exit_code == 0, result.output
    data = json.loads(result.output)
    assert [(e["effect"], e["constraint"]) for e in data["events"]] == [("release", "string"), ("contact", "string")]
    assert set(data["events"][0]["state"]) == {"x", "xdot", "y", "ydot"}
    assert [s["t"] for s in data["samples"]] == [0.0, 0.5, 1.0, 1.5, 2.0]
    first = data["samples"][0]
    assert set(first) == {"t", "x", "xdot", "y", "ydot", "lambda_string", "Q_string_x", "Q_string_y"}
    # At the lowest point T = m v0²/l + m g = 2 l λ.
    assert 2 * 0.9 * first["lambda_string"] == pytest.approx(0.3 * 5.5 ** 2 / 0.9 + 0.3 * 9.81, rel=1e-12)


def test_set_overrides_the_files_value():
    result = run(CIRCLE, "--t-end", "2", "--set", "v0=4.5", "--json")
    slack = json.loads(result.output)["events"][0]
    assert -slack["state"]["y"] / 0.9 == pytest.approx((2 * 9.81 * 0.9 - 4.5 ** 2) / (3 * 9.81 * 0.9), abs=1e-9)


def test_csv_has_one_row_per_sample_and_per_event_in_time_order():
    result = run(CIRCLE, "--t-end", "1", "--samples", "3", "--csv")
    rows = list(csv.DictReader(io.StringIO(result.output)))
    assert [r["event"] for r in rows] == ["", "release", "", ""]
    times = [float(r["t"]) for r in rows]
    assert times == sorted(times)


def test_plot_writes_a_script_free_svg_with_the_events_marked(tmp_path):
    out = tmp_path / "circle.svg"
    result = run(CIRCLE, "--t-end", "2", "--plot", str(out))
    assert result.exit_code == 0, result.output
    svg = out.read_text()
    assert svg.startswith("<svg") and "<script" not in svg
    assert "release" in svg and "contact" in svg and "lambda_string" in svg


def test_animate_draws_the_scenes_geometry(tmp_path):
    out = tmp_path / "sphere.svg"
    result = run(SPHERE, "--t-end", "1", "--animate", str(out))
    assert result.exit_code == 0, result.output
    assert "<animate" in out.read_text()


def test_animate_without_geometry_is_refused_in_one_line(tmp_path):
    result = run(str(ROOT / "problems" / "half_atwood.toml"), "--t-end", "1", "--animate", str(tmp_path / "x.svg"))
    assert result.exit_code == 2 and "[geometry]" in result.output


@pytest.mark.parametrize("args, message", [
    ((SPHERE, "--t-end", "-1"), "--t-end must be a positive number"),
    ((SPHERE, "--t-end", "nan"), "--t-end must be a positive number"),
    ((SPHERE, "--t-end", "soon"), "--t-end must be a positive number"),
    ((SPHERE, "--set", "mass=2"), "no parameter named mass"),
    ((SPHERE, "--set", "m"), "write name=number"),
    ((SPHERE, "--set", "m=heavy"), "write name=number"),
    ((SPHERE, "--samples", "1"), "--samples must be a whole number"),
    ((str(ROOT / "missing.toml"),), "cannot read the file"),
])
def test_bad_input_gets_one_line_and_exit_code_2(args, message):
    result = run(*args)
    assert result.exit_code == 2
    lines = result.output.strip().splitlines()
    assert len(lines) == 1 and message in lines[0] and lines[0].startswith("error: ")


@pytest.mark.parametrize("text, message", [
    # the parameter l has no value
    ('l = { dimension = "length", domain = "positive" }', "parameter 'l' has no value"),
    # the bob starts off the string's circle, inside it is allowed, outside is not
    ('l = { dimension = "length", domain = "positive", value = 1.0 }\n[initial]\nx = 2\ny = 0',
     "wrong side of constraint 'string'"),
])
def test_bad_scenes_get_one_line_and_exit_code_2(tmp_path, text, message):
    scene = tmp_path / "bob.toml"
    scene.write_text(f'''id = "bob"
[coordinates]
x = {{ dimension = "length" }}
y = {{ dimension = "length" }}
[energy]
kinetic = "m/2*(xdot^2 + ydot^2)"
potential = "m*g*y"
[[constraints]]
name = "string"
f = "l^2 - x^2 - y^2"
kind = "unilateral"
[parameters]
m = {{ dimension = "mass", domain = "positive", value = 1.0 }}
g = {{ dimension = "acceleration", domain = "positive", value = 9.81 }}
{text}
''')
    result = run(str(scene))
    assert result.exit_code == 2, result.output
    lines = result.output.strip().splitlines()
    assert len(lines) == 1 and message in lines[0], result.output


def test_text_output_lists_events():
    result = run(SPHERE, "--t-end", "1")
    assert result.exit_code == 0
    assert result.output.startswith("0 event(s)")  # at rest on the top: it never leaves
    assert not math.isnan(float(result.output.splitlines()[-1].split()[0]))


def test_a_run_longer_than_its_budget_stops_with_one_line():
    result = run(CIRCLE, "--t-end", "1e9", "--budget", "0.5")
    assert result.exit_code == 2
    assert result.output.startswith("error: stopped at t = ") and "time budget" in result.output


def test_a_scene_whose_forces_are_not_finite_gets_one_line(tmp_path):
    scene = tmp_path / "bad.toml"
    scene.write_text('''id = "bad"
[parameters]
m = { dimension = "mass", domain = "positive", value = 1.0 }
k = { dimension = "energy", domain = "positive", value = 1.0 }
a = { dimension = "length", domain = "positive", value = 1.0 }
[coordinates]
x = { dimension = "length" }
[energy]
kinetic = "m/2*xdot^2"
potential = "k*sqrt(x/a)"
[initial]
x = -1
''')
    result = run(str(scene), "--t-end", "1")
    assert result.exit_code == 2, result.output
    assert len(result.output.strip().splitlines()) == 1 and "not finite" in result.output


@pytest.mark.parametrize("samples, header", [
    ("3", "samples (all 3):"), ("25", "samples (every 2nd of 25):"), ("31", "samples (every 3rd of 31):"),
    ("201", "samples (every 20th of 201):"), ("211", "samples (every 21st of 211):"),
    ("111", "samples (every 11th of 111):"),
])
def test_the_text_output_names_the_sample_stride_in_english(samples, header):
    # It printed 'every 1th of 3', 'every 2th of 25', 'every 21th of 211'.
    result = run(SPHERE, "--t-end", "0.5", "--samples", samples)
    assert result.exit_code == 0, result.output
    assert header in result.output
