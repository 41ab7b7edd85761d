"""Scene files: the instructor's description of a mechanical problem.

A scene file is TOML (one problem per file in ``problems/``). Its keys are a contract that other
tools write, so they are read exactly as documented in ``docs/scene-format.md``. Every expression
in it goes through our whitelist parser (:mod:`grader.expressions`), never through ``eval`` or
``sympify``: scene files are uploaded through the web and are untrusted input.

Errors name the file, the key and the problem, e.g.
``sphere.toml: energy.kinetic: unknown name 'tehta' (did you mean 'theta'?)``.

Examples
--------
>>> scene = parse_scene('''
... id = "drop"
... title = "Falling body"
... statement = "A body falls."
... [parameters]
... m = { dimension = "mass", domain = "positive" }
... g = { dimension = "acceleration", domain = "positive" }
... [coordinates]
... z = { dimension = "length" }
... [energy]
... kinetic = "m/2*zdot^2"
... potential = "m*g*z"
... ''', source="drop.toml")
>>> scene.kinetic
m*zdot**2/2
"""

from __future__ import annotations

import re
import tomllib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Mapping

import sympy

from grader.expressions import (
    Dimension,
    DimensionError,
    Domain,
    ExpressionError,
    Namespace,
    Variable,
    dimension_of,
    parse_dimension,
    parse_domain,
    parse_expression,
)
from grader.expressions.dimensions import parse_unit
from grader.expressions.functions import FUNCTIONS
from grader.mechanics.geometry import Geometry, read_geometry
from grader.mechanics.scene_schema import structure_problems

__all__ = [
    "AnswerSpec",
    "Constraint",
    "Coordinate",
    "FeedbackSpec",
    "NumericSpec",
    "Parameter",
    "Parametrization",
    "Scene",
    "SceneError",
    "load_scene",
    "parse_scene",
]

ENERGY = parse_dimension("energy")
TIME = parse_dimension("time")
_NAME = re.compile(r"^[A-Za-z][A-Za-z0-9_]*$")


def _is_function_name(name: str) -> bool:
    """Whether expressions read ``name`` as a function (sin, ln, dot, ddot): no variable may be named so."""
    return name in FUNCTIONS or name in ("dot", "ddot")
_MAX_SOURCE_BYTES = 256 * 1024
_MAX_ITEMS = 64


class SceneError(ValueError):
    """A scene file that cannot be used, with the file, key and problem named."""

    def __init__(self, source: str, key: str, problem: str):
        self.source, self.key, self.problem = source, key, problem
        super().__init__(f"{source}: {key}: {problem}" if key else f"{source}: {problem}")


@dataclass(frozen=True)
class Parameter:
    name: str
    symbol: sympy.Symbol
    dimension: Dimension
    domain: Domain
    value: float | None = None
    # Drawn per student (docs/scene-format.md, "Randomised parameters"): {"random": {min, max, step}}
    # or {"choices": [...]}, as in the file; the engine keeps the parameter symbolic.
    draw: dict[str, Any] | None = None
    # The name of a parameter of the same dimension this one stays below (d < R).
    below: str | None = None


@dataclass(frozen=True)
class Coordinate:
    """A generalized coordinate q with its velocity q̇ and acceleration q̈ as plain symbols."""

    name: str
    symbol: sympy.Symbol
    dot: sympy.Symbol
    ddot: sympy.Symbol
    dimension: Dimension
    domain: Domain


@dataclass(frozen=True)
class Constraint:
    """A holonomic constraint f(q, t) = 0 and its Lagrange multiplier."""

    name: str
    f: sympy.Expr
    kind: str  # "bilateral" | "unilateral" | "rolling" (the engine treats all three alike)
    multiplier: sympy.Symbol
    dimension: Dimension
    # Effects, read only by grader.simulate (see docs/scene-format.md, "Effects"): expressions in
    # the parameters, so that a simulation with other parameter values uses them too.
    restitution: sympy.Expr = sympy.Integer(0)  # unilateral: Newton's impact law, 0 = inelastic
    mu_s: sympy.Expr | None = None  # rolling: static friction coefficient
    mu_k: sympy.Expr | None = None  # rolling: kinetic friction coefficient
    normal: str | None = None  # rolling: the constraint whose multiplier is the normal force


@dataclass(frozen=True)
class Parametrization:
    """A change of variables for answers: each scene coordinate as a function of new ones."""

    variables: dict[str, Coordinate]
    mapping: dict[sympy.Symbol, sympy.Expr]  # scene coordinate symbol -> expression in new variables


@dataclass(frozen=True)
class FeedbackSpec:
    expr: str
    message: str
    score: float | None = None  # partial credit for an answer that matches expr


@dataclass(frozen=True)
class NumericSpec:
    """How a ``kind = "numeric"`` answer is checked: its unit and tolerance (grader.answers.numeric)."""

    unit: str
    tolerance: dict[str, Any] | None = None


@dataclass(frozen=True)
class AnswerSpec:
    name: str
    prompt: str
    expr: sympy.Expr
    kind: str  # "expression" | "equation"
    in_terms_of: tuple[str, ...] | None
    dimension: Dimension | None
    where: tuple[sympy.Expr, sympy.Expr] | None  # lhs = rhs over answer names and state
    feedback: tuple[FeedbackSpec, ...]
    symbol: sympy.Symbol  # stands for this answer inside later answers and `where`
    source_expr: str
    alternatives: tuple[sympy.Expr, ...] = ()  # other values that are also right (in parameters)
    numeric: NumericSpec | None = None  # kind = "numeric": unit and tolerance
    weight: float = 1.0  # the answer's weight in the problem's score
    tests: tuple[dict[str, Any], ...] = ()  # [[answers.tests]]: {answer, expect, score?, values?}
    at_rest: bool = False  # where = "thetaddot = 0, thetadot = 0": the equilibrium at rest, not passed through


@dataclass
class Scene:
    """A parsed, validated scene. Build it with :func:`load_scene` or :func:`parse_scene`."""

    id: str
    title: str
    statement: str
    source: str
    text: str
    parameters: dict[str, Parameter]
    coordinates: dict[str, Coordinate]
    kinetic: sympy.Expr
    potential: sympy.Expr
    constraints: list[Constraint]
    initial: dict[str, sympy.Expr]
    parametrization: Parametrization | None
    answers: list[AnswerSpec]
    time: sympy.Symbol
    namespace: Namespace
    forces: dict[tuple[str, str], sympy.Symbol] = field(default_factory=dict)
    # [feedback] detail: "kind" (slip messages state no value) or "full" (grader.answers.feedback)
    feedback_detail: str = "kind"
    geometry: Geometry | None = None  # where to draw bodies (pictures only; see geometry.py)
    simulation: dict[str, Any] = field(default_factory=dict)  # [simulation]: t_end, show_students (pictures)

    @property
    def lagrangian(self) -> sympy.Expr:
        return self.kinetic - self.potential

    def answer(self, name: str) -> AnswerSpec:
        for spec in self.answers:
            if spec.name == name:
                return spec
        raise KeyError(name)

    def answer_coordinates(self) -> dict[str, Coordinate]:
        """The coordinates answers are written in: the parametrization's, else the scene's."""
        return self.parametrization.variables if self.parametrization else self.coordinates


def _top_level_parts(text: str) -> list[str]:
    """``text`` split at the commas outside brackets (atan2(y, x) = 0 is one condition).

    >>> _top_level_parts("thetaddot = 0, thetadot = 0")
    ['thetaddot = 0', ' thetadot = 0']
    >>> _top_level_parts("atan2(y, x) = 1")
    ['atan2(y, x) = 1']
    """
    parts, depth, start = [], 0, 0
    for i, character in enumerate(text):
        depth += character in "([{"
        depth -= character in ")]}"
        if character == "," and depth == 0:
            parts.append(text[start:i])
            start = i + 1
    return parts + [text[start:]]


def load_scene(path: str | Path) -> Scene:
    """Read and validate a scene file.

    Examples
    --------
    >>> load_scene("problems/sphere.toml").id
    'sphere'
    """
    path = Path(path)
    try:
        raw = path.read_bytes()
    except OSError as exc:
        raise SceneError(path.name, "", f"cannot read the file ({exc.strerror})") from None
    if len(raw) > _MAX_SOURCE_BYTES:
        raise SceneError(path.name, "", f"file is larger than {_MAX_SOURCE_BYTES // 1024} KiB")
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise SceneError(path.name, "", f"not UTF-8 text (byte {exc.start})") from None
    return parse_scene(text, source=path.name)


def parse_scene(text: str, source: str = "<scene>") -> Scene:
    """Parse scene TOML text into a validated :class:`Scene` (see the module example)."""
    if len(text.encode("utf-8")) > _MAX_SOURCE_BYTES:
        raise SceneError(source, "", f"file is larger than {_MAX_SOURCE_BYTES // 1024} KiB")
    try:
        data = tomllib.loads(text)
        # The keys and their types first (scene_schema.py): a misspelt key is an error, not ignored.
        problems = structure_problems(data)
    except tomllib.TOMLDecodeError as exc:
        raise SceneError(source, "", f"not valid TOML: {exc}") from None
    except RecursionError:  # tomllib and the schema recurse per level of [[[...]]] or {a={b=...}}
        raise SceneError(source, "", "nested too deeply") from None
    if problems:
        raise SceneError(source, *problems[0])
    return _SceneReader(data, source, text).read()


class _SceneReader:
    """Reads one scene file's table, building the namespace as it goes."""

    def __init__(self, data: dict[str, Any], source: str, text: str):
        self.data, self.source, self.text = data, source, text
        self.variables: list[Variable] = []
        self.dimensions: dict[sympy.Symbol, Dimension] = {}

    # -- small helpers ---------------------------------------------------------------------------
    def fail(self, key: str, problem: str) -> SceneError:
        return SceneError(self.source, key, problem)

    def table(self, key: str, required: bool = False) -> dict[str, Any]:
        value = self.data.get(key)
        if value is None:
            if required:
                raise self.fail(key, "missing (required)")
            return {}
        if not isinstance(value, dict):
            raise self.fail(key, "must be a table")
        if len(value) > _MAX_ITEMS:
            raise self.fail(key, f"more than {_MAX_ITEMS} entries")
        return value

    def string(self, table: Mapping[str, Any], key: str, where: str, default: str | None = None) -> str:
        value = table.get(key, default)
        if value is None:
            raise self.fail(f"{where}.{key}" if where else key, "missing (required)")
        if not isinstance(value, str):
            raise self.fail(f"{where}.{key}" if where else key, "must be a string")
        return value

    def check_name(self, key: str, name: str) -> None:
        if not _NAME.match(name) or name.startswith(("lambda_", "Q_")) or name == "t":
            raise self.fail(key, f"'{name}' is not a usable name (letters, digits and _; "
                                 "not t, lambda_..., Q_...)")
        if _is_function_name(name):
            raise self.fail(key, f"'{name}' is the name of a function in expressions; choose another name")

    def add(self, variable: Variable) -> sympy.Symbol:
        if any(v.name == variable.name for v in self.variables):
            raise self.fail(variable.name, f"the name '{variable.name}' is defined twice")
        self.variables.append(variable)
        self.dimensions[variable.symbol] = variable.dimension
        return variable.symbol

    def declared(self, key: str, name: str, spec: Any) -> tuple[Dimension, Domain]:
        """The dimension and domain of a declared name: ``name = { dimension, domain }``."""
        self.check_name(key, name)
        if not isinstance(spec, dict):
            raise self.fail(key, 'must be a table like { dimension = "length", domain = "positive" }')
        return (self.dimension(f"{key}.dimension", spec.get("dimension")),
                self.domain(f"{key}.domain", spec.get("domain")))

    def dimension(self, key: str, spec: Any, default: str | None = None) -> Dimension:
        if spec is None:
            if default is None:
                raise self.fail(key, "missing (required)")
            spec = default
        if not isinstance(spec, str):
            raise self.fail(key, "a dimension is a name such as \"length\" or an SI expression such as \"kg*m^2\"")
        try:
            return parse_dimension(spec)
        except (ValueError, ExpressionError) as exc:
            raise self.fail(key, f"unknown dimension {spec!r}: {exc}") from None

    def domain(self, key: str, spec: Any, default: str = "real") -> Domain:
        try:
            return parse_domain(default if spec is None else spec)
        except (ValueError, TypeError, ExpressionError) as exc:
            raise self.fail(key, f"bad domain {spec!r}: {exc}") from None

    def expression(self, key: str, text: Any, namespace: Namespace) -> sympy.Expr:
        if isinstance(text, (int, float)) and not isinstance(text, bool):
            text = repr(text)
        if not isinstance(text, str):
            raise self.fail(key, "must be an expression in a string")
        try:
            return parse_expression(text, namespace).expr
        except ExpressionError as exc:
            column = f" at column {exc.position + 1}" if getattr(exc, "position", None) is not None else ""
            hint = f" ({exc.hint})" if getattr(exc, "hint", None) else ""
            raise self.fail(key, f"{exc.message}{column} in {text!r}{hint}") from None

    def dimension_of(self, key: str, expr: sympy.Expr) -> Dimension:
        try:
            return dimension_of(expr, self.dimensions)
        except DimensionError as exc:
            raise self.fail(key, f"dimensionally inconsistent: {exc}") from None

    # -- sections ----------------------------------------------------------------------------------
    def read(self) -> Scene:
        scene_id = self.string(self.data, "id", "")
        if not re.match(r"^[a-z0-9][a-z0-9_-]{0,63}$", scene_id):
            raise self.fail("id", "use 1-64 lowercase letters, digits, '-' or '_'")
        title = self.string(self.data, "title", "", default=scene_id)
        statement = self.string(self.data, "statement", "", default="")
        time = self.add(Variable("t", TIME, parse_domain("real"), "time"))

        parameters = self.read_parameters()
        coordinates = self.read_coordinates("coordinates", self.table("coordinates", required=True))
        if not coordinates:
            raise self.fail("coordinates", "a scene needs at least one generalized coordinate")
        state_ns = Namespace(self.variables)
        kinetic, potential = self.read_energy(state_ns)
        constraints = self.read_constraints(state_ns, coordinates)
        forces = self.add_constraint_forces(constraints, coordinates)
        parametrization = self.read_parametrization(coordinates)
        initial = self.read_initial(Namespace(self.variables))
        answers = self.read_answers(coordinates, parametrization)
        geometry = self.read_geometry()
        return Scene(
            id=scene_id, title=title, statement=statement, source=self.source, text=self.text,
            parameters=parameters, coordinates=coordinates, kinetic=kinetic, potential=potential,
            constraints=constraints, initial=initial, parametrization=parametrization,
            answers=answers, time=time, namespace=Namespace(self.variables), forces=forces,
            geometry=geometry, simulation=dict(self.table("simulation")),
            feedback_detail=self.table("feedback").get("detail", "kind"),
        )

    def read_geometry(self) -> Geometry | None:
        namespace = Namespace([v for v in self.variables if v.kind in ("parameter", "coordinate", "time")])
        length = parse_dimension("length")

        def is_length(key: str, expr: sympy.Expr) -> None:
            found = self.dimension_of(key, expr)
            if found != length:
                raise self.fail(key, f"must be a length, not {found.describe()}")

        return read_geometry(self.table("geometry"), lambda key, text: self.expression(key, text, namespace),
                             is_length, self.fail)

    def read_parameters(self) -> dict[str, Parameter]:
        parameters = {}
        for name, spec in self.table("parameters").items():
            key = f"parameters.{name}"
            dim, dom = self.declared(key, name, spec)
            value = spec.get("value")
            if value is not None:
                if isinstance(value, bool) or not isinstance(value, (int, float)):
                    raise self.fail(f"{key}.value", "must be a number")
                if not dom.contains(float(value)):
                    raise self.fail(f"{key}.value", f"{value} is outside the domain")
                value = float(value)
            draw = self.read_draw(key, spec, dom)
            symbol = self.add(Variable(name, dim, dom, "parameter"))
            parameters[name] = Parameter(name, symbol, dim, dom, value, draw, spec.get("below"))
        for p in parameters.values():
            if p.below is not None:
                self.check_below(p, parameters)
        return parameters

    def check_below(self, p: Parameter, parameters: Mapping[str, Parameter]) -> None:
        """``below = "R"``: another parameter of the same dimension, and numbers that keep the order."""
        key = f"parameters.{p.name}.below"
        other = parameters.get(p.below)
        if other is None or other is p:
            raise self.fail(key, f"must name another parameter, got {p.below!r}")
        if other.dimension != p.dimension:
            raise self.fail(key, f"{p.name} is {p.dimension.describe()} and {other.name} "
                                 f"{other.dimension.describe()}: only quantities of one dimension are ordered")
        if p.value is not None and other.value is not None and not p.value < other.value:
            raise self.fail(key, f"{p.name} = {p.value:g} is not below {other.name} = {other.value:g}")
        lows, highs = _numbers(p), _numbers(other)
        if lows and highs and not min(lows) < max(highs):
            raise self.fail(key, f"no values of {p.name} and {other.name} keep {p.name} < {other.name}")

    def read_draw(self, key: str, spec: Mapping[str, Any], domain: Domain) -> dict[str, Any] | None:
        """``random = {min, max, step}`` or ``choices = [...]``: values drawn per student."""
        given = [k for k in ("value", "random", "choices") if spec.get(k) is not None]
        if len(given) > 1:
            raise self.fail(key, f"give one of value, random and choices, not {' and '.join(given)}")
        if spec.get("random") is not None:
            r = spec["random"]
            numbers = {k: r.get(k) for k in ("min", "max", "step")} if isinstance(r, dict) else {}
            for k, v in numbers.items():
                if isinstance(v, bool) or not isinstance(v, (int, float)):
                    raise self.fail(f"{key}.random.{k}", "must be a number")
            if not numbers:
                raise self.fail(f"{key}.random", "write random = { min = ..., max = ..., step = ... }")
            if numbers["step"] <= 0:
                raise self.fail(f"{key}.random.step", "must be positive")
            if numbers["max"] < numbers["min"]:
                raise self.fail(f"{key}.random", "max is less than min")
            if (numbers["max"] - numbers["min"]) / numbers["step"] > 1e6:
                raise self.fail(f"{key}.random.step", "allows more than a million values; use a larger step")
            for k in ("min", "max"):
                if not domain.contains(float(numbers[k])):
                    raise self.fail(f"{key}.random.{k}", f"{numbers[k]} is outside the domain")
            return {"random": numbers}
        if spec.get("choices") is not None:
            choices = spec["choices"]
            if not isinstance(choices, list) or not choices or any(
                    isinstance(c, bool) or not isinstance(c, (int, float)) for c in choices):
                raise self.fail(f"{key}.choices", "must be a non-empty list of numbers")
            outside = [c for c in choices if not domain.contains(float(c))]
            if outside:
                raise self.fail(f"{key}.choices", f"{outside[0]} is outside the domain")
            return {"choices": list(choices)}
        return None

    def read_coordinates(self, where: str, table: Mapping[str, Any]) -> dict[str, Coordinate]:
        coordinates = {}
        for name, spec in table.items():
            key = f"{where}.{name}"
            dim, dom = self.declared(key, name, spec)
            # Its velocity and acceleration are named {name}dot and {name}ddot: a coordinate d would
            # have the acceleration ddot, which expressions read as the function ddot(x).
            clash = next((f"{name}{s}" for s in ("dot", "ddot") if _is_function_name(f"{name}{s}")), None)
            if clash is not None:
                raise self.fail(key, f"the coordinate '{name}' would have a velocity or acceleration named "
                                     f"'{clash}', which is the name of a function in expressions (ddot(x) is "
                                     "ẍ); choose another name for it")
            real = parse_domain("real")
            q = self.add(Variable(name, dim, dom, "coordinate"))
            qd = self.add(Variable(f"{name}dot", dim / TIME, real, "velocity"))
            qdd = self.add(Variable(f"{name}ddot", dim / TIME ** 2, real, "acceleration"))
            coordinates[name] = Coordinate(name, q, qd, qdd, dim, dom)
        return coordinates

    def read_energy(self, namespace: Namespace) -> tuple[sympy.Expr, sympy.Expr]:
        energy = self.table("energy", required=True)
        result = []
        for part in ("kinetic", "potential"):
            key = f"energy.{part}"
            expr = self.expression(key, energy.get(part, "0"), namespace)
            if expr.free_symbols and self.dimension_of(key, expr) != ENERGY:
                raise self.fail(key, f"is {self.dimension_of(key, expr).describe()}, not an energy")
            if any(s.name.endswith("ddot") for s in expr.free_symbols):
                raise self.fail(key, "energies may not depend on accelerations")
            result.append(expr)
        kinetic, potential = result
        if kinetic == 0:
            raise self.fail("energy.kinetic", "a scene needs a kinetic energy")
        if any(str(s).endswith("dot") for s in potential.free_symbols):
            raise self.fail("energy.potential", "the potential may not depend on velocities "
                                                "(velocity-dependent potentials are not supported)")
        return kinetic, potential

    def read_constraints(self, namespace: Namespace, coordinates: dict[str, Coordinate]) -> list[Constraint]:
        raw = self.data.get("constraints", [])
        if not isinstance(raw, list) or not all(isinstance(c, dict) for c in raw):
            raise self.fail("constraints", "write each constraint as a [[constraints]] table")
        if len(raw) >= len(coordinates) + 1:
            raise self.fail("constraints", f"{len(raw)} constraints on {len(coordinates)} coordinates "
                                           "leave no motion")
        coordinate_symbols = {c.symbol for c in coordinates.values()}
        velocity_symbols = {c.dot for c in coordinates.values()} | {c.ddot for c in coordinates.values()}
        constraints = []
        for index, spec in enumerate(raw):
            name = spec.get("name", f"c{index + 1}")
            key = f"constraints[{index}] ({name})"
            if not isinstance(name, str) or not re.match(r"^[A-Za-z][A-Za-z0-9]*$", name):
                raise self.fail(f"constraints[{index}].name", "letters and digits only, e.g. \"string\"")
            if any(c.name == name for c in constraints):
                raise self.fail(f"{key}.name", f"two constraints are named '{name}'")
            f = self.expression(f"{key}.f", self.string(spec, "f", key), namespace)
            if f.free_symbols & velocity_symbols:
                raise self.fail(f"{key}.f", "depends on velocities: only holonomic constraints f(q, t) = 0 "
                                            "are supported")
            if not f.free_symbols & coordinate_symbols:
                raise self.fail(f"{key}.f", "does not involve any coordinate")
            kind = spec.get("kind", "bilateral")
            if kind not in ("bilateral", "unilateral", "rolling"):
                raise self.fail(f"{key}.kind", "must be \"bilateral\", \"unilateral\" or \"rolling\"")
            dim = self.dimension_of(f"{key}.f", f)
            effects = self.read_effects(key, spec, kind, dim)
            multiplier = self.add(Variable(f"lambda_{name}", ENERGY / dim, parse_domain("real"), "multiplier"))
            constraints.append(Constraint(name, f, kind, multiplier, dim, **effects))
        for c in constraints:
            if c.normal is not None:
                normal = next((k for k in constraints if k.name == c.normal and k is not c), None)
                if normal is None or normal.dimension != parse_dimension("length"):
                    raise self.fail(f"constraints ({c.name}).normal", f"'{c.normal}' must name another "
                                    "constraint whose f is a distance from the surface (a length)")
        return constraints

    def read_effects(self, key: str, spec: Mapping[str, Any], kind: str, dim: Dimension) -> dict[str, Any]:
        """The simulation's effect keys of one constraint (numbers or expressions in parameters)."""
        allowed = {"unilateral": {"restitution"}, "rolling": {"mu_s", "mu_k", "normal"}}.get(kind, set())
        stray = sorted({"restitution", "mu_s", "mu_k", "normal"} & set(spec) - allowed)
        if stray:
            raise self.fail(f"{key}.{stray[0]}", f"does not apply to a {kind} constraint")
        parameters = Namespace(self._parameters())
        effects: dict[str, Any] = {}
        for name in sorted(allowed - {"normal"}):
            if name not in spec:
                if kind == "rolling":
                    raise self.fail(f"{key}.{name}", "missing (required for a rolling constraint)")
                continue
            value = self.expression(f"{key}.{name}", spec[name], parameters)
            if value.free_symbols and self.dimension_of(f"{key}.{name}", value) != parse_dimension("dimensionless"):
                raise self.fail(f"{key}.{name}", "must be a dimensionless number")
            if value.is_number and (value < 0 or (name == "restitution" and value > 1)):
                raise self.fail(f"{key}.{name}", "must lie in [0, 1]" if name == "restitution" else "must be >= 0")
            effects[name] = value
        if kind == "rolling":
            if dim != parse_dimension("length"):
                raise self.fail(f"{key}.f", "a rolling constraint's f is the slip of the contact point "
                                            "(a length), e.g. \"s - R*theta\"")
            effects["normal"] = self.string(spec, "normal", key)
        return effects

    def add_constraint_forces(self, constraints: list[Constraint],
                              coordinates: dict[str, Coordinate]) -> dict[tuple[str, str], sympy.Symbol]:
        forces = {}
        for c in constraints:
            for q in coordinates.values():
                variable = Variable(f"Q_{c.name}_{q.name}", ENERGY / q.dimension, parse_domain("real"), "force")
                forces[(c.name, q.name)] = self.add(variable)
        return forces

    def read_parametrization(self, coordinates: dict[str, Coordinate]) -> Parametrization | None:
        spec = self.table("parametrization")
        if not spec:
            return None
        declared = self.table_in(spec, "variables", "parametrization")
        # A variable may be a scene coordinate kept as it is (the cart's X of a pendulum hung from a
        # cart, next to the pendulum's angle): it is that coordinate, and maps to itself.
        kept = {name: self.kept_coordinate(f"parametrization.variables.{name}", coordinates[name], spec_)
                for name, spec_ in declared.items() if name in coordinates}
        new = self.read_coordinates("parametrization.variables",
                                    {n: s for n, s in declared.items() if n not in coordinates})
        variables = {name: kept.get(name) or new[name] for name in declared}
        if not variables:
            raise self.fail("parametrization.variables", "names the new variables; it is empty")
        mapping_spec = dict(self.table_in(spec, "map", "parametrization"))
        namespace = Namespace(self.variables)
        mapping = {c.symbol: c.symbol for c in kept.values()}
        for name, text in mapping_spec.items():
            if name in kept:
                key = f"parametrization.map.{name}"
                if self.expression(key, text, namespace) != kept[name].symbol:
                    raise self.fail(key, f"{name} is also a variable of the parametrization, so it maps to "
                                         f"itself: write {name} = \"{name}\" or leave it out")
                continue
            key = f"parametrization.map.{name}"
            if name not in coordinates:
                raise self.fail(key, f"'{name}' is not a coordinate of the scene")
            expr = self.expression(key, text, namespace)
            allowed = {v.symbol for v in variables.values()} | {p.symbol for p in self._parameters()} | {
                next(v.symbol for v in self.variables if v.name == "t")}
            if not expr.free_symbols <= allowed:
                extra = ", ".join(sorted(str(s) for s in expr.free_symbols - allowed))
                raise self.fail(key, f"may use only parameters, t and the new variables, not {extra}")
            if expr.free_symbols and self.dimension_of(key, expr) != coordinates[name].dimension:
                raise self.fail(key, f"is {self.dimension_of(key, expr).describe()}, but {name} is "
                                     f"{coordinates[name].dimension.describe()}")
            mapping[coordinates[name].symbol] = expr
        missing = [n for n in coordinates if coordinates[n].symbol not in mapping]
        if missing:
            raise self.fail("parametrization.map", f"gives no expression for {', '.join(missing)}")
        return Parametrization(variables, mapping)

    def kept_coordinate(self, key: str, coordinate: Coordinate, spec: Any) -> Coordinate:
        """A parametrization variable named like a scene coordinate: that coordinate, unchanged."""
        dim, dom = self.declared(key, coordinate.name, spec)
        if dim != coordinate.dimension:
            raise self.fail(f"{key}.dimension", f"is {dim.describe()}, but the scene coordinate {coordinate.name} "
                                                f"it keeps is {coordinate.dimension.describe()}")
        if spec.get("domain") is not None and dom != coordinate.domain:
            raise self.fail(f"{key}.domain", f"differs from the domain of the scene coordinate {coordinate.name} "
                                             "it keeps; declare the domain once, in [coordinates]")
        return coordinate

    def table_in(self, table: Mapping[str, Any], key: str, where: str) -> dict[str, Any]:
        value = table.get(key, {})
        if not isinstance(value, dict):
            raise self.fail(f"{where}.{key}", "must be a table")
        return value

    def _parameters(self) -> list[Variable]:
        return [v for v in self.variables if v.kind == "parameter"]

    def read_initial(self, namespace: Namespace) -> dict[str, sympy.Expr]:
        allowed = {v.name: v for v in self.variables if v.kind in ("coordinate", "velocity")}
        parameter_symbols = {p.symbol for p in self._parameters()}
        initial = {}
        for name, text in self.table("initial").items():
            key = f"initial.{name}"
            if name not in allowed:
                raise self.fail(key, f"'{name}' is not a coordinate or a velocity")
            expr = self.expression(key, text, namespace)
            if not expr.free_symbols <= parameter_symbols:
                raise self.fail(key, "may use numbers and parameters only")
            if expr.free_symbols and self.dimension_of(key, expr) != allowed[name].dimension:
                raise self.fail(key, f"is {self.dimension_of(key, expr).describe()}, but {name} is "
                                     f"{allowed[name].dimension.describe()}")
            initial[name] = expr
        return initial

    def read_answers(self, coordinates: dict[str, Coordinate],
                     parametrization: Parametrization | None) -> list[AnswerSpec]:
        raw = self.data.get("answers", [])
        if not isinstance(raw, list) or not all(isinstance(a, dict) for a in raw):
            raise self.fail("answers", "write each answer as an [[answers]] table")
        if len(raw) > _MAX_ITEMS:
            raise self.fail("answers", f"more than {_MAX_ITEMS} answers")
        answers: list[AnswerSpec] = []
        known = {v.name for v in self.variables}
        for index, spec in enumerate(raw):
            name = self.string(spec, "name", f"answers[{index}]")
            key = f"answers[{index}] ({name})"
            self.check_name(f"{key}.name", name)
            if name in known:
                raise self.fail(f"{key}.name", f"'{name}' is already a name in the scene")
            namespace = Namespace(self.variables)
            source_expr = self.string(spec, "expr", key)
            expr = self.expression(f"{key}.expr", source_expr, namespace)
            kind = spec.get("kind", "expression")
            if kind not in ("expression", "equation", "small_oscillation", "maximum", "minimum", "numeric"):
                raise self.fail(f"{key}.kind", "must be \"expression\", \"equation\", \"small_oscillation\", "
                                               "\"maximum\", \"minimum\" or \"numeric\"")
            if kind == "small_oscillation" and (spec.get("where") is None
                                                or expr not in {v.symbol for v in self.variables
                                                                if v.kind == "coordinate"}):
                raise self.fail(f"{key}.kind", "a small_oscillation answer names the oscillating coordinate "
                                               "in expr and its equilibrium in where")
            in_terms_of = spec.get("in_terms_of")
            if in_terms_of is not None:
                if not isinstance(in_terms_of, list) or not all(isinstance(n, str) for n in in_terms_of):
                    raise self.fail(f"{key}.in_terms_of", "must be a list of names")
                unknown = [n for n in in_terms_of if n not in known or n.startswith(("lambda_", "Q_"))]
                if unknown:
                    raise self.fail(f"{key}.in_terms_of", f"unknown or unusable name(s): {', '.join(unknown)}")
                in_terms_of = tuple(in_terms_of)
            dimension = None
            if spec.get("dimension") is not None:
                dimension = self.dimension(f"{key}.dimension", spec["dimension"])
            inferred = self.dimension_of(f"{key}.expr", expr)
            if kind == "small_oscillation":
                inferred = parse_dimension("frequency")  # the angular frequency of the oscillation
            if dimension is not None and inferred != dimension:
                raise self.fail(f"{key}.dimension", f"the expression is {inferred.describe()}, "
                                                    f"not {dimension.describe()}")
            where, at_rest = None, False
            if spec.get("where") is not None:
                where, at_rest = self.read_where(f"{key}.where", spec["where"], namespace)
            feedback = self.read_feedback(key, spec.get("feedback", []))
            alternatives = self.read_alternatives(key, spec.get("alternatives", []), namespace, inferred,
                                                  {a.symbol for a in answers})
            prompt = self.string(spec, "prompt", key, default=name.replace("_", " "))
            numeric = self.read_numeric(key, spec, kind, dimension or inferred)
            weight = spec.get("weight", 1.0)
            if isinstance(weight, bool) or not isinstance(weight, (int, float)) or not 0 <= weight < 1e6:
                raise self.fail(f"{key}.weight", "must be a number >= 0")
            tests = self.read_tests(key, spec.get("tests", []))
            symbol = self.add(Variable(name, inferred, parse_domain("real"), "answer"))
            known.add(name)
            answers.append(AnswerSpec(name, prompt, expr, kind, in_terms_of, dimension or inferred,
                                      where, feedback, symbol, source_expr, alternatives, numeric,
                                      float(weight), tests, at_rest))
        return answers

    def read_numeric(self, key: str, spec: Mapping[str, Any], kind: str, dimension: Dimension) -> NumericSpec | None:
        """``unit`` and ``tolerance`` of a numeric answer (checked by grader.answers.numeric)."""
        if kind != "numeric":
            extra = [k for k in ("unit", "tolerance") if k in spec]
            if extra:
                raise self.fail(f"{key}.{extra[0]}", 'applies to kind = "numeric" answers only')
            return None
        unit = spec.get("unit")
        if unit is None:
            if not dimension.is_dimensionless:
                raise self.fail(f"{key}.unit", f"missing: a numeric answer that is {dimension.describe()} "
                                               "states its unit (such as \"N\")")
            unit = ""
        try:
            _, unit_dimension = parse_unit(unit)
        except (ValueError, ExpressionError) as exc:
            raise self.fail(f"{key}.unit", str(exc)) from None
        if unit_dimension != dimension:
            raise self.fail(f"{key}.unit", f"{unit!r} is {unit_dimension.describe()}, but the answer is "
                                           f"{dimension.describe()}")
        tolerance = spec.get("tolerance")
        if tolerance is not None:
            for k in ("relative", "absolute"):
                v = tolerance.get(k)
                if v is not None and not (isinstance(v, (int, float)) and not isinstance(v, bool) and 0 <= v < 1e300):
                    raise self.fail(f"{key}.tolerance.{k}", "must be a number >= 0")
            figures = tolerance.get("sig_figs")
            if figures is not None and (isinstance(figures, bool) or not isinstance(figures, int)
                                        or not 1 <= figures <= 15):
                raise self.fail(f"{key}.tolerance.sig_figs", "must be a whole number from 1 to 15")
            if not tolerance:
                raise self.fail(f"{key}.tolerance", "give relative, absolute or sig_figs")
            tolerance = dict(tolerance)
        return NumericSpec(unit, tolerance)

    def read_tests(self, key: str, raw: Any) -> tuple[dict[str, Any], ...]:
        """``[[answers.tests]]``: example answers and the verdict each must get (grader.answers.question_tests)."""
        if not isinstance(raw, list) or not all(isinstance(t, dict) for t in raw):
            raise self.fail(f"{key}.tests", "write each test as [[answers.tests]] with answer and expect")
        parameters = {v.name for v in self.variables if v.kind == "parameter"}
        tests = []
        for i, test in enumerate(raw):
            where = f"{key}.tests[{i}]"
            entry = {"answer": self.string(test, "answer", where), "expect": self.string(test, "expect", where)}
            if entry["expect"] not in ("equivalent", "not_equivalent", "invalid"):
                raise self.fail(f"{where}.expect", 'must be "equivalent", "not_equivalent" or "invalid"')
            if test.get("score") is not None:
                score = test["score"]
                if isinstance(score, bool) or not isinstance(score, (int, float)) or not 0 <= score <= 1:
                    raise self.fail(f"{where}.score", "must be a number from 0 to 1")
                entry["score"] = float(score)
            if test.get("values") is not None:
                unknown = [n for n in test["values"] if n not in parameters]
                if unknown:
                    raise self.fail(f"{where}.values", f"{unknown[0]!r} is not a parameter")
                entry["values"] = {n: float(v) for n, v in test["values"].items()}
            tests.append(entry)
        return tuple(tests)

    def read_alternatives(self, key: str, raw: Any, namespace: Namespace, dimension: Dimension,
                          answer_symbols: set) -> tuple[sympy.Expr, ...]:
        """``alternatives = ["-acos(g/(omega^2*l))"]``: other values of the answer that are also right."""
        if not isinstance(raw, list):
            raise self.fail(f"{key}.alternatives", "must be a list of expressions")
        alternatives = []
        for i, text in enumerate(raw):
            where = f"{key}.alternatives[{i}]"
            value = self.expression(where, text, namespace)
            if value.free_symbols & answer_symbols:
                raise self.fail(where, "may use the scene's parameters and coordinates, not other answers")
            got = self.dimension_of(where, value)
            if got != dimension:
                raise self.fail(where, f"is {got.describe()}, but the answer is {dimension.describe()}")
            alternatives.append(value)
        return tuple(alternatives)

    def read_where(self, key: str, text: Any, namespace: Namespace) -> tuple[tuple[sympy.Expr, sympy.Expr], bool]:
        """The condition lhs = rhs, and whether it is an equilibrium asked at rest.

        Several conditions, separated by commas, are read only as an equilibrium at rest: an
        acceleration set to zero and velocities set to zero (``"thetaddot = 0, thetadot = 0"``: the
        tension in a pendulum hanging at rest in an accelerating car, where ``[initial]`` would
        otherwise have it swing through that angle).
        """
        if not isinstance(text, str):
            raise self.fail(key, "write a condition such as \"normal_force = 0\"")
        conditions = [self._condition(key, part, namespace) for part in _top_level_parts(text)]
        if len(conditions) == 1:
            return conditions[0], False
        velocities = {v.symbol for v in self.variables if v.kind == "velocity"}
        accelerations = {v.symbol for v in self.variables if v.kind == "acceleration"}
        at_rest = [c for c in conditions if c[0] in velocities and c[1] == 0]
        others = [c for c in conditions if c not in at_rest]
        if len(others) != 1 or others[0][1] != 0 or not others[0][0].free_symbols & accelerations:
            raise self.fail(key, "several conditions are read only as an equilibrium at rest: an acceleration "
                                 "set to zero and velocities set to zero, as in \"thetaddot = 0, thetadot = 0\"")
        return others[0], True

    def _condition(self, key: str, text: str, namespace: Namespace) -> tuple[sympy.Expr, sympy.Expr]:
        if text.count("=") != 1:
            raise self.fail(key, "write a condition such as \"normal_force = 0\"")
        lhs_text, rhs_text = text.split("=")
        lhs = self.expression(key, lhs_text, namespace)
        rhs = self.expression(key, rhs_text, namespace)
        self.dimension_of(key, lhs - rhs)
        return lhs, rhs

    def read_feedback(self, key: str, raw: Any) -> tuple[FeedbackSpec, ...]:
        if not isinstance(raw, list) or not all(isinstance(f, dict) for f in raw):
            raise self.fail(f"{key}.feedback", "write each entry as [[answers.feedback]] with expr and message")
        entries = []
        for i, f in enumerate(raw):
            score = f.get("score")
            if score is not None and (isinstance(score, bool) or not isinstance(score, (int, float))
                                      or not 0 <= score <= 1):
                raise self.fail(f"{key}.feedback[{i}].score", "must be a number from 0 to 1 (the share of the "
                                                               "answer's points)")
            entries.append(FeedbackSpec(self.string(f, "expr", f"{key}.feedback[{i}]"),
                                        self.string(f, "message", f"{key}.feedback[{i}]"),
                                        None if score is None else float(score)))
        return tuple(entries)


def _numbers(p: Parameter) -> list[float]:
    """The numbers a parameter may take: its value, its random range's ends or its choices."""
    if p.value is not None:
        return [p.value]
    if p.draw and "random" in p.draw:
        return [float(p.draw["random"]["min"]), float(p.draw["random"]["max"])]
    if p.draw and "choices" in p.draw:
        return [float(c) for c in p.draw["choices"]]
    return []
