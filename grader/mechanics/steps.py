"""A step-by-step derivation like the paper's: L', partial derivatives, equations, solution.

Each :class:`Step` carries the same content as text (sympy str syntax) and as LaTeX, for the
instructor's review page and, after the deadline, for students.

Examples
--------
>>> from grader.mechanics.scene import load_scene
>>> from grader.mechanics.lagrange import derive
>>> [s.title for s in derive(load_scene("problems/yoyo.toml")).steps][:2]
['Lagrangian', 'Constraints and the extended Lagrangian']
"""

from __future__ import annotations

from dataclasses import dataclass, field

import sympy

__all__ = ["Step", "derivation_steps"]


@dataclass
class Step:
    title: str
    text: list[str] = field(default_factory=list)
    latex: list[str] = field(default_factory=list)

    def add(self, text: str, latex: str) -> None:
        self.text.append(text)
        self.latex.append(latex)


def derivation_steps(derivation) -> list[Step]:
    """The derivation of a scene as a list of steps (see the module docstring)."""
    scene, eom = derivation.scene, derivation.eom.tidy()
    names = scene.namespace.latex_names()

    def tex(expr) -> str:
        return sympy.latex(expr, symbol_names=names)

    def eq(lhs_text, lhs_tex, rhs) -> tuple[str, str]:
        return f"{lhs_text} = {sympy.sstr(rhs)}", f"{lhs_tex} = {tex(rhs)}"

    steps = []
    s = Step("Lagrangian")
    s.add(*eq("T", "T", scene.kinetic))
    s.add(*eq("V", "V", scene.potential))
    s.add(*eq("L = T - V", "L = T - V", scene.lagrangian))
    steps.append(s)

    s = Step("Constraints and the extended Lagrangian")
    if not scene.constraints:
        s.add("No constraints: L' = L.", r"\text{No constraints: } L' = L")
    for k in scene.constraints:
        s.add(f"f_{k.name} = {sympy.sstr(k.f)} = 0 ({k.kind})",
              rf"f_{{\mathrm{{{k.name}}}}} = {tex(k.f)} = 0 \quad (\text{{{k.kind}}})")
    extended = scene.lagrangian + sum((k.multiplier * k.f for k in scene.constraints), sympy.Integer(0))
    s.add(*eq("L' = L + sum(lambda_i*f_i)", r"L' = L + \sum_i \lambda_i f_i", extended))
    steps.append(s)

    for q in scene.coordinates.values():
        p = eom.partials[q.name]
        # Titles are text with $...$ math (the pages render it): the coordinate as θ, not "theta".
        s = Step(f"Partial derivatives for ${tex(q.symbol)}$")
        s.add(*eq(f"dL/d{q.name}", rf"\frac{{\partial L}}{{\partial {tex(q.symbol)}}}", p["dL_dq"]))
        s.add(*eq(f"dL/d{q.dot.name}", rf"\frac{{\partial L}}{{\partial {tex(q.dot)}}}", p["dL_dqdot"]))
        s.add(*eq(f"d/dt dL/d{q.dot.name}", rf"\frac{{d}}{{dt}}\frac{{\partial L}}{{\partial {tex(q.dot)}}}",
                  p["ddt_dL_dqdot"]))
        for k in scene.constraints:
            s.add(*eq(f"df_{k.name}/d{q.name}",
                      rf"\frac{{\partial f_{{\mathrm{{{k.name}}}}}}}{{\partial {tex(q.symbol)}}}",
                      p[f"df_{k.name}"]))
        steps.append(s)

    s = Step("Euler-Lagrange equations with multipliers")
    for q in scene.coordinates:
        s.add(f"{sympy.sstr(eom.lhs[q])} = {sympy.sstr(eom.rhs[q])}", f"{tex(eom.lhs[q])} = {tex(eom.rhs[q])}")
    steps.append(s)

    s = Step("Solution for accelerations and multipliers")
    for q in scene.coordinates.values():
        s.add(*eq(q.ddot.name, tex(q.ddot), eom.accelerations[q.name]))
    for k in scene.constraints:
        s.add(*eq(k.multiplier.name, tex(k.multiplier), eom.multipliers[k.name]))
    steps.append(s)

    if scene.constraints:
        s = Step(r"Generalized constraint forces $Q = \lambda\, \partial f/\partial q$")
        for k in scene.constraints:
            for q in scene.coordinates.values():
                symbol = scene.forces[(k.name, q.name)]
                s.add(*eq(symbol.name, tex(symbol), eom.constraint_forces[k.name][q.name]))
        steps.append(s)

    s = Step("Answers")
    for spec in scene.answers:
        value = derivation.answers[spec.name]
        where = f" where {sympy.sstr(spec.where[0])} = {sympy.sstr(spec.where[1])}" if spec.where else ""
        where += ", at rest" if spec.at_rest else ""
        if spec.kind == "small_oscillation":
            s.add(f"{spec.name} = frequency of small oscillations of {sympy.sstr(spec.expr)} about the "
                  f"equilibrium{where} = sqrt(-d({spec.expr}ddot)/d{spec.expr}) = {sympy.sstr(value)}",
                  rf"\text{{{_tex_text(spec.name)}}} = \sqrt{{-\partial \ddot{{{tex(spec.expr)}}}/"
                  rf"\partial {tex(spec.expr)}}} = {tex(value)}")
        elif spec.kind == "equation":
            s.add(f"{spec.name}: {sympy.sstr(spec.expr)} = {sympy.sstr(value)}",
                  rf"\text{{{_tex_text(spec.name)}}}: {tex(spec.expr)} = {tex(value)}")
        elif spec.name in derivation.implicit:
            rule = derivation.implicit[spec.name]
            at = (f"at root {rule['root'] + 1} (counted upwards) of {rule['condition']} = 0 for {rule['unknown']} "
                  f"in [{rule['interval'][0]:g}, {rule['interval'][1]:g}]")
            s.add(f"{spec.name} = {sympy.sstr(spec.expr)}{where} = {sympy.sstr(value)} {at}: no closed form, "
                  "found numerically at each student's numbers",
                  rf"\text{{{_tex_text(spec.name)}}} = {tex(value)} \text{{ {at}, found numerically}}")
        else:
            s.add(f"{spec.name} = {sympy.sstr(spec.expr)}{where} = {sympy.sstr(value)}",
                  rf"\text{{{_tex_text(spec.name)}}} = {tex(spec.expr)} = {tex(value)}")
    steps.append(s)
    return steps


def _tex_text(name: str) -> str:
    # An answer's name as a label: underscores read as spaces ("angular acceleration").
    return name.replace("_", " ")
