"""``grader bench derive``: time to derive each scene, beside sympy's ``LagrangesMethod``.

For every scene file, in the same run and the same process, three timings (best of N, with sympy's
cache cleared before each repetition so no run profits from an earlier one):

- ``engine eom``: our equations of motion solved for accelerations and multipliers
  (:func:`grader.mechanics.lagrange.equations_of_motion`), the same work as the baseline;
- ``engine full``: loading the file and the whole derivation: every answer eliminated to its
  ``in_terms_of`` and simplified, special values, the step-by-step derivation; also as CPU time
  of this process, which a machine loaded by other work does not inflate as it does wall time;
- ``LagrangesMethod``: ``sympy.physics.mechanics.LagrangesMethod`` on the same Lagrangian and
  holonomic constraints (with dynamicsymbols), ``form_lagranges_equations()`` then
  ``solve_multipliers()``.

The ratio is baseline time / our time, so > 1 means we are faster. Figures go to
``bench-results/derive.json``.
"""

from __future__ import annotations

import json
import statistics
import sys
import time
from pathlib import Path

import click
import sympy
from sympy.core.cache import clear_cache

__all__ = ["bench_derive", "lagranges_method_baseline"]


def lagranges_method_baseline(scene) -> dict:
    """Derive a scene with sympy's LagrangesMethod and solve for the multipliers."""
    from sympy.physics.mechanics import LagrangesMethod, dynamicsymbols

    # dynamicsymbols are functions of their own t, not of the scene's (real) time symbol.
    t = dynamicsymbols._t
    coords = list(scene.coordinates.values())
    q = [dynamicsymbols(c.name) for c in coords]
    subs = {scene.time: t}
    for c, qi in zip(coords, q):
        subs[c.symbol] = qi
        subs[c.dot] = qi.diff(t)
    L = scene.lagrangian.xreplace(subs)
    constraints = [k.f.xreplace(subs) for k in scene.constraints]
    lm = LagrangesMethod(L, q, hol_coneqs=constraints or None)
    lm.form_lagranges_equations()
    return lm.solve_multipliers() if constraints else {}


def _baseline_child(path: str, repeat: int, connection) -> None:
    from grader.mechanics.scene import load_scene

    scene = load_scene(path)
    connection.send(_best_of(lambda: lagranges_method_baseline(scene), repeat))


def _baseline_time(path: Path, repeat: int, timeout_s: float) -> float | None:
    """Best time of the baseline, run in a child that is killed after ``timeout_s`` (None then)."""
    import multiprocessing

    context = multiprocessing.get_context("fork")
    parent, child = context.Pipe()
    process = context.Process(target=_baseline_child, args=(str(path), repeat, child), daemon=True)
    process.start()
    try:
        if parent.poll(timeout_s):
            return parent.recv()
        return None
    finally:
        process.kill()
        process.join()


def _best_of(function, repeat: int) -> float:
    return _best_of_both(function, repeat)[0]


def _best_of_both(function, repeat: int) -> tuple[float, float]:
    """Best wall-clock and best CPU time of ``repeat`` runs (CPU time is what a loaded machine
    does not inflate: other processes take turns on the cores, not this process's instructions)."""
    from grader.mechanics.simplification import forget_forms

    walls, cpus = [], []
    for _ in range(repeat):
        clear_cache()
        forget_forms()  # each repetition as the first: our readable forms are remembered too
        start, start_cpu = time.perf_counter(), time.process_time()
        function()
        walls.append(time.perf_counter() - start)
        cpus.append(time.process_time() - start_cpu)
    return min(walls), min(cpus)


@click.command("derive")
@click.argument("paths", nargs=-1, type=click.Path(exists=True, dir_okay=False))
@click.option("--repeat", default=3, show_default=True, help="Repetitions per timing (best is kept).")
@click.option("--out", default="bench-results/derive.json", show_default=True, type=click.Path())
@click.option("--baseline-timeout", default=300.0, show_default=True,
              help="Seconds the baseline may take for one scene (all repetitions) before it is killed.")
def bench_derive(paths: tuple[str, ...], repeat: int, out: str, baseline_timeout: float) -> None:
    """Time the engine on each scene (default: problems/*.toml) against sympy's LagrangesMethod."""
    from grader.mechanics.lagrange import derive, equations_of_motion
    from grader.mechanics.scene import load_scene

    files = [Path(p) for p in paths] or sorted(Path("problems").glob("*.toml"))
    if not files:
        raise click.UsageError("no scene files given and none in problems/")
    rows = []
    w = max(28, *(len(p.stem) for p in files))  # the scene column fits the longest file name
    header = (f"{'scene':{w}} {'engine eom':>11} {'engine full':>12} {'full (CPU)':>11} {'LagrangesMethod':>16} "
              f"{'ratio eom':>10}")
    click.echo(header)
    click.echo("-" * len(header))
    for path in files:
        try:
            scene = load_scene(path)
            eom = _best_of(lambda: equations_of_motion(scene), repeat)
            full, full_cpu = _best_of_both(lambda: derive(load_scene(path)), repeat)
        except Exception as exc:  # a scene this engine cannot derive is a row, not the end of the run
            click.echo(f"{path.stem:{w}} {'error':>11}  {type(exc).__name__}: {str(exc)[:90]}")
            rows.append({"scene": path.stem, "error": str(exc)})
            continue
        baseline = _baseline_time(path, repeat, baseline_timeout)
        if baseline is None:
            # A timed-out baseline counts at its time limit: the ratio is then a lower bound.
            bound = baseline_timeout / repeat
            rows.append({"scene": scene.id, "engine_eom_s": eom, "engine_full_s": full,
                         "engine_full_cpu_s": full_cpu, "lagranges_method_s": None, "baseline_timed_out_after_s": baseline_timeout,
                         "ratio_eom": bound / eom, "ratio_full": bound / full, "ratio_is_lower_bound": True})
            click.echo(f"{scene.id:{w}} {eom * 1e3:9.1f}ms {full * 1e3:10.1f}ms {full_cpu * 1e3:9.1f}ms "
                       f"{'> ' + format(bound, '.0f') + ' s':>16} "
                       f"{'> ' + format(bound / eom, '.0f'):>9}x", nl=True)
        else:
            rows.append({"scene": scene.id, "engine_eom_s": eom, "engine_full_s": full,
                         "engine_full_cpu_s": full_cpu, "lagranges_method_s": baseline, "ratio_eom": baseline / eom,
                         "ratio_full": baseline / full})
            click.echo(f"{scene.id:{w}} {eom * 1e3:9.1f}ms {full * 1e3:10.1f}ms {full_cpu * 1e3:9.1f}ms "
                       f"{baseline * 1e3:14.1f}ms "
                       f"{baseline / eom:9.1f}x")
        sys.stdout.flush()
    timed = [r for r in rows if "ratio_eom" in r]
    median_ratio = statistics.median(r["ratio_eom"] for r in timed) if timed else float("nan")
    click.echo("-" * len(header))
    click.echo(f"median ratio LagrangesMethod / engine eom: {median_ratio:.1f}x "
               f"(> 1: the engine is faster; best of {repeat}, sympy cache cleared each time)")
    Path(out).parent.mkdir(parents=True, exist_ok=True)
    Path(out).write_text(json.dumps({"sympy": sympy.__version__, "repeat": repeat, "rows": rows,
                                     "median_ratio_eom": median_ratio}, indent=2))
    click.echo(f"figures written to {out}")
