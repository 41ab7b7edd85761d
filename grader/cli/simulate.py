"""``grader simulate FILE``: the motion of a scene with its declared effects.

Integrates from ``[initial]`` and reports the samples (coordinates, velocities, multipliers and
generalized reaction forces) and every event (time, effect, constraint, state). Bad input gets
one line on stderr and exit code 2.
"""

from __future__ import annotations

import csv
import json
import math
import sys

import click


def _fail(message: str) -> None:
    click.echo(f"error: {message}", err=True)
    sys.exit(2)


def _positive_number(text: str, what: str) -> float:
    try:
        value = float(text)
    except ValueError:
        value = math.nan
    if not (math.isfinite(value) and value > 0):
        _fail(f"{what} must be a positive number, not {text!r}")
    return value


def _overrides(pairs: tuple[str, ...]) -> dict[str, float]:
    values = {}
    for pair in pairs:
        name, sep, text = pair.partition("=")
        name = name.strip()
        try:
            value = float(text)
        except ValueError:
            value = math.nan
        if not sep or not name or not math.isfinite(value):
            _fail(f"--set {pair!r}: write name=number, e.g. --set m=0.5")
        values[name] = value
    return values


@click.command()
@click.argument("path", type=click.Path(dir_okay=False))
@click.option("--t-end", "t_end", default="5", show_default=True, help="End time in seconds.")
@click.option("--set", "settings", multiple=True, metavar="NAME=VALUE",
              help="Override a parameter's value (repeatable); wins over the file's value.")
@click.option("--samples", default="201", show_default=True, help="Number of evenly spaced samples.")
@click.option("--json", "as_json", is_flag=True, help='Print {"events": [...], "samples": [...]}.')
@click.option("--csv", "as_csv", is_flag=True, help="Print the samples and events as CSV.")
@click.option("--plot", type=click.Path(dir_okay=False), help="Draw coordinates and reaction forces to an SVG.")
@click.option("--animate", type=click.Path(dir_okay=False), help="Animate the scene's [geometry] to an SVG.")
@click.option("--budget", default="60", show_default=True, help="Give up after this many seconds of computing.")
def simulate(path: str, t_end: str, settings: tuple[str, ...], samples: str, as_json: bool, as_csv: bool,
             plot: str | None, animate: str | None, budget: str) -> None:
    """Integrate a scene file from its [initial] state, with its declared effects."""
    from grader.mechanics.scene import SceneError, load_scene
    from grader.simulate.compiled import SingularDynamics, parameter_values
    from grader.simulate.initial import InitialStateError
    from grader.simulate.events import SimulationError
    from grader.simulate.trajectory import simulate_scene

    if as_json and as_csv:
        _fail("choose one of --json and --csv")
    end = _positive_number(t_end, "--t-end")
    count = _positive_number(samples, "--samples")
    if count != int(count) or not 2 <= count <= 100_000:
        _fail(f"--samples must be a whole number from 2 to 100000, not {samples!r}")
    budget_s = _positive_number(budget, "--budget")
    overrides = _overrides(settings)
    try:
        scene = load_scene(path)
        if animate and scene.geometry is None:
            _fail(f"{scene.source}: --animate needs a [geometry] table saying where to draw the bodies")
        trajectory = simulate_scene(scene, overrides, t_end=end, samples=int(count), budget_s=budget_s)
    except KeyError as exc:
        _fail(exc.args[0] if exc.args else str(exc))
    except (SceneError, InitialStateError, SingularDynamics, SimulationError, ValueError) as exc:
        _fail(str(exc))
    if plot or animate:
        from grader.simulate.plot import animation_of, plot_of

        pictures = [(plot, lambda: plot_of(trajectory, scene.title))] + [
            (animate, lambda: animation_of(scene, trajectory, parameter_values(scene, overrides)))]
        for target, draw in pictures:
            if target:
                try:
                    with open(target, "w", encoding="utf-8") as handle:
                        handle.write(draw())
                except OSError as exc:
                    _fail(f"cannot write {target}: {exc.strerror}")
    if as_json:
        click.echo(json.dumps(trajectory.to_json()))
    elif as_csv:
        _write_csv(trajectory)
    else:
        _write_text(trajectory)


def _write_csv(trajectory) -> None:
    rows = trajectory.sample_rows()
    columns = ["t", "event", "constraint"] + [c for c in (rows[0] if rows else {}) if c != "t"]
    writer = csv.DictWriter(sys.stdout, fieldnames=columns, lineterminator="\n")
    writer.writeheader()
    merged = [(r["t"], 1, r) for r in rows] + [
        (e.t, 0, {"t": e.t, "event": e.effect, "constraint": e.constraint, **e.state}) for e in trajectory.events]
    for _, _, row in sorted(merged, key=lambda item: (item[0], item[1])):
        writer.writerow({key: (repr(value) if isinstance(value, float) else value) for key, value in row.items()})


def _ordinal(k: int) -> str:
    """2nd, 3rd, 11th, 20th, 21st, 22nd (the sample stride; it printed '2th', '21th')."""
    suffix = "th" if 10 <= k % 100 <= 20 else {1: "st", 2: "nd", 3: "rd"}.get(k % 10, "th")
    return f"{k}{suffix}"


def _write_text(trajectory) -> None:
    click.echo(f"{len(trajectory.events)} event(s)")
    for e in trajectory.events:
        state = ", ".join(f"{k} = {v:.10g}" for k, v in e.state.items())
        click.echo(f"  t = {e.t:.12g}  {e.effect} ({e.constraint}): {state}")
    rows = trajectory.sample_rows()
    if not rows:
        return
    columns = list(rows[0])
    step = max(1, len(rows) // 10)
    click.echo(f"samples (all {len(rows)}):" if step == 1 else f"samples (every {_ordinal(step)} of {len(rows)}):")
    click.echo("  " + "  ".join(f"{c:>14}" for c in columns))
    for row in rows[::step]:
        click.echo("  " + "  ".join(f"{row[c]:>14.6g}" for c in columns))
