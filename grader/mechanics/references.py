"""Reference answers in the form the checker takes, so that the service never re-runs the engine.

Each :class:`ReferenceAnswer` holds the reference in sympy's str() syntax (our parser reads it
back exactly), the variables a student may use with their dimensions and domains, and the
instructor's feedback for known wrong answers, already validated against those variables.

Examples
--------
>>> from grader.mechanics.scene import load_scene
>>> from grader.mechanics.lagrange import derive
>>> [r.reference for r in derive(load_scene("problems/yoyo.toml")).references()]
['2*g/3', '2*g/(3*R)', 'g*m/3']
"""

from __future__ import annotations

from dataclasses import asdict, dataclass, field

import sympy

from grader.expressions import ExpressionError, Namespace, parse_expression
from grader.mechanics.scene import SceneError
from grader.mechanics.report import equation_text

__all__ = ["ReferenceAnswer", "reference_answers", "dimension_text", "domain_json"]


@dataclass(frozen=True)
class ReferenceAnswer:
    name: str
    prompt: str
    kind: str
    reference: str
    variables: dict[str, dict]
    dimension: str
    latex: str
    feedback: list[dict] = field(default_factory=list)

    def to_json(self) -> dict:
        return asdict(self)


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


def reference_answers(derivation) -> list[ReferenceAnswer]:
    """One :class:`ReferenceAnswer` per answer of the derived scene."""
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
        variables = {}
        for s in sorted(symbols, key=str):
            v = by_symbol[s]
            variables[v.name] = {"dimension": dimension_text(v.dimension), "domain": domain_json(v.domain),
                                 "kind": v.kind}
        namespace = Namespace([by_symbol[s] for s in symbols])
        feedback = []
        for i, f in enumerate(spec.feedback):
            try:
                parse_expression(f.expr, namespace)
            except ExpressionError as exc:
                raise SceneError(scene.source, f"answers ({spec.name}).feedback[{i}].expr",
                                 f"{exc.message} in {f.expr!r} (feedback may use only "
                                 f"{', '.join(variables) or 'numbers'})") from None
            feedback.append({"expr": f.expr, "message": f.message})
        result.append(ReferenceAnswer(spec.name, spec.prompt, spec.kind, reference, variables,
                                      dimension_text(spec.dimension), latex, feedback))
    return result
