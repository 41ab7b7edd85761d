"""``grader derive FILE [--json]``: the engine's derivation of one scene file."""

from __future__ import annotations

import json
import sys

import click


@click.command()
@click.argument("path", type=click.Path(dir_okay=False))
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object (the derive contract).")
@click.option("--latex", is_flag=True, help="Print the step-by-step derivation as LaTeX.")
@click.option("--budget", "budget_s", default=60.0, show_default=True, type=click.FloatRange(min=0.1),
              help="Seconds the derivation may take; past them it stops and says which step ran out.")
def derive(path: str, as_json: bool, latex: bool, budget_s: float) -> None:
    """Derive equations of motion, multipliers, constraint forces and answers of a scene file."""
    from grader.mechanics.budget import BudgetExceeded
    from grader.mechanics.lagrange import derive as derive_scene
    from grader.mechanics.report import derivation_text
    from grader.mechanics.scene import SceneError, load_scene

    try:
        scene = load_scene(path)
        derivation = derive_scene(scene, budget_s=budget_s)
    except SceneError as exc:
        click.echo(f"error: {exc}", err=True)
        sys.exit(2)
    except BudgetExceeded as exc:
        click.echo(f"error: {scene.source}: {exc}", err=True)
        sys.exit(3)
    if as_json:
        click.echo(json.dumps(derivation.to_json(), indent=2, ensure_ascii=False))
    elif latex:
        for step in derivation.steps:
            click.echo(f"% {step.title}")
            for line in step.latex:
                click.echo(f"\\[ {line} \\]")
    else:
        click.echo(derivation_text(derivation), nl=False)
