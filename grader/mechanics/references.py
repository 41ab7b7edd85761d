"""Reference answers in the form the checker takes, so that the service never re-runs the engine.

Each reference answer holds the reference in sympy's str() syntax (our parser reads it back
exactly), the variables a student may use with their dimensions and domains, the instructor's
feedback for known wrong answers (already validated against those variables) and how much slip
feedback may say.

The contract is one typed definition, :class:`grader.answers.reference.ReferenceAnswer`, owned by
the checker that consumes it. The engine comes before the checker in the one-way data flow and may
not import it, so it emits plain JSON objects with exactly that class's keys; the layers after the
engine read them with ``ReferenceAnswer.from_json``, which validates them (a test checks that every
scene's output passes).

Examples
--------
>>> from grader.mechanics.scene import load_scene
>>> from grader.mechanics.lagrange import derive
>>> [r["reference"] for r in derive(load_scene("problems/yoyo.toml")).references()]
['2*g/3', '2*g/(3*R)', 'g*m/3']
"""

from __future__ import annotations

from typing import Any

import sympy

from grader.expressions import ExpressionError, Namespace, parse_expression, parse_system
from grader.mechanics.scene import SceneError
from grader.mechanics.report import equation_text

__all__ = ["reference_answers", "dimension_text", "domain_json", "parameter_specs"]


# Kinds of answer the engine computes differently but the checker compares as expressions.
_CHECKED_AS = {"small_oscillation": "expression", "maximum": "expression", "minimum": "expression"}

def dimension_text(dimension) -> str:
    """A dimension as an ASCII SI expression that ``parse_dimension`` reads back ("kg*m/s^2")."""
    if dimension.is_dimensionless:
        return "dimensionless"
    parts = []
    for unit, exponent in (("kg", dimension.mass), ("m", dimension.length), ("s", dimension.time)):
        if exponent == 0:
            continue
        parts.append(unit if exponent == 1 else f"{unit}^({exponent})" if exponent.denominator != 1
                     else f"{unit}^{exponent}")
    return "*".join(parts)


def domain_json(domain):
    """A domain as the scene format writes it: "positive", "nonnegative", "real" or [lo, hi]."""
    return domain.to_json()


def parameter_specs(scene) -> dict[str, dict[str, Any]]:
    """The parameters that have numbers: ``{name: {"dimension", "value" | "random" | "choices"}}``.

    What the service draws a student's numbers from (``grader.answers.randomised``); parameters
    without a number stay symbolic and are left out.

    Examples
    --------
    >>> from grader.mechanics.scene import load_scene
    >>> parameter_specs(load_scene("problems/yoyo.toml"))["g"]
    {'dimension': 'm*s^-2', 'value': 9.81}
    """
    specs = {}
    for name, p in scene.parameters.items():
        if p.draw is not None:
            specs[name] = {"dimension": dimension_text(p.dimension), **p.draw}
        elif p.value is not None:
            specs[name] = {"dimension": dimension_text(p.dimension), "value": p.value}
    for name, p in scene.parameters.items():
        if p.below is not None and name in specs and p.below in specs:
            specs[name]["below"] = p.below  # a student's numbers keep the order too
    return specs


def _readable_by_the_checker(scene, spec, texts: list[str], namespace: Namespace) -> None:
    """SceneError unless the checker reads every reference text back (a closed form with LambertW or
    a RootOf, which nobody can type, would make every student's answer invalid)."""
    for text in texts:
        try:
            if spec.kind == "equation":
                parse_system(text, namespace, printed=False)
            else:
                parse_expression(text, namespace, printed=False)
        except ExpressionError as error:
            raise SceneError(scene.source, f"answers ({spec.name})",
                             f"the closed form {text} cannot be checked: {error.message}{_what_to_ask(spec)}") from None


# Kinds that have a value only in closed form: kind = "numeric" is another kind, so it cannot ask for them.
_CLOSED_FORM_ONLY = {
    "equation": "an equation is checked in closed form only",
    "small_oscillation": "a small-oscillation frequency is computed in closed form only; the equilibrium "
                         "itself may be asked as kind = \"numeric\"",
    "maximum": "a maximum is computed in closed form only",
    "minimum": "a minimum is computed in closed form only",
}


def _what_to_ask(spec) -> str:
    """What the instructor can do about a closed form the checker cannot read, by the answer's kind."""
    if spec.numeric is not None:
        return ""
    if spec.kind in _CLOSED_FORM_ONLY:
        return f" ({_CLOSED_FORM_ONLY[spec.kind]})"
    return ' (asked as kind = "numeric", it is found numerically)'


def reference_answers(derivation) -> list[dict[str, Any]]:
    """One reference answer (JSON data, see :class:`grader.answers.reference.ReferenceAnswer`) per answer."""
    scene = derivation.scene
    names = scene.namespace.latex_names()
    by_symbol = {v.symbol: v for v in scene.namespace.variables}
    result = []
    for spec in scene.answers:
        value = derivation.answers[spec.name]
        # Every parameter is readable, so an answer may carry factors that cancel (an equation of
        # motion multiplied by m, an acceleration written as a force over m); state variables are
        # limited to what the answer is asked in.
        symbols = set(value.free_symbols) | {p.symbol for p in scene.parameters.values()}
        if spec.in_terms_of is not None:
            symbols |= {scene.namespace.symbol(n) for n in spec.in_terms_of}
        if spec.kind == "equation":
            symbols |= spec.expr.free_symbols
            reference = equation_text(spec.expr, value)
            latex = f"{sympy.latex(spec.expr, symbol_names=names)} = {sympy.latex(value, symbol_names=names)}"
        else:
            reference = sympy.sstr(value)
            latex = sympy.latex(value, symbol_names=names)
        implicit = derivation.implicit.get(spec.name)
        if implicit is not None:
            x = scene.namespace.symbol(implicit["unknown"])
            symbols.add(x)  # the checker reads the condition and the answer in it
            lo, hi = implicit["interval"]
            latex += (rf" \text{{ at root {implicit['root'] + 1} of }} "
                      rf"{sympy.latex(parse_expression(implicit['condition'], scene.namespace).expr, symbol_names=names)}"
                      rf" = 0 \text{{ in }} {names.get(x, str(x))} \in [{lo:g}, {hi:g}]")
        alternatives = []
        for alternative in [*derivation.alternatives.get(spec.name, ()), *spec.alternatives]:
            symbols |= alternative.free_symbols
            alternatives.append(equation_text(spec.expr, alternative) if spec.kind == "equation"
                                else sympy.sstr(alternative))
        variables = {}
        for s in sorted(symbols, key=str):
            v = by_symbol[s]
            variables[v.name] = {"dimension": dimension_text(v.dimension), "domain": domain_json(v.domain),
                                 "kind": v.kind}
            below = scene.parameters[v.name].below if v.name in scene.parameters else None
            if below is not None:
                variables[v.name]["below"] = below  # compared only where d < R, as the scene says
        namespace = Namespace([by_symbol[s] for s in symbols])
        _readable_by_the_checker(scene, spec, [reference, *alternatives], namespace)
        feedback = []
        for i, f in enumerate(spec.feedback):
            try:
                parse_expression(f.expr, namespace)
            except ExpressionError as exc:
                raise SceneError(scene.source, f"answers ({spec.name}).feedback[{i}].expr",
                                 f"{exc.message} in {f.expr!r} (feedback may use only "
                                 f"{', '.join(variables) or 'numbers'})") from None
            feedback.append({"expr": f.expr, "message": f.message,
                             **({"score": f.score} if f.score is not None else {})})
        result.append({"name": spec.name, "prompt": spec.prompt, "kind": _CHECKED_AS.get(spec.kind, spec.kind),
                       "reference": reference,
                       "variables": variables, "dimension": dimension_text(spec.dimension), "latex": latex,
                       "feedback": feedback, "feedback_detail": scene.feedback_detail})
        if alternatives:
            result[-1]["alternatives"] = alternatives
        if spec.weight != 1.0:
            result[-1]["weight"] = spec.weight
        if spec.tests:
            result[-1]["tests"] = [dict(t) for t in spec.tests]
        if spec.numeric is not None:
            numbers = parameter_specs(scene)
            depends = value.free_symbols if implicit is None else (
                value.free_symbols | parse_expression(implicit["condition"], scene.namespace).expr.free_symbols) - {
                scene.namespace.symbol(implicit["unknown"])}
            unknown = sorted(str(s) for s in depends if str(s) not in numbers)
            if unknown:
                raise SceneError(scene.source, f"answers ({spec.name}).kind",
                                 f"a numeric answer needs a number for everything its value depends on; "
                                 f"give {', '.join(unknown)} a value, random range or choices")
            result[-1].update(unit=spec.numeric.unit, parameters=numbers)
            if implicit is not None:
                result[-1]["implicit"] = dict(implicit)
            if spec.numeric.tolerance is not None:
                result[-1]["tolerance"] = dict(spec.numeric.tolerance)
    return result
