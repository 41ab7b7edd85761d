"""``grader derive FILE [--json]``: the engine's derivation of one scene file."""

from __future__ import annotations

import json
import sys

import click


@click.command()
@click.argument("path", type=click.Path(dir_okay=False))
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object (the derive contract).")
@click.option("--latex", is_flag=True, help="Print the step-by-step derivation as LaTeX.")
def derive(path: str, as_json: bool, latex: bool) -> None:
    """Derive equations of motion, multipliers, constraint forces and answers of a scene file."""
    from grader.mechanics.lagrange import derive as derive_scene
    from grader.mechanics.report import derivation_text
    from grader.mechanics.scene import SceneError, load_scene

    try:
        derivation = derive_scene(load_scene(path))
    except SceneError as exc:
        click.echo(f"error: {exc}", err=True)
        sys.exit(2)
    if as_json:
        click.echo(json.dumps(derivation.to_json(), indent=2, ensure_ascii=False))
    elif latex:
        for step in derivation.steps:
            click.echo(f"% {step.title}")
            for line in step.latex:
                click.echo(f"\\[ {line} \\]")
    else:
        click.echo(derivation_text(derivation), nl=False)
