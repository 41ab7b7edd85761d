r"""Text -> sympy with our own whitelist grammar, plus dimensions, domains and variables.

Used by scene loading (instructor text) and answer checking (student text).
Nothing here calls eval, exec, sympify or parse_expr on input text: a hand-written
tokenizer and Pratt parser build sympy objects directly.

Modules: ``errors`` (ExpressionError, DimensionError), ``dimensions``, ``variables``
(Domain, Variable, Namespace), ``parser`` (entry points), ``tokens``, ``names``
(name resolution and LaTeX names), ``functions`` (the whitelist), ``unicode_input``,
``latex_input`` and ``magnitudes`` (size limits on exact arithmetic).

Examples
--------
>>> from grader.expressions import Namespace, Variable, parse_expression, dimension_of
>>> ns = Namespace([Variable("m", "mass", "positive"), Variable("g", "acceleration", "positive"),
...                 Variable("l", "length", "positive"), Variable("theta", "angle", "real")])
>>> p = parse_expression("m g l (1 - cos θ)", ns)
>>> p.text
'g*l*m*(1 - cos(theta))'
>>> print(p.latex)
g l m \left(1 - \cos{\left(\theta \right)}\right)
>>> dimension_of(p.expr, ns.dimensions()).describe()
'an energy or torque (kg·m²/s²)'
"""

from .dimensions import Dimension, dimension_of, parse_dimension
from .errors import DimensionError, ExpressionError
from .parser import Parsed, ParsedEquation, parse_equation, parse_expression, parse_system
from .variables import Domain, Namespace, Variable, parse_domain

__all__ = [
    "Dimension", "parse_dimension", "dimension_of", "DimensionError",
    "Domain", "parse_domain", "Variable", "Namespace",
    "parse_expression", "parse_equation", "parse_system", "Parsed", "ParsedEquation",
    "ExpressionError",
]
