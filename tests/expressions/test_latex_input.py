"""The LaTeX subset."""

import pytest

from grader.expressions import ExpressionError
from grader.expressions.latex_input import classify_command, subscript_text


@pytest.mark.parametrize("command, expected", [
    ("theta", ("greek", "theta")), ("varphi", ("greek", "phi")), ("Omega", ("greek", "Omega")),
    ("pi", ("greek", "pi")), ("sin", ("function", "sin")), ("arctan", ("function", "atan")),
    ("cdot", ("op", "*")), ("times", ("op", "*")), ("div", ("op", "/")), ("quad", ("space", "")),
    ("dfrac", ("structure", "frac")), ("sqrt", ("structure", "sqrt")), ("ddot", ("structure", "ddot")),
    ("mathrm", ("wrapper", "mathrm")),
])
def test_commands(command, expected):
    assert classify_command(command, 0) == expected


@pytest.mark.parametrize("command", ["int", "sum", "partial", "infty", "input", "def"])
def test_other_commands_are_refused_by_name(command):
    with pytest.raises(ExpressionError) as err:
        classify_command(command, 3)
    assert err.value.code == "unsupported_function" and f"\\{command}" in err.value.message


@pytest.mark.parametrize("content, name", [("1", "1"), ("roll,s", "roll_s"), ("\\mathrm{roll}, s", "roll_s"),
                                          ("\\text{surface}", "surface"), ("\\theta", "theta")])
def test_subscripts(content, name):
    assert subscript_text(content, 0) == name


@pytest.mark.parametrize("content", ["", "a+b", "\\frac{1}{2}"])
def test_subscripts_must_be_names(content):
    with pytest.raises(ExpressionError):
        subscript_text(content, 0)


# -- red team 2026-11 ---------------------------------------------------------------------------

@pytest.mark.parametrize("command, expected", [
    ("big", ("space", "")), ("Big", ("space", "")), ("bigg", ("space", "")), ("Bigg", ("space", "")),
    ("bigm", ("space", "")), ("Biggm", ("space", "")), ("bigl", ("structure", "bigl")),
    ("Bigr", ("structure", "bigr")), ("biggl", ("structure", "bigl")), ("Biggr", ("structure", "bigr")),
    ("mid", ("structure", "vert")), ("scriptstyle", ("space", "")),
])
def test_bracket_sizes_and_bars(command, expected):
    assert classify_command(command, 0) == expected


# -- answers from math input editors and OCR (MathQuill, MathLive, Mathpix, Word's LaTeX) ---------------

from grader.expressions import parse_equation, parse_expression, parse_system  # noqa: E402


@pytest.mark.parametrize("latex, plain", [
    # MathLive's own spellings: \mleft( \mright), \exponentialE, \differentialD, ^{\doubleprime}
    (r"m\cdot g\cdot\cos\mleft(\theta\mright)", "m g cos(theta)"),
    (r"\exponentialE^{-\frac{t}{\sqrt{l/g}}}", "exp(-t sqrt(g/l))"),
    (r"l\left(\frac{\differentialD\theta}{\differentialD t}\right)^{2}", "l thetadot^2"),
    (r"\frac{\differentialD^{2}\theta}{\differentialD t^{2}}", "thetaddot"),
    (r"\theta^{\doubleprime}", "thetaddot"), (r"\theta^\doubleprime", "thetaddot"),
    # Mathpix's \cfrac; \bullet for a product; \lbrace \rbrace and \lbrack \rbrack as brackets
    (r"\cfrac{g}{l}", "g/l"), (r"m \bullet g", "m g"),
    (r"m\lbrace g+l \rbrace", "m (g + l)"), (r"m\lbrack g+l \rbrack", "m (g + l)"),
    # a name in another font is the name: bold, sans-serif, upright Greek
    (r"\boldsymbol{m}\,\boldsymbol{g}\cos\boldsymbol{\theta}", "m g cos(theta)"),
    (r"\bm{m}\mathsf{g}\,\textit{l}\,\textbf{r}", "m g l r"), (r"\ddot{\boldsymbol{\theta}}", "thetaddot"),
    (r"2\uppi\sqrt{\frac{l}{g}}", "2 pi sqrt(l/g)"), (r"\uptheta", "theta"),
    # \left\lvert … \right\rvert is |…|
    (r"\left\lvert x\right\rvert", "abs(x)"), (r"\left\vert x\right\vert", "abs(x)"),
    # dots set over a letter, as Word's and some OCR's LaTeX write them
    (r"\overset{\cdot}{\theta}", "thetadot"), (r"\overset{.}{\theta}", "thetadot"),
    (r"\overset{\cdot\cdot}{\theta}", "thetaddot"), (r"\overset{..}{\theta}", "thetaddot"),
    (r"\stackrel{.}{r}", "rdot"),
    # LaTeX's ~ (a non-breaking space) and \mathrm{2} (digits set upright)
    (r"m~g~\cos\theta", "m g cos(theta)"), (r"\mathrm{m}\mathrm{g}\left(3\mathrm{cos}\theta-\mathrm{2}\right)",
                                            "m g (3 cos(theta) - 2)"),
    # spacing alone in a wrapper, a full stop or a comma closing the sentence the formula was set in
    (r"m g\text{ }l", "m g l"), (r"m g \text {. }", "m g"), (r"m g \text{,}", "m g"), ("m g,", "m g"),
    # Spanish and Portuguese sine (Mathpix writes \operatorname{sen}; babel-spanish has \sen)
    (r"\operatorname{sen}\theta", "sin(theta)"), (r"\mathrm{sen}\,\theta", "sin(theta)"), (r"\sen\theta", "sin(theta)"),
    ("sen(theta)", "sin(theta)"), (r"\operatorname{senh}\theta", "sinh(theta)"),
    # an implication before the only line: "so"
    (r"\Rightarrow T = m g", "m g"), (r"\therefore T = m g", "m g"), ("∴ T = m g", "m g"), ("⇒ T = m g", "m g"),
])
def test_editor_and_ocr_latex_reads_as_the_plain_text(ns, latex, plain):
    assert parse_expression(latex, ns).expr == parse_expression(plain, ns).expr


@pytest.mark.parametrize("latex, plain", [
    (r"\implies \ddot{\theta}+\frac{g}{l}\sin\theta=0", "thetaddot + g/l sin(theta) = 0"),
    (r"\Longrightarrow \ddot{\theta}=-\frac{g}{l}\sin\theta", "thetaddot = -g/l sin(theta)"),
    (r"\ddot{\theta}&=-\frac{g}{l}\sin\theta", "thetaddot = -g/l sin(theta)"),   # a line copied out of align
    (r"\ddot{\theta}=-\frac{g}{l}\sin\theta \label{eq:1}", "thetaddot = -g/l sin(theta)"),
    (r"\ddot{\theta}=-\frac{g}{l}\sin\theta \nonumber", "thetaddot = -g/l sin(theta)"),
])
def test_editor_equations_read_as_the_plain_equation(ns, latex, plain):
    got, expected = parse_equation(latex, ns), parse_equation(plain, ns)
    assert (got.lhs, got.rhs) == (expected.lhs, expected.rhs)


@pytest.mark.parametrize("latex", [
    r"\left\{\begin{aligned} x &= l \\ y &= 2 l \end{aligned}\right.",
    r"\begin{alignat}{2} x &= l \\ y &= 2 l \end{alignat}",
    r"x = l \text{ and } y = 2 l", r"x = l \quad\text{and}\quad y = 2 l",
    # a wide space between two whole equations sets them side by side (Mathpix)
    r"x = l \qquad y = 2 l", r"x = l \quad (1) \qquad y = 2 l \quad (2)",
    # and an equation's number before it, (1) \quad x = l, is no factor
    r"(1)\quad x = l \\ (2)\quad y = 2 l", r"(1)\quad x = l \qquad (2)\quad y = 2 l",
])
def test_a_system_in_a_brace_or_joined_by_and_is_its_equations(ns, latex):
    assert [(eq.lhs, eq.rhs) for eq in parse_system(latex, ns)] == \
        [(eq.lhs, eq.rhs) for eq in parse_system("x = l; y = 2 l", ns)]


@pytest.mark.parametrize("latex, named", [
    # MathLive's empty box, and an empty subscript box
    (r"m g^{\placeholder{}}", r"empty box (\placeholder)"), (r"\frac{\placeholder{}}{l}", r"empty box (\placeholder)"),
    (r"m_{\placeholder{}}", r"empty box (\placeholder)"), (r"\dot{\theta}_{}", "the subscript is empty"),
    # units after the answer, as Mathpix and Word set them: named as units, never read as variables
    (r"m g \mathrm{~N}", r"'\mathrm{~N}' reads as a unit"), (r"l \mathrm{~m}", r"'\mathrm{~m}' reads as a unit"),
    (r"l\text{ m}", r"'\text{ m}' reads as a unit"), (r"g\;\mathrm{m/s^2}", r"'\mathrm{m/s^2}' reads as a unit"),
    (r"g\,\frac{\mathrm{m}}{\mathrm{s}^2}", r"'\mathrm{s}': units are not part of the answer"),
    (r"m g \text{ newtons}", "reads as a unit"),
    # words; "and" joins two equations, not two expressions
    (r"x \text{ and } l", r"'\text{ and }' cannot be used in a single expression"),
    (r"m g\qquad\text{(tension)}", r"'\text{(tension)}' is text"), (r"\mathrm{m g \cos\theta}", "is text"),
    # relations that are not an equation
    (r"T \approx m g", r"'\approx' (approximately equal) is not an equation"),
    (r"T \simeq m g", r"'\simeq'"), (r"T \equiv m g", r"'\equiv'"), (r"T \propto m", r"'\propto'"),
    (r"T \neq m g", r"'\neq' (not equal)"), (r"T \leq m g", r"'\leq' is an inequality"),
    (r"T \to m g", r"'\to' is an arrow"),
    # a derivation: the steps before the arrow are not the answer
    (r"x - l = 0 \Rightarrow x = l", r"'\Rightarrow' joins two steps of a derivation"),
    ("x = l ⟹ x - l = 0", "'⟹' joins two steps of a derivation"),
    (r"\theta = 0 \\ \Rightarrow T = m g", r"'\Rightarrow' joins two steps of a derivation"),
    (r"x \Rightarrow l", r"'\Rightarrow' is an arrow"),   # where the '=' belongs
    (r"x = l \implies", r"'\implies' at the end leads to nothing"),
    ("x = l ⇒ $", "'⇒' at the end leads to nothing"),
    # norms, vectors, TeX's \over, complex numbers, a mark over a letter that is no dot
    (r"\left\| x \right\|", "(a norm)"), (r"\|x\|", "(a norm)"), (r"\Vert x\Vert", "(a norm)"),
    (r"\vec{T} = m g", "(a vector)"), (r"{m \over g}", r"'\over'"), (r"x \imaginaryI", "complex numbers"),
    (r"\overset{\rightarrow}{x}", "(a mark over a letter)"),
    # ~ in plain text: 'approximately', or a space?
    ("x ~ l", "'~' reads as 'approximately' or as a LaTeX space"),
    (r"x ~ \frac{l}{2}", "'~' reads as 'approximately' or as a LaTeX space"),   # set apart: 'about
    # & that is no alignment point
    (r"\ddot{\theta}&-g", "'&' (a LaTeX alignment mark)"),
    # Typst's and speech's "theta dot": which name is dotted?
    ("l theta dot^2", "'dot' alone is not a variable"), ("l (theta dot)^2", "'dot' alone is not a variable"),
    ("l dot theta^2", "'dot' alone is not a variable"),  # Typst's l⋅θ², or ASCIIMath's l θ̇²?
])
def test_editor_notation_that_cannot_be_read_is_refused_naming_it(ns, latex, named):
    with pytest.raises(ExpressionError) as err:
        parse_system(latex, ns) if "=" in latex or "\\\\" in latex else parse_expression(latex, ns)
    assert named in str(err.value) and err.value.hint


@pytest.mark.parametrize("latex, plain", [
    # LaTeX ignores spaces, and OCR (Mathpix) puts one between every two factors: \sin 2 \theta prints
    # sin 2θ, as \sin 2\theta does, so it is sin(2θ), never sin(2)·θ
    (r"\sin 2 \theta", "sin(2 theta)"), (r"\frac{1}{2} m g \sin 2 \theta", "m g sin(2 theta)/2"),
    (r"\cos 2 \omega t", "cos(2 omega t)"), (r"\sin 3 \theta \cos \theta", "sin(3 theta) cos(theta)"),
    (r"\sin 2 x", "sin(2 x)"), (r"\operatorname{sen} 2 \theta", "sin(2 theta)"),
])
def test_latex_spaces_do_not_cut_a_function_argument(latex, plain):
    from grader.expressions import Namespace, Variable
    ns = Namespace([Variable("m", "mass", "positive"), Variable("g", "acceleration", "positive"),
                    Variable("theta", "angle", "real"), Variable("x", "dimensionless", "real"),
                    Variable("omega", "angular_velocity", "real"), Variable("t", "time", "real")])
    assert parse_expression(latex, ns).expr == parse_expression(plain, ns).expr


@pytest.mark.parametrize("text, expected", [
    ("sin 2 θ", "sin(2*theta)"), ("sin 2θ", "sin(2*theta)"), ("cos 3 x", "cos(3*x)"), ("exp 2 x", "exp(2*x)"),
    # the number alone before another function or an operator is the whole argument
    ("sin 2 cos θ", "sin(2)*cos(theta)"), ("sin 2 + x", "x + sin(2)"),
    # an exponent ends at a typed space: e^2 x is e²·x (in LaTeX too, e^{2} x)
    ("e^2 x", "x*exp(2)"),
])
def test_a_number_then_a_name_is_a_plain_function_argument_spaced_or_not(text, expected):
    # as in LaTeX: nobody means sin(2)·θ by sin 2 θ; the reading is said in a note
    import sympy

    from grader.expressions import Namespace, Variable
    ns = Namespace([Variable("theta", "angle", "real"), Variable("x", "dimensionless", "real")])
    parsed = parse_expression(text, ns)
    assert sympy.sstr(parsed.expr) == expected


@pytest.mark.parametrize("latex, named", [
    (r"m g \cdots", r"'\cdots' (an ellipsis)"), (r"m g+\ldots", r"'\ldots' (an ellipsis)"),
    (r"m g \text { (N) }", "reads as a unit"), (r"m g\,\text{[N]}", "reads as a unit"),
])
def test_ellipses_and_bracketed_units_are_refused_naming_them(ns, latex, named):
    with pytest.raises(ExpressionError) as err:
        parse_expression(latex, ns)
    assert named in str(err.value) and err.value.hint


@pytest.mark.parametrize("latex, plain", [
    # a subscript set apart from its name, as LaTeX allows and OCR (m _ { 1 }) and Word ({m}_{1}) write it
    (r"m _ { 1 }", "m1"), (r"m_ {1}", "m1"), (r"m _1", "m1"), (r"m _ 1", "m1"), (r"{m}_{1}", "m1"),
    (r"{\theta}_1", "theta_1"), (r"\theta _ { 1 }", "theta_1"), (r"{\dot{\theta}}_{1}", "theta1dot"),
    (r"{\dot{\theta}}_1^2", "theta1dot^2"), (r"\dot { \theta } _ { 1 } ^ { 2 }", "theta1dot^2"),
    (r"\dot{\theta} _1", "theta1dot"), (r"{m_{1}}{m}_{1}", "m1^2"),
])
def test_a_subscript_set_apart_from_its_name_is_the_names(latex, plain):
    from grader.expressions import Namespace, Variable
    ns = Namespace([Variable("m1", "mass", "positive"), Variable("theta1", "angle", "real", "coordinate"),
                    Variable("theta1dot", "angular_velocity", "real", "velocity")])
    assert parse_expression(latex, ns).expr == parse_expression(plain, ns).expr


@pytest.mark.parametrize("latex", [r"\frac{g}{m}_1", r"\sqrt{m}_1"])
def test_a_subscript_after_a_fraction_or_root_is_not_moved_inside(latex):
    # LaTeX sets it on the whole fraction or root, which is no name: refused, never read as m1
    from grader.expressions import Namespace, Variable
    ns = Namespace([Variable("m1", "mass", "positive"), Variable("g", "acceleration", "positive")])
    with pytest.raises(ExpressionError):
        parse_expression(latex, ns)


@pytest.mark.parametrize("latex, plain", [
    # a final answer in a box, coloured or underlined: the box around the whole answer or a whole side is
    # no bracket (\boxed{T = m g} is an equation), around a part it groups that part, as its braces do
    (r"\boxed{m g}", "m g"), (r"T = \boxed{m g}", "m g"), (r"\boxed{T = m g}", "m g"),
    (r"m \boxed{g + l}", "m (g + l)"), (r"\boxed{g + l}^2", "(g + l)^2"), (r"$\boxed{m g}$", "m g"),
    (r"\textcolor{red}{m g}", "m g"), (r"{\color{blue} m g}", "m g"), (r"\colorbox{yellow}{$m g$}", "m g"),
    (r"\underline{\underline{m g}}", "m g"), (r"\phantom{-}m g", "m g"), (r"m g\hspace{1em}", "m g"),
    (r"m g\enspace", "m g"), (r"\mathstrut m g\strut", "m g"), (r"m\allowbreak g", "m g"),
    # a prime after a space: LaTeX ignores it
    (r"\theta ^{\prime}", "thetadot"), (r"\theta ^ { \prime \prime }", "thetaddot"),
])
def test_looks_around_an_answer_are_read_through(ns, latex, plain):
    assert parse_expression(latex, ns).expr == parse_expression(plain, ns).expr


@pytest.mark.parametrize("latex", [r"\boxed{\ddot{\theta} = -\frac{g}{l}\sin\theta}",
                                   r"\ddot{\theta} = \boxed{-\frac{g}{l}\sin\theta}",
                                   r"\displaylines{\ddot{\theta} = -\frac{g}{l}\sin\theta}"])
def test_a_boxed_equation_is_the_equation(ns, latex):
    got, expected = parse_equation(latex, ns), parse_equation("thetaddot = -g/l sin(theta)", ns)
    assert (got.lhs, got.rhs) == (expected.lhs, expected.rhs)


@pytest.mark.parametrize("latex, named", [
    (r"\boxed m g", r"\boxed needs braces"), (r"\textcolor{red} m", r"\textcolor needs the text to colour"),
    (r"\dot{\theta}^{\prime}", r"'\prime' can only follow a variable name"),
])
def test_malformed_looks_are_refused_naming_them(ns, latex, named):
    with pytest.raises(ExpressionError) as err:
        parse_expression(latex, ns)
    assert named in str(err.value)


@pytest.mark.parametrize("latex, plain", [
    # the decimal comma as LaTeX writes it ({,} keeps the comma from spacing), MathLive's \lparen \rparen,
    # and a function name set upright by Word (\mathrm{\cos})
    (r"0{,}5\,m g", "0.5 m g"), (r"m g\times1{,}25", "1.25 m g"),
    (r"\cos\lparen\theta\rparen", "cos(theta)"), (r"\cos\mleft\lparen\theta\mright\rparen", "cos(theta)"),
    (r"\mathrm{\cos}\theta", "cos(theta)"),
])
def test_decimal_commas_parentheses_and_upright_functions_in_latex(ns, latex, plain):
    assert parse_expression(latex, ns).expr == parse_expression(plain, ns).expr


@pytest.mark.parametrize("text, named", [
    ("0,5 m", "decimal point"),   # a bare comma stays refused: a decimal, or a list?
    (r"m g\,\mathrm{kg\cdot m\cdot s^{-2}}", "reads as a unit"),
    ("frac(m, 2)", "write a/b for a fraction"),   # Typst
    ("m dot g", "for a product (Typst's m dot g) write m*g"),
])
def test_what_other_editors_write_is_refused_with_the_fix(ns, text, named):
    with pytest.raises(ExpressionError) as err:
        parse_expression(text, ns)
    assert named in str(err.value)


@pytest.mark.parametrize("text", ["m l θ˙2", "ml θ̇2"])
def test_digits_after_a_dot_that_name_nothing_say_how_to_write_a_power(ns, text):
    # θ˙2 copied out of a web page's MathML (θ̇² that lost its raise): the refusal says to write ^
    with pytest.raises(ExpressionError) as err:
        parse_expression(text, ns)
    assert "write a power with ^" in err.value.hint


@pytest.mark.parametrize("text, plain", [
    # a LaTeX subscript closes its symbol, and primes or dots belong to the letters they are written
    # after: m₁x'' is m₁·x'' when only x'' (not x) is a variable
    (r"m_{1}x^{\prime\prime}", "m1 xddot"), ("m₁x''", "m1 xddot"), ("m1x''", "m1 xddot"), ("m_1x''", "m1 xddot"),
    (r"m_{1}\ddot{x}", "m1 xddot"),
])
def test_primes_after_a_subscripted_name_belong_to_the_next_letter(text, plain):
    from grader.expressions import Namespace, Variable
    ns = Namespace([Variable("m1", "mass", "positive"), Variable("xddot", "acceleration", "real", "acceleration")])
    assert parse_expression(text, ns).expr == parse_expression(plain, ns).expr


@pytest.mark.parametrize("latex, plain", [(r"x = l \quad y", "x = l y"), (r"x = (l \quad y)", "x = l y"),
                                          (r"x \quad = l", "x = l")])
def test_a_wide_space_inside_one_equation_is_a_space(ns, latex, plain):
    [got], [expected] = parse_system(latex, ns), parse_system(plain, ns)
    assert (got.lhs, got.rhs) == (expected.lhs, expected.rhs)


@pytest.mark.parametrize("latex, plain", [
    # \sqrt without braces takes one character or command, as LaTeX prints it: \sqrt2 g is √2·g, never √(2g)
    (r"\sqrt2 g", "sqrt(2) g"), (r"\sqrt2g", "sqrt(2) g"), (r"\sqrt g l", "sqrt(g) l"), (r"\sqrt\pi", "sqrt(pi)"),
    (r"\sqrt 3+1", "sqrt(3) + 1"), (r"\sqrt g/\sqrt l", "sqrt(g/l)"),
    # a bracket, a structure or a function after it is the whole argument
    (r"\sqrt(g l)", "sqrt(g l)"), (r"\sqrt\left(g l\right)", "sqrt(g l)"), (r"\sqrt\frac{g}{l}", "sqrt(g/l)"),
    (r"\sqrt\left|x\right|", "sqrt(abs(x))"), (r"\sqrt\cos\theta", "sqrt(cos(theta))"),
])
def test_an_unbraced_root_takes_what_latex_puts_under_it(ns, latex, plain):
    assert parse_expression(latex, ns).expr == parse_expression(plain, ns).expr


@pytest.mark.parametrize("latex, named", [
    (r"\sqrt12", r"'\sqrt12' puts only '1' under the root"), (r"\sqrt gl", r"'\sqrt gl' puts only 'g' under the root"),
    (r"\sqrt -g", r"\sqrt needs braces, as in \sqrt{x}"),
])
def test_an_unbraced_root_over_glued_characters_is_refused(ns, latex, named):
    # LaTeX prints √1 2 and √g l: was the root of 12, or of gl, meant?
    with pytest.raises(ExpressionError) as err:
        parse_expression(latex, ns)
    assert named in str(err.value)


@pytest.mark.parametrize("latex, plain", [
    # \dot without braces dots one character, as TeX prints it: \dot xy is ẋ·y (the glued name xy with a
    # dot would read x·ẏ); a declared or Greek name stays whole (\dot theta, as \dot\theta)
    (r"\dot xy", "xdot y"), (r"\dot yx", "x ydot"), (r"\dot theta", "thetadot"), (r"\dot x l", "xdot l"),
])
def test_an_unbraced_dot_marks_one_character(latex, plain):
    from grader.expressions import Namespace, Variable
    ns = Namespace([Variable("x", "length", "real", "coordinate"), Variable("xdot", "velocity", "real", "velocity"),
                    Variable("y", "length", "real", "coordinate"), Variable("ydot", "velocity", "real", "velocity"),
                    Variable("l", "length", "positive"), Variable("theta", "angle", "real", "coordinate"),
                    Variable("thetadot", "angular_velocity", "real", "velocity")])
    assert parse_expression(latex, ns).expr == parse_expression(plain, ns).expr


def test_sen_is_a_product_when_s_e_and_n_are_all_declared():
    # as tg and lg: the Spanish sine only when the letters are not all variables
    from grader.expressions import Namespace, Variable
    ns = Namespace([Variable("s", "length", "real"), Variable("e", "dimensionless", "positive"),
                    Variable("n", "dimensionless", "positive")])
    assert parse_expression("sen", ns).expr == parse_expression("s*e*n", ns).expr


@pytest.mark.parametrize("latex, plain", [
    # what a formula copied from Wikipedia gives: its LaTeX in a {\displaystyle …} group
    (r"{\displaystyle T=mg\cos \theta +ml{\dot {\theta }}^{2}}", "m g cos(theta) + m l thetadot^2"),
    (r"{\textstyle mg\cos \theta ,}", "m g cos(theta)"),
    (r"{\displaystyle {\begin{aligned}T&=mg\cos \theta \end{aligned}}}", "m g cos(theta)"),
    (r"m{\displaystyle g+l}", "m (g + l)"),   # a part: still a group
])
def test_a_wikipedia_style_group_around_the_answer_is_read_through(ns, latex, plain):
    assert parse_expression(latex, ns).expr == parse_expression(plain, ns).expr


@pytest.mark.parametrize("text, plain", [
    # Word's linear format writes a fraction's parts in brackets, and its d as a mathematical italic 𝑑
    ("(d^2 θ)/(dt^2)", "thetaddot"), ("(𝑑^2 𝜃)/(𝑑𝑡^2 )", "thetaddot"), ("𝑑²𝜃/𝑑𝑡²", "thetaddot"),
    ("(dθ)/dt", "thetadot"), ("(d θ)/(d t)", "thetadot"),
])
def test_word_linear_leibniz_derivatives(ns, text, plain):
    assert parse_expression(text, ns).expr == parse_expression(plain, ns).expr


def test_a_bracketed_leibniz_quotient_keeps_a_declared_d_as_a_variable():
    from grader.expressions import Namespace, Variable
    ns = Namespace([Variable("x", "length", "real", "coordinate"), Variable("xdot", "velocity", "real", "velocity"),
                    Variable("d", "length", "positive"), Variable("t", "time", "positive")])
    assert parse_expression("(dx)/(dt)", ns).expr == parse_expression("x/t", ns).expr


@pytest.mark.parametrize("latex, plain", [(r"\text{Answer: } m g", "m g"), (r"\text{EOM:}\; T = m g", "m g")])
def test_a_caption_before_the_whole_answer_is_no_part_of_it(ns, latex, plain):
    assert parse_expression(latex, ns).expr == parse_expression(plain, ns).expr


def test_a_caption_after_the_start_is_still_text(ns):
    with pytest.raises(ExpressionError) as err:
        parse_expression(r"m g \text{ so: }", ns)
    assert "is text" in str(err.value)


# -- red team 2026-11-10b: an empty group carrying a superscript -----------------------------------

@pytest.mark.parametrize("latex, plain", [
    (r"x{}^{2}", "x^2"), (r"x{ }^{2}", "x^2"), (r"x{}^2", "x^2"), (r"m l\dot{\theta}{}^{2}", "m l thetadot^2"),
    (r"\left(x+l\right){}^{2}", "(x + l)^2"), (r"x{}^{2}l", "x^2 l"), (r"2{}^{3}x", "8 x"),
    (r"m g\cos\theta+m l\dot{\theta}{}^{2}", "m g cos(theta) + m l thetadot^2"),
])
def test_an_empty_group_between_an_operand_and_its_power_is_nothing(ns, latex, plain):
    assert parse_expression(latex, ns).expr == parse_expression(plain, ns).expr


@pytest.mark.parametrize("latex", [r"{}^{2}x", r"x+{}^{2}l", r"x{}", r"x{}l"])
def test_an_empty_group_carrying_nothing_or_a_prescript_is_refused(ns, latex):
    with pytest.raises(ExpressionError) as err:
        parse_expression(latex, ns)
    assert "empty" in str(err.value)


# -- red team 2026-11-10b: MathML or HTML pasted as text is named, not read as inequalities ----------

@pytest.mark.parametrize("text, tag, kind", [
    ("<math><mi>x</mi><mo>+</mo><mn>1</mn></math>", "'<math>'", "MathML"),
    ('<math xmlns="http://www.w3.org/1998/Math/MathML"><mi>l</mi></math>', "'<math xmlns=", "MathML"),
    ("<mrow><mi>m</mi><mi>g</mi></mrow>", "'<mrow>'", "MathML"),
    ("<msup><mi>x</mi><mn>2</mn></msup>", "'<msup>'", "MathML"),
    ("m g <mo>+</mo> l", "'<mo>'", "MathML"),
    ("x<sup>2</sup>", "'<sup>'", "HTML"),
    ("<p>m g l</p>", "'<p>'", "HTML"),
])
def test_pasted_markup_is_refused_naming_the_tag(ns, text, tag, kind):
    with pytest.raises(ExpressionError) as err:
        parse_expression(text, ns)
    assert tag in str(err.value) and f"{kind} markup" in str(err.value) and "LaTeX" in err.value.hint


@pytest.mark.parametrize("text", ["x < l", "x<l", "m<g", "x <> l", "x <= l"])
def test_a_less_than_sign_is_still_an_inequality(ns, text):
    with pytest.raises(ExpressionError) as err:
        parse_expression(text, ns)
    assert "markup" not in str(err.value)


# -- red team 2026-11-10b: \frac's unbraced arguments over letters and digits glued ----------------

@pytest.mark.parametrize("latex, plain", [
    (r"\frac x2", "x/2"), (r"\frac l2", "l/2"), (r"\frac g2l", "g/2 l"), (r"\frac x2 l", "x/2 l"),
    (r"m\frac g2", "m g/2"), (r"\frac12 m \frac x2", "m x/4"), (r"\frac x2x", "x^2/2"),
])
def test_an_unbraced_frac_argument_is_one_character_also_before_a_digit(ns, latex, plain):
    assert parse_expression(latex, ns).expr == parse_expression(plain, ns).expr


@pytest.mark.parametrize("latex", [r"\frac 1x2", r"\frac 2l3"])
def test_a_number_right_after_an_unbraced_frac_needs_an_operator(ns, latex):
    with pytest.raises(ExpressionError) as err:
        parse_expression(latex, ns)
    assert "missing operator" in str(err.value)


# -- red team 2026-11-10b: MathType's braced base before primes, and primes typed in a superscript ---

@pytest.mark.parametrize("latex, plain", [
    (r"{\theta }^{\prime \prime }", "thetaddot"), (r"{\theta}^{\prime}", "thetadot"),
    (r"{\theta}''", "thetaddot"), (r"{\theta}'", "thetadot"), (r"{\theta }^{''}", "thetaddot"),
    (r"\theta^{''}", "thetaddot"), (r"\theta^{'}", "thetadot"), (r"\theta^{'2}", "thetadot^2"),
    (r"m l{\theta }^{\prime }{}^{2}", "m l thetadot^2"), (r"m l\left({\theta }^{\prime }\right)^{2}", "m l thetadot^2"),
    (r"{\theta }^{\prime \prime }+\frac{g}{l}\sin\theta", "thetaddot + g/l sin(theta)"),
])
def test_primes_on_a_braced_name_or_in_a_superscript_are_its_derivatives(ns, latex, plain):
    assert parse_expression(latex, ns).expr == parse_expression(plain, ns).expr


@pytest.mark.parametrize("latex", [r"\dot{\theta}^{\prime}", r"\frac{g}{\theta}^{\prime}", r"\sqrt{\theta}''",
                                   r"{\theta+l}''", r"\frac{g}{x}_{1}^{\prime}", r"{x}l^{\prime}"])
def test_primes_on_a_command_argument_or_a_group_stay_refused(ns, latex):
    with pytest.raises(ExpressionError):
        parse_expression(latex, ns)


@pytest.mark.parametrize("latex, plain", [
    (r"{x}_{1}^{\prime }", "x1dot"), (r"{{x}_{1}}^{\prime }", "x1dot"),
    (r"{x}_{1}^{\prime \prime }", "x1ddot"), (r"m{x}_{1}^{\prime }{x}_{2}^{\prime }", "m x1dot x2dot"),
])
def test_primes_on_a_braced_subscripted_name_are_its_derivatives(latex, plain):
    from grader.expressions import Namespace, Variable
    two = Namespace([Variable("m", "mass", "positive"), Variable("x1", "length"), Variable("x1dot", "velocity"),
                     Variable("x1ddot", "acceleration"), Variable("x2", "length"), Variable("x2dot", "velocity")])
    assert parse_expression(latex, two).expr == parse_expression(plain, two).expr


# -- red team 2026-11-10b: MathType's brace of a system, and LaTeX's other line breaks -------------

@pytest.mark.parametrize("latex", [
    r"\left\{\begin{matrix}x=l \\ y=2l\end{matrix}\right.", r"\left\{ \begin{matrix} x&=l \\ y&=2 l \\ \end{matrix} \right.",
    r"x = l \newline y = 2 l", r"x = l \\[2pt] y = 2 l", r"x = l \\ [1ex] y = 2 l", r"x = l \\[0.5em] y = 2 l",
    r"\begin{aligned} x &= l \\[3mm] y &= 2 l \end{aligned}",
])
def test_a_matrix_in_a_brace_and_spaced_or_spelled_line_breaks_separate_equations(ns, latex):
    assert [(eq.lhs, eq.rhs) for eq in parse_system(latex, ns)] == \
        [(eq.lhs, eq.rhs) for eq in parse_system("x = l; y = 2 l", ns)]


@pytest.mark.parametrize("latex", [r"\begin{matrix}x=l \\ y=2l\end{matrix}", r"\begin{pmatrix}x \\ y\end{pmatrix} = 0"])
def test_a_matrix_outside_a_brace_is_still_refused_by_name(ns, latex):
    with pytest.raises(ExpressionError) as err:
        parse_system(latex, ns)
    assert "matrix}" in str(err.value)


# -- red team 2026-11-10b: primes and a subscript on a function name are refused, not a crash ------

@pytest.mark.parametrize("latex", [r"\sin''_{1}", r"\sin′_{1}", r"\cos''_{1}\theta", r"\sin'_1", r"\tan''_{2} x"])
def test_a_subscript_after_primes_on_a_function_is_refused(ns, latex):
    with pytest.raises(ExpressionError) as err:
        parse_expression(latex, ns)
    assert "_" in str(err.value)


# -- red team 22: commands with the next letters glued on, and MathQuill's '\ ' between a number and a name --

@pytest.mark.parametrize("name, fix", [
    ("cdotg", r"write \cdot g, with a space"), ("timesl", r"write \times l"), ("costheta", r"write \cos\theta"),
    ("sinalpha", r"write \sin\alpha"), ("thetam", r"write \theta m"), ("thetadot", r"write \dot{\theta}"),
    ("phiddot", r"write \ddot{\phi}"), ("omegat", r"write \omega t"),
])
def test_a_command_with_letters_glued_on_is_named_with_the_space_or_backslash_to_type(name, fix):
    # \cdotg was "the LaTeX command \cdotg is not supported; use + - * / ^, \frac, \sqrt and functions such as \sin"
    with pytest.raises(ExpressionError) as err:
        classify_command(name, 0)
    assert "one name" in err.value.message and err.value.hint.startswith(fix)


@pytest.mark.parametrize("name", ["leftarrow", "bigcirc", "textsc", "sech", "arcsinh", "sqrtx", "partial"])
def test_other_unknown_commands_get_no_glued_reading(name):
    with pytest.raises(ExpressionError) as err:
        classify_command(name, 0)
    assert "one name" not in err.value.message


@pytest.mark.parametrize("latex", [r"\sin\ 2\ \theta", r"\sin 2\,\theta", r"\sin 2~\theta", r"\sin\ 2\quad\theta",
                                   r"\sin 2\;\theta"])
def test_latex_spacing_between_a_number_and_a_name_keeps_them_one_argument(ns, latex):
    # MathQuill writes a typed space as '\ ': \sin\ 2\ \theta was sin(2)·θ while \sin 2 \theta is sin(2θ)
    assert parse_expression(latex, ns).expr == parse_expression(r"\sin 2\theta", ns).expr


def test_latex_spacing_after_a_command_still_ends_a_functions_argument(ns):
    # \sin\theta\, l is sin(θ)·l: only a number then a name is glued across a space
    assert parse_expression(r"\sin\theta\, l", ns).expr == parse_expression(r"\sin(\theta) l", ns).expr
