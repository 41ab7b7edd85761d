"""``grader derive FILE [--json]``: the engine's derivation of one scene file, and its question tests.

Exit status: 2 for a scene error, 3 when the budget ran out, 4 when a question test
(``[[answers.tests]]``) did not get the verdict it expects.
"""

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
    try:
        tests = _question_tests(derivation)
    except SceneError as exc:
        click.echo(f"error: {exc}", err=True)
        sys.exit(2)
    if as_json:
        click.echo(json.dumps({**derivation.to_json(), "question_tests": tests}, indent=2, ensure_ascii=False))
    elif latex:
        for step in derivation.steps:
            click.echo(f"% {step.title}")
            for line in step.latex:
                click.echo(f"\\[ {line} \\]")
    else:
        click.echo(derivation_text(derivation), nl=False)
        if tests:
            click.echo("\nQuestion tests")
            for t in tests:
                wanted = t["expect"] + (f" (score {t['expected_score']:g})" if "expected_score" in t else "")
                got = t["got"] + (f" (score {t['score']:g})" if "expected_score" in t or t["got"] != t["expect"] else "")
                click.echo(f"  {'ok  ' if t['passed'] else 'FAIL'} {t['answer_name']}: {t['answer']!r} expects "
                           f"{wanted}, got {got}" + ("" if t["passed"] else f": {t['reason']}"))
    if any(not t["passed"] for t in tests):
        from grader.answers.question_tests import failure_report

        click.echo(f"error: {scene.source}: question tests failed:\n{failure_report(tests)}", err=True)
        sys.exit(4)


def _question_tests(derivation) -> list[dict]:
    """The scene's ``[[answers.tests]]`` run with the checker (exit status 4 when one fails)."""
    from grader.answers.question_tests import run_question_tests

    return run_question_tests(derivation.references())
