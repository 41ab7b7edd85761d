"""``grader bench simulate``: what effects cost, and what compiling buys.

For each scene, in the same process and run (best of N):

- ``plain``: ``solve_ivp(CompiledScene.rhs, DOP853)`` over [0, T]: the compiled bilateral
  right-hand side and nothing else;
- ``simulate``: :meth:`grader.simulate.trajectory.Simulation.run` on the same scene, with the
  effects it declares. For a scene that declares none (only bilateral constraints) it must cost
  what ``plain`` costs: the ratio simulate / plain is the "no-effect scene runs as fast as before"
  row;
- per right-hand-side evaluation: the compiled one, beside the 40-digit finite-difference one
  that confirms the engine in the tests (:mod:`grader.simulate.constrained`).

Figures go to ``bench-results/simulate.json``.
"""

from __future__ import annotations

import json
import time
from pathlib import Path

import click
import numpy as np

__all__ = ["bench_simulate"]

DEFAULT_SCENES = ("tests/mechanics/scenes/double_pendulum.toml", "tests/mechanics/scenes/atwood_massive_pulley.toml",
                  "problems/pendulum.toml", "problems/vertical_circle.toml", "problems/incline_slipping.toml")


def _best_of(function, repeat: int) -> float:
    best = float("inf")
    for _ in range(repeat):
        start = time.perf_counter()
        function()
        best = min(best, time.perf_counter() - start)
    return best


def _row(path: str, t_end: float, repeat: int) -> dict:
    from scipy.integrate import solve_ivp

    from grader.mechanics.scene import load_scene
    from grader.simulate.compiled import CompiledScene, parameter_values
    from grader.simulate.effects import declared_effects
    from grader.simulate.initial import initial_state
    from grader.simulate.scene_numeric import SceneModel
    from grader.simulate.lagrangian_numeric import snapshot
    from grader.simulate.trajectory import Simulation

    scene = load_scene(path)
    compiled = CompiledScene(scene, parameter_values(scene))
    effects = declared_effects(scene, compiled.values)
    simulation = Simulation(compiled, effects)
    q0, qdot0 = initial_state(scene, compiled)
    y0 = np.concatenate([q0, qdot0])

    def plain():
        solve_ivp(compiled.rhs, (0.0, t_end), y0, method="DOP853", rtol=simulation.rtol, atol=simulation.atol,
                  dense_output=True)

    # Interleaved, so that both see the same load on a shared machine.
    plain_s = simulate_s = float("inf")
    for _ in range(repeat):
        plain_s = min(plain_s, _best_of(plain, 1))
        simulate_s = min(simulate_s, _best_of(lambda: simulation.run(0.0, q0, qdot0, t_end, (0.0, t_end)), 1))
    # The work itself, free of timing noise: evaluations of the compiled M, F, J, b in each run
    # (the simulation's include one per sample for the reaction forces).
    counts = []
    for run in (plain, lambda: simulation.run(0.0, q0, qdot0, t_end, (0.0, t_end))):
        calls = [0]
        terms = compiled.terms

        def counted(*args, terms=terms, calls=calls):
            calls[0] += 1
            return terms(*args)

        compiled.terms = counted
        try:
            run()
        finally:
            del compiled.terms
        counts.append(calls[0])
    evaluations = 2000
    compiled_us = _best_of(lambda: [compiled.rhs(0.0, y0) for _ in range(evaluations)], repeat) / evaluations * 1e6
    model = SceneModel(scene, {})
    reference_us = _best_of(lambda: [snapshot(model.numeric, 0.0, q0, qdot0) for _ in range(20)], 1) / 20 * 1e6
    declared = sorted({e.kind for e in effects if e.kind != "bilateral"})
    return {"scene": scene.id, "effects": declared, "t_end": t_end, "plain_s": plain_s, "simulate_s": simulate_s,
            "ratio": simulate_s / plain_s, "plain_evaluations": counts[0], "simulate_evaluations": counts[1],
            "events": len(simulation.run(0.0, q0, qdot0, t_end, ()).events),
            "compiled_rhs_us": compiled_us, "finite_difference_rhs_us": reference_us}


@click.command("simulate")
@click.argument("paths", nargs=-1, type=click.Path(exists=True, dir_okay=False))
@click.option("--t-end", default=10.0, show_default=True, help="Seconds of motion per scene.")
@click.option("--repeat", default=3, show_default=True, help="Repetitions per timing (best is kept).")
@click.option("--out", default="bench-results/simulate.json", show_default=True, type=click.Path())
def bench_simulate(paths: tuple[str, ...], t_end: float, repeat: int, out: str) -> None:
    """Time the effect-aware simulation against a plain integration of the same compiled RHS."""
    rows = [_row(p, t_end, repeat) for p in (paths or DEFAULT_SCENES)]
    header = (f"{'scene':24} {'effects':20} {'plain':>9} {'simulate':>9} {'ratio':>6} {'evaluations':>13} "
              f"{'events':>6} {'rhs compiled':>13} {'rhs 40-digit':>13}")
    click.echo(header)
    click.echo("-" * len(header))
    for r in rows:
        evaluations = f"{r['plain_evaluations']}/{r['simulate_evaluations']}"
        click.echo(f"{r['scene']:24} {', '.join(r['effects']) or 'none':20} {r['plain_s'] * 1e3:7.1f}ms "
                   f"{r['simulate_s'] * 1e3:7.1f}ms {r['ratio']:6.2f} {evaluations:>13} {r['events']:6d} "
                   f"{r['compiled_rhs_us']:11.1f}us {r['finite_difference_rhs_us'] / 1e3:11.1f}ms")
    click.echo("-" * len(header))
    click.echo("ratio = simulate / plain time; evaluations = compiled M, F, J, b evaluations plain/simulate.")
    click.echo("A scene without effects does the plain work plus one evaluation per sample (2 here).")
    Path(out).parent.mkdir(parents=True, exist_ok=True)
    Path(out).write_text(json.dumps({"t_end": t_end, "repeat": repeat, "rows": rows}, indent=2))
    click.echo(f"figures written to {out}")
