"""LaTeX -> MathML on the server: what sympy's latex() and statements write must show as math."""

import pytest
import sympy

from grader.web.student.mathml import to_mathml, unsupported


def test_a_fraction_with_a_squared_dot_reads_as_nested_mathml():
    html = to_mathml(r"\frac{1}{2} m \dot{\theta}^{2}")
    assert "<mfrac><mn>1</mn><mn>2</mn></mfrac>" in html
    assert '<msup><mover accent="true"><mi>θ</mi><mo>˙</mo></mover><mn>2</mn></msup>' in html


def test_a_function_power_applies_to_its_argument():
    # sympy writes sin²θ as \sin^{2}{\left(\theta \right)}: the square sits on "sin", then ⁡ applies it.
    html = to_mathml(sympy.latex(sympy.sin(sympy.Symbol("theta")) ** 2))
    assert "<msup><mi>sin</mi><mn>2</mn></msup><mo>\u2061</mo>" in html


m, g, t, theta, l = sympy.symbols("m g t theta l", positive=True)
SYMPY_OUTPUTS = [
    m * g * (3 * sympy.cos(theta) - 2), sympy.sqrt(g / l) * sympy.sin(theta) ** 2,
    sympy.exp(-t / 2) * sympy.atan2(m, g), sympy.Abs(g - m) / 2, sympy.Symbol("x_1") ** sympy.Rational(3, 2),
    1 / (g + m) ** 3, sympy.Matrix([[1, 2], [3, m]]), sympy.Derivative(sympy.Function("f")(t), t, 2),
    sympy.Eq(m * sympy.Symbol("thetaddot"), -g * sympy.sin(theta)),
]


@pytest.mark.parametrize("expr", SYMPY_OUTPUTS, ids=str)
def test_everything_sympy_writes_for_answers_is_understood(expr):
    tex = sympy.latex(expr)
    assert unsupported(tex) == []
    assert to_mathml(tex).startswith('<math display="inline">')


def test_unknown_commands_show_as_errors_and_are_listed():
    assert "<merror><mtext>\\foo</mtext></merror>" in to_mathml(r"a + \foo")
    assert unsupported(r"a + \foo + \begin{weird}x\end{weird}") == ["\\foo", "\\begin{weird}"]


def test_the_source_is_escaped_never_obeyed():
    html = to_mathml(r"\text{<script>alert(1)</script>} < b")
    assert "<script>" not in html and "&lt;script&gt;" in html


@pytest.mark.parametrize("tex", ["{" * 5000 + "x", "}}}{{{", "\\", r"\frac", r"\sqrt[", r"\left(", "^_^", ""])
def test_broken_or_hostile_tex_never_raises(tex):
    assert to_mathml(tex).startswith("<math")


def test_tex_takes_one_digit_as_an_argument():
    assert "<mfrac><mn>1</mn><mn>2</mn></mfrac>" in to_mathml(r"\tfrac12 m R^2")


def test_display_math_is_a_block():
    assert to_mathml("x", display=True).startswith('<math display="block">')


@pytest.mark.parametrize("tex, subscript", [
    (r"\lambda_{surface}", "<msub><mi>λ</mi><mtext>surface</mtext></msub>"),
    (r"\lambda_surface", "<msub><mi>λ</mi><mtext>surface</mtext></msub>"),  # as authors type it
    (r"\lambda_{\mathrm{surface}}", "<msub><mi>λ</mi><mtext>surface</mtext></msub>"),  # as latex_name writes it
    (r"f_{\mathrm{unwind}}", "<msub><mi>f</mi><mtext>unwind</mtext></msub>"),
    (r"x_{ab}^{2}", "<msubsup><mi>x</mi><mtext>ab</mtext><mn>2</mn></msubsup>"),
])
def test_a_word_subscript_is_upright_text_not_a_product_of_letters(tex, subscript):
    assert subscript in to_mathml(tex)


@pytest.mark.parametrize("tex, subscript", [
    (r"m_{1}", "<msub><mi>m</mi><mn>1</mn></msub>"),
    (r"\lambda_{s}", "<msub><mi>λ</mi><mi>s</mi></msub>"),
    (r"x_a b", "<msub><mi>x</mi><mi>a</mi></msub><mi>b</mi>"),  # letters apart are apart
])
def test_one_letter_and_number_subscripts_stay_as_they_were(tex, subscript):
    assert subscript in to_mathml(tex)
