"""The engine's results as JSON (``grader derive --json``) and as a readable derivation.

Examples
--------
>>> from grader.mechanics.scene import load_scene
>>> from grader.mechanics.lagrange import derive
>>> derivation_json(derive(load_scene("problems/yoyo.toml")))["answers"]["tension"]
'g*m/3'
"""

from __future__ import annotations

import sympy

__all__ = ["derivation_json", "derivation_text", "equation_text", "steps_json"]


def equation_text(lhs: sympy.Expr, rhs: sympy.Expr) -> str:
    """An equation as ``"lhs = rhs"`` in sympy's str() syntax."""
    return f"{sympy.sstr(lhs)} = {sympy.sstr(rhs)}"


def derivation_json(derivation) -> dict:
    """The ``grader derive --json`` contract: every expression a string in the file's own names."""
    scene, eom = derivation.scene, derivation.eom.tidy()
    answers = {}
    for spec in scene.answers:
        value = derivation.answers[spec.name]
        answers[spec.name] = (equation_text(spec.expr, value) if spec.kind == "equation"
                              else sympy.sstr(value))
    # Other right values the engine derived (a special value at several roots nothing decides).
    alternatives = {spec.name: [equation_text(spec.expr, v) if spec.kind == "equation" else sympy.sstr(v)
                                for v in derivation.alternatives[spec.name]]
                    for spec in scene.answers if derivation.alternatives.get(spec.name)}
    return {
        "id": scene.id,
        "equations_of_motion": [equation_text(eom.lhs[q], eom.rhs[q]) for q in scene.coordinates],
        "multipliers": {k: sympy.sstr(v) for k, v in eom.multipliers.items()},
        "constraint_forces": {k: {q: sympy.sstr(v) for q, v in forces.items()}
                              for k, forces in eom.constraint_forces.items()},
        "accelerations": {q: sympy.sstr(v) for q, v in eom.accelerations.items()},
        "answers": answers,
        **({"alternatives": alternatives} if alternatives else {}),
        # Numeric answers without a closed form: the root their unknown is at (grader.expressions.implicit).
        **({"implicit": dict(derivation.implicit)} if derivation.implicit else {}),
    }


def steps_json(steps) -> list[dict]:
    """The step-by-step derivation as JSON: ``[{"title", "text": [...], "latex": [...]}]``."""
    return [{"title": s.title, "text": list(s.text), "latex": list(s.latex)} for s in steps]


def derivation_text(derivation) -> str:
    """The step-by-step derivation as plain text, one step after another."""
    lines = [f"{derivation.scene.title} ({derivation.scene.id})", ""]
    for number, step in enumerate(derivation.steps, start=1):
        lines.append(f"{number}. {step.title}")
        lines += [f"   {line}" for line in step.text]
        lines.append("")
    return "\n".join(lines).rstrip() + "\n"
