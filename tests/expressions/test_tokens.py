"""The tokenizer keeps positions in the text as typed, and refuses what it cannot read."""

import pytest
import sympy

from grader.expressions import ExpressionError
from grader.expressions.tokens import MAX_NESTING, check_brackets, tokenize


def kinds(text):
    return [(t.kind, t.value) for t in tokenize(text)[:-1]]


@pytest.mark.parametrize("text, expected", [
    ("x**2", [("name", "x"), ("op", "^"), ("number", 2)]),
    ("a == b", [("name", "a"), ("op", "="), ("name", "b")]),
    ("2x", [("number", 2), ("name", "x")]),
    ("2e3x", [("number", 2000), ("name", "x")]),
    ("2e", [("number", 2), ("name", "e")]),                    # e not followed by digits is a name
    ("θ₁", [("name", "theta_1")]),
    ("m_{12}", [("name", "m_12")]),
    ("Q_{roll,s}", [("name", "Q_roll_s")]),
    ("\\lambda_{surface}", [("name", "lambda_surface")]),
    ("x·y×z", [("name", "x"), ("op", "*"), ("name", "y"), ("op", "*"), ("name", "z")]),
    ("x−y", [("name", "x"), ("op", "-"), ("name", "y")]),
    ("x⁻¹²", [("name", "x"), ("sup", -12)]),
    ("√∛", [("root", 2), ("root", 3)]),
    ("\\left( x \\right]", [("open", "("), ("name", "x"), ("close", "]")]),
    ("\\frac\\sqrt\\dot", [("command", "frac"), ("command", "sqrt"), ("command", "dot")]),
    ("\\sin\\arctan", [("name", "sin"), ("name", "atan")]),
    ("a\\,b\\;c\\quad d", [("name", "a"), ("name", "b"), ("name", "c"), ("name", "d")]),
    ("x\ny", [("name", "x"), ("newline", "\n"), ("name", "y")]),
])
def test_token_kinds_and_values(text, expected):
    assert kinds(text) == expected


@pytest.mark.parametrize("text, order", [("θ̇", 1), ("θ̈", 2), ("x'", 1), ("x''", 2), ("x″", 2), ("ẋ", 1), ("ẍ", 2)])
def test_derivative_marks_are_counted_on_the_name(text, order):
    token = tokenize(text)[0]
    assert token.kind == "name" and token.order == order and token.end == len(text)


def test_positions_refer_to_the_original_text():
    tokens = tokenize("\\theta + √x·θ̇")
    assert [(t.pos, t.end) for t in tokens[:-1]] == [(0, 6), (7, 8), (9, 10), (10, 11), (11, 12), (12, 14)]


def test_decimals_are_exact_and_flagged():
    token = tokenize("0.1")[0]
    assert token.value == sympy.Rational(1, 10) and token.decimal


@pytest.mark.parametrize("text, code, position", [
    ("x + 1e100000", "too_large", 4),
    ("1" * 1001, "too_large", 0),
    ("x\x01", "bad_character", 1),
    ("m_{1", "unbalanced", 2),
    ("\\", "syntax", 0),
    ("\\left< x \\right>", "unsupported_function", 0),
    ("|x", "unbalanced", 0),                # an absolute value never closed
    ("x + ||", "syntax", 4),                # empty bars
    ("\\rvert x", "unbalanced", 0),         # a closing bar with none open
    ("\\mathrm", "syntax", 0), ("\\mathrm +x", "syntax", 0),  # no argument TeX reads as a name
    ("x⁻", "syntax", 1),
])
def test_tokenizer_errors(text, code, position):
    with pytest.raises(ExpressionError) as err:
        tokenize(text)
    assert (err.value.code, err.value.position) == (code, position)


@pytest.mark.parametrize("text", ["a!", "a.b", "a:b", "a<b", "a@b"])
def test_stray_punctuation_is_reported_where_the_parser_meets_it(text):
    token = tokenize(text)[1]
    assert token.kind == "bad" and token.error.position == 1


# ± typed in ASCII: "-b +- sqrt(D)" and "x = +-2" were read as one sign, -b - sqrt(D) and x = -2.
@pytest.mark.parametrize("text, typed", [
    ("-b +- sqrt(b^2 - 4*a*c)", "'+-'"), ("x = +-2", "'+-'"), ("x = +/-2", "'+/-'"), ("a -+ b", "'-+'"),
    ("x = +\u22122", "'+\u2212'"), ("a \u2212+ b", "'\u2212+'"),   # a Unicode minus
])
def test_plus_minus_typed_in_ascii_is_refused_not_read_as_one_sign(text, typed):
    token = next(t for t in tokenize(text) if t.kind == "bad")
    assert typed in str(token.error) and "one sign" in token.error.hint


@pytest.mark.parametrize("text", ["x + (-2)", "x+ -2", "x - -2", "x--2", "1e-3", "a*-b", "a/-b", "a^-2"])
def test_a_sign_after_an_operator_is_still_read(text):
    assert not any(t.kind == "bad" for t in tokenize(text))



# A programmer's "not equal" (PrairieLearn's tests type 5!=5) is named as such, not as a factorial.
@pytest.mark.parametrize("text", ["5!=5", "x != y", "a!=b+1"])
def test_not_equal_typed_in_ascii_is_named_not_read_as_a_factorial(text):
    token = next(t for t in tokenize(text) if t.kind == "bad")
    assert "'!=' (not equal)" in str(token.error) and "factorial" not in str(token.error)
    assert "equation with =" in token.error.hint

# Maxima's (STACK's) notation: the refusal names what was typed and what to type instead.
@pytest.mark.parametrize("text, named, hint", [
    ("%pi/2", "'%pi'", "write pi"), ("2*%pi*r", "'%pi'", "write pi"), ("%e^x", "'%e'", "write e"),
    ("a + %i*b", "'%i'", "complex"), ("f := x^2", "':='", "equation with ="), ("x:=1", "':='", "equation with ="),
])
def test_maxima_notation_is_refused_naming_it_and_the_fix(text, named, hint):
    token = next(t for t in tokenize(text) if t.kind == "bad")
    assert named in str(token.error) and hint in token.error.hint


@pytest.mark.parametrize("text, code, position", [
    ("(a", "unbalanced", 0),
    ("a)", "unbalanced", 1),
    ("((a)", "unbalanced", 0),
    ("(a]", "unbalanced", 2),
    ("{a)", "unbalanced", 2),
    ("(" * (MAX_NESTING + 1) + ")" * (MAX_NESTING + 1), "too_deep", MAX_NESTING),
])
def test_bracket_errors_point_at_the_unmatched_bracket(text, code, position):
    with pytest.raises(ExpressionError) as err:
        check_brackets(tokenize(text))
    assert (err.value.code, err.value.position) == (code, position)


def test_fifty_levels_are_allowed():
    check_brackets(tokenize("(" * MAX_NESTING + "x" + ")" * MAX_NESTING))


@pytest.mark.parametrize("text, reading", [
    ("|x|", "abs ( x )"),
    ("2|x|", "2 abs ( x )"),
    ("|a|b|c|", "abs ( a ) b abs ( c )"),          # a bar with none open opens a factor
    ("|x + |y||", "abs ( x + abs ( y ) )"),        # after an operator a bar opens
    ("||x| - 1|", "abs ( abs ( x ) - 1 )"),
    ("\\left| x \\right|", "abs ( x )"),
    ("\\lvert x \\rvert", "abs ( x )"),
])
def test_absolute_value_bars_become_abs_calls(text, reading):
    tokens = tokenize(text)[:-1]
    assert " ".join(str(t.value) for t in tokens) == reading
    assert all(text[t.pos:t.end] == t.text for t in tokens)  # every token still points at what was typed


@pytest.mark.parametrize("text", ["R1||R2||R3", "R1 || R2 || R3", "x||y", "1||1||2", "(a+b)||c||d", "2||x||",
                                  "R1||R2| + |R3|"])
def test_a_double_bar_after_an_operand_is_refused_as_the_parallel_operator(text):
    # edX's a||b is a b/(a + b); read as a·‖b‖, R1||R2||R3 was the product R1·R2·R3 (red team 26)
    with pytest.raises(ExpressionError) as err:
        tokenize(text)
    assert err.value.code == "ambiguous" and "'||'" in err.value.message and "parallel" in err.value.message
    assert "a*b/(a + b)" in err.value.hint and "a*|b|" in err.value.hint


@pytest.mark.parametrize("text", ["x\\%", "50\\%", "\\frac{x}{100}\\%"])
def test_latex_percent_is_named_as_a_percent_sign(text):
    # CortexJS and MathLive write x\% ; it was "'\' must start a LaTeX command"
    with pytest.raises(ExpressionError) as err:
        tokenize(text)
    assert "percent" in err.value.message and "0.3 for 30%" in err.value.hint


@pytest.mark.parametrize("text", ["|x||y|", "||x|-|y||", "||x||", "|x|*||y||", "|||x|||", "2||x| - 1|", "y||x|-|y||"])
def test_double_bars_that_open_or_close_absolute_values_are_still_read(text):
    assert "abs" in [t.value for t in tokenize(text)]  # 2||x| - 1|: nested absolute values, closed apart


@pytest.mark.parametrize("text, name", [("\\log_{10} x", "log_10"), ("\\log_2 x", "log_2"), ("\\log_{2}(x)", "log_2")])
def test_a_latex_logarithm_keeps_its_base(text, name):
    assert tokenize(text)[0].value == name


# -- red team 2026-11: LaTeX as other editors write it -------------------------------------------

@pytest.mark.parametrize("text", ["30^\\circ", "30^{\\circ}", "30 ^ { \\circ }", "30\\degree", "30°"])
def test_every_degree_notation_after_a_number_is_degrees(text):
    assert kinds(text) == [("number", sympy.pi / 6)]


@pytest.mark.parametrize("text", ["x^\\circ", "x^{\\circ}", "(30)^\\circ", "\\degree"])
def test_degrees_after_anything_but_a_number_are_refused_by_name(text):
    with pytest.raises(ExpressionError) as err:
        tokenize(text)
    assert "degree" in err.value.message and "30°" in err.value.hint


@pytest.mark.parametrize("text", ["\\(x\\)", "\\[x\\]", "$x$", "$$x$$", "\\( x \\)"])
def test_math_delimiters_around_pasted_latex_are_decoration(text):
    assert kinds(text) == [("name", "x")]


@pytest.mark.parametrize("text", ["\\bigl(x\\bigr)", "\\Bigl(x\\Bigr)", "\\biggl(x\\biggr)", "\\Biggl(x\\Biggr)",
                                  "\\big(x\\big)", "\\Big(x\\Big)", "\\bigg(x\\bigg)", "\\Bigg(x\\Bigg)",
                                  "\\left(x\\right)"])
def test_sized_brackets_are_brackets(text):
    assert kinds(text) == [("open", "("), ("name", "x"), ("close", ")")]


@pytest.mark.parametrize("text", ["\\bigl|x\\bigr|", "\\mid x\\mid", "∣x∣", "|x|", "\\Bigl| x \\Bigr|"])
def test_every_absolute_value_bar(text):
    assert kinds(text) == [("name", "abs"), ("open", "("), ("name", "x"), ("close", ")")]


def test_a_sized_bracket_before_something_else_is_refused_naming_the_command():
    with pytest.raises(ExpressionError) as err:
        tokenize("\\bigl/ x")
    assert "\\bigl" in err.value.message and "/" in err.value.message


@pytest.mark.parametrize("text, name", [("𝑚𝑔", "mg"), ("𝜃̇", "theta"), ("𝑚₁", "m_1"), ("2𝑥", "x")])
def test_styled_letters_make_names(text, name):
    assert [t.value for t in tokenize(text) if t.kind == "name"] == [name]


@pytest.mark.parametrize("text", ["x—y", "x‒y", "x‐y", "x‑y", "x﹣y"])
def test_dashes_are_minus(text):
    assert kinds(text) == [("name", "x"), ("op", "-"), ("name", "y")]


# -- red team 2026-11: superscript letters and delimiters that are not brackets -----------------

@pytest.mark.parametrize("text, shown, named, fix", [
    ("e⁻ᵃᵇ", "⁻ᵃᵇ", ["'ᵃ' (MODIFIER LETTER SMALL A)", "'ᵇ' (MODIFIER LETTER SMALL B)"], "e^(-a b)"),
    ("e⁻ᵗ", "⁻ᵗ", ["'ᵗ' (MODIFIER LETTER SMALL T)"], "e^(-t)"),
    ("e⁻²ᵗ", "⁻²ᵗ", ["'ᵗ'"], "e^(-2t)"),
    ("xⁿ", "ⁿ", ["'ⁿ' (SUPERSCRIPT LATIN SMALL LETTER N)"], "x^n"),
    ("eˣ", "ˣ", ["'ˣ' (MODIFIER LETTER SMALL X)"], "e^x"),
    ("2ᵏ", "ᵏ", ["'ᵏ'"], "2^k"),
    ("e⁽ᵏᵗ⁾", "⁽ᵏᵗ⁾", ["'⁽' (SUPERSCRIPT LEFT PARENTHESIS)", "'ᵏ'"], "e^(k t)"),
    ("eᶿ", "ᶿ", ["'ᶿ' (MODIFIER LETTER SMALL THETA)"], "e^θ"),
    ("cos θ ᵃ", "ᵃ", ["'ᵃ'"], "x^a"),                         # nothing directly before it: a generic base
])
def test_superscript_letters_are_refused_naming_them_and_the_power_to_type(text, shown, named, fix):
    with pytest.raises(ExpressionError) as err:
        tokenize(text)
    error = err.value
    assert error.code == "bad_character" and error.position == text.index(shown)
    assert error.message.startswith(f"cannot read the superscript '{shown}'")
    assert all(name in error.message for name in named)
    assert error.hint.endswith(f"as in {fix}")


@pytest.mark.parametrize("text", ["x²", "x⁻¹", "x⁻¹²"])
def test_superscript_digits_are_still_powers(text):
    assert kinds(text)[-1][0] == "sup"


@pytest.mark.parametrize("text, named, fix", [
    ("\\left/ x \\right.", "'\\left/' (a slash sized as a delimiter)", "write / for division, without \\left"),
    ("\\bigl/ x", "'\\bigl/' (a slash sized as a delimiter)", "without \\bigl"),
    ("\\left. x \\right|", "'\\left.' (an invisible delimiter)", "delete '\\left.' and the \\left or \\right"),
    ("\\left( x \\right.", "'\\right.' (an invisible delimiter)", "delete '\\right.'"),
    ("\\left\\langle x \\right\\rangle", "\\left followed by '\\langle'", "\\left( ... \\right)"),
])
def test_delimiters_that_are_not_brackets_are_refused_naming_them_and_the_fix(text, named, fix):
    with pytest.raises(ExpressionError) as err:
        tokenize(text)
    assert named in err.value.message and fix in err.value.hint
    assert err.value.code == "unsupported_function"


@pytest.mark.parametrize("text", ["e" + "ᵃᵇ" * 900, "x" * 500 + "ᵃ",
                                  "e" + "".join(chr(c) for c in range(0x1D43, 0x1D5B)) * 30])
def test_a_long_run_of_superscript_letters_is_refused_briefly(text):
    with pytest.raises(ExpressionError) as err:
        tokenize(text)
    assert len(err.value.message) < 300 and len(err.value.hint) < 100


@pytest.mark.parametrize("text, expected", [
    (r"\begin{aligned} x &= 1 \\ y &= 2 \end{aligned}",
     [("name", "x"), ("op", "="), ("number", 1), ("newline", "\n"), ("name", "y"), ("op", "="), ("number", 2)]),
    (r"\begin{align*} x &= 1 \end{align*}", [("name", "x"), ("op", "="), ("number", 1)]),
    ("\\begin {gather}\nx = 1\n\\end {gather}", [("newline", "\n"), ("name", "x"), ("op", "="), ("number", 1),
                                                 ("newline", "\n")]),
])
def test_a_layout_environment_around_pasted_equations_is_only_layout(text, expected):
    # \begin{aligned} ... \end{aligned}: its & are alignment points, its \\ separate the equations
    assert kinds(text) == expected


@pytest.mark.parametrize("text, named", [
    (r"\begin{pmatrix} 1 & 2 \end{pmatrix}", r"\begin{pmatrix}"),
    (r"\begin{matrix} x \end{matrix}", r"\begin{matrix}"),
    (r"\begin{tabular}{ll} x \end{tabular}", r"\begin{tabular}"),
])
def test_other_environments_are_refused_by_name(text, named):
    with pytest.raises(ExpressionError) as err:
        tokenize(text)
    assert named in err.value.message and r"\begin{aligned}" in err.value.hint


@pytest.mark.parametrize("text, expected", [
    # a system of aligned equations in a brace: the brace and the alignat column count {2} are layout
    (r"\left\{\begin{aligned} x &= 1 \\ y &= 2 \end{aligned}\right.",
     [("name", "x"), ("op", "="), ("number", 1), ("newline", "\n"), ("name", "y"), ("op", "="), ("number", 2)]),
    (r"\left\lbrace\begin{aligned} x &= 1 \end{aligned}\right.", [("name", "x"), ("op", "="), ("number", 1)]),
    (r"\begin{alignat}{2} x &= 1 \end{alignat}", [("name", "x"), ("op", "="), ("number", 1)]),
    (r"\begin{alignedat}{3} x &= 1 \end{alignedat}", [("name", "x"), ("op", "="), ("number", 1)]),
    # cases and array, as Mathpix and Word write a system: its equations (the column layout {l} too
    # is layout); an '&' there is read only beside '=' (elsewhere it starts a condition or a column)
    (r"\begin{cases} x = 1 \\ y = 2 \end{cases}",
     [("name", "x"), ("op", "="), ("number", 1), ("newline", "\n"), ("name", "y"), ("op", "="), ("number", 2)]),
    (r"\left\{\begin{array}{l} x = 1 \end{array}\right.", [("name", "x"), ("op", "="), ("number", 1)]),
    (r"\left\{\begin{array}{rcl} x &=& 1 \end{array}\right.", [("name", "x"), ("op", "="), ("number", 1)]),
])
def test_a_system_in_a_brace_is_read_as_its_equations(text, expected):
    assert kinds(text) == expected


@pytest.mark.parametrize("text", ["x &= 1", r"\end{aligned} x &= 1", "x =& 1", "x & = 1"])
def test_an_ampersand_beside_equals_is_an_alignment_point_anywhere(text):
    # a line copied out of an align environment keeps its &=
    assert kinds(text) == [("name", "x"), ("op", "="), ("number", 1)]


@pytest.mark.parametrize("text", ["a & b", "x = 1 & y", r"\begin{cases} x & y > 0 \end{cases}"])
def test_an_ampersand_that_is_not_alignment_is_refused_by_name(text):
    tokens = tokenize(text)
    bad = [t for t in tokens if t.kind == "bad" and t.text == "&"]
    assert bad and "alignment mark" in bad[0].error.message


@pytest.mark.parametrize("text, name, order", [
    ("theta''_1", "theta_1", 2), ("θ''₁", "theta_1", 2), ("x'_{2}", "x_2", 1), ("θ'₁₂", "theta_12", 1),
])
def test_a_subscript_typed_after_the_primes_belongs_to_the_name(text, name, order):
    [token] = tokenize(text)[:-1]
    assert (token.kind, token.value, token.order) == ("name", name, order)


def test_digits_after_a_prime_without_an_underscore_are_not_a_subscript():
    assert [t.kind for t in tokenize("x'2")[:-1]] == ["name", "number"]


@pytest.mark.parametrize("text, expected", [
    (r"x = 1 \quad (2)", [("name", "x"), ("op", "="), ("number", 1)]),
    (r"x = 1 \qquad (12a)", [("name", "x"), ("op", "="), ("number", 1)]),
    (r"x = 1 \tag{2}", [("name", "x"), ("op", "="), ("number", 1)]),
    (r"x = 1 \tag*{A}", [("name", "x"), ("op", "="), ("number", 1)]),
    (r"x = 1 \quad (2) \\ y = 2", [("name", "x"), ("op", "="), ("number", 1), ("newline", "\n"),
                                   ("name", "y"), ("op", "="), ("number", 2)]),
    (r"x = 1 \quad (2); y", [("name", "x"), ("op", "="), ("number", 1), ("op", ";"), ("name", "y")]),
])
def test_an_equation_number_after_a_wide_space_or_in_a_tag_is_no_factor(text, expected):
    # θ̈ = −(g/(2l)) sin θ \quad (2) must not read as the right equation times 2
    assert kinds(text) == expected


@pytest.mark.parametrize("text, expected", [
    (r"x \quad (2) y", [("name", "x"), ("open", "("), ("number", 2), ("close", ")"), ("name", "y")]),
    ("x(2)", [("name", "x"), ("open", "("), ("number", 2), ("close", ")")]),
    ("(2)(3) x", [("open", "("), ("number", 2), ("close", ")"), ("open", "("), ("number", 3), ("close", ")"),
                  ("name", "x")]),
    ("(2)^2 x", [("open", "("), ("number", 2), ("close", ")"), ("op", "^"), ("number", 2), ("name", "x")]),
])
def test_a_bracketed_number_elsewhere_is_still_a_factor(text, expected):
    assert kinds(text) == expected


@pytest.mark.parametrize("text", ["x (2)", "(2) y = l", "x = l\n(2) y = l", "x + y = l (2)", "x = l (1); y = l",
                                  "x = l (2), y = l",
                                  r"x + y = l \;\;(2)"])
def test_a_bracketed_number_set_apart_at_a_line_end_is_ambiguous(text):
    # an equation's number (Word numbers them so) or a factor: read as a factor it would silently change
    # the equation, so it is refused naming both readings
    bad = [t for t in tokenize(text) if t.kind == "bad"]
    assert bad and bad[0].error.code == "ambiguous" and "equation's number or as a factor" in bad[0].error.message


@pytest.mark.parametrize("text, expected", [
    # a Python module prefix is one name token, the function, spanning what was typed
    ("np.sin(x)", [("name", "sin"), ("open", "("), ("name", "x"), ("close", ")")]),
    ("2*math.pi", [("number", 2), ("op", "*"), ("name", "pi")]),
    # MATLAB's element-wise operators are the operators
    ("a.*b./c.^2", [("name", "a"), ("op", "*"), ("name", "b"), ("op", "/"), ("name", "c"), ("op", "^"), ("number", 2)]),
    # Word's FUNCTION APPLICATION is a space, INVISIBLE TIMES a product
    ("sin\u2061x", [("name", "sin"), ("name", "x")]),
    ("m\u2062g", [("name", "m"), ("op", "*"), ("name", "g")]),
])
def test_operators_and_prefixes_of_other_tools(text, expected):
    assert kinds(text) == expected


def test_a_module_prefixed_name_points_at_what_was_typed():
    token = tokenize("x + np.sqrt(x)")[2]
    assert (token.value, token.text, token.pos) == ("sqrt", "np.sqrt", 4)


@pytest.mark.parametrize("text", ["m.g", "x.y"])
def test_a_dot_between_names_is_still_refused(text):
    # Only .*, ./ and .^ are MATLAB's operators; a bare dot between names is no product.
    bad = [t for t in tokenize(text) if t.kind == "bad"]
    assert bad and "attribute access" in bad[0].error.message


@pytest.mark.parametrize("text, name, order", [
    # ASCIIMath's subscript in round brackets, which it does not print: x_(2) is x₂, never x·2
    ("x_(2)", "x_2", 0), ("theta_(0)", "theta_0", 0), ("m_( 12 )", "m_12", 0), ("v_(max)", "v_max", 0),
    ("θ_(1)", "theta_1", 0), ("x_(α)", "x_alpha", 0), ("θ̇_(1)", "theta_1", 1), ("theta''_(2)", "theta_2", 2),
])
def test_a_subscript_in_round_brackets_belongs_to_the_name(text, name, order):
    [token] = tokenize(text)[:-1]
    assert (token.kind, token.value, token.order) == ("name", name, order)


def test_only_a_plain_index_in_round_brackets_is_a_subscript():
    # x_(1 + n) holds no index to read: the bracket stays a bracket
    assert kinds("x_(1 + n)")[1:] == [("open", "("), ("number", 1), ("op", "+"), ("name", "n"), ("close", ")")]
    # after x_(2) a second bracket is a factor of its own
    assert kinds("x_(2)(y)") == [("name", "x_2"), ("open", "("), ("name", "y"), ("close", ")")]


@pytest.mark.parametrize("text, value", [
    # scientific notation whose minus a word processor or PDF changed, and calculators' ᴇ (TI, NumWorks):
    # 1.5e−3 was 1.5·e − 3 with Euler's e
    ("1.5e−3", sympy.Rational(3, 2000)), ("1.5E–3", sympy.Rational(3, 2000)), ("2e—2", sympy.Rational(1, 50)),
    ("1e‒3", sympy.Rational(1, 1000)), ("1e‐3", sympy.Rational(1, 1000)), ("1e‑3", sympy.Rational(1, 1000)),
    ("1e﹣3", sympy.Rational(1, 1000)), ("1e－3", sympy.Rational(1, 1000)), ("1e＋3", 1000),
    ("1.5ᴇ3", 1500), ("1.5ᴇ-3", sympy.Rational(3, 2000)), ("1.5ᴇ⁻3", sympy.Rational(3, 2000)),
    ("1.5ᴇ−3", sympy.Rational(3, 2000)), ("1.5ᴇ+3", 1500),
])
def test_a_power_of_ten_with_any_minus_is_one_number(text, value):
    [token] = tokenize(text)[:-1]
    assert (token.kind, token.value, token.decimal) == ("number", value, True)


def test_an_exponent_mark_without_a_power_is_not_a_number():
    # no digit after the minus: Euler's e
    assert kinds("2e−x") == [("number", 2), ("name", "e"), ("op", "-"), ("name", "x")]
    # a raised minus is a calculator's sign only after its ᴇ: 1e⁻2 is not read as 1/100
    with pytest.raises(ExpressionError):
        tokenize("1e⁻2")


@pytest.mark.parametrize("text", ["1ᴇ", "ᴇ3", "1ᴇ2ᴇ3"])
def test_a_calculators_e_without_its_number_is_refused_saying_what_it_is(text):
    with pytest.raises(ExpressionError) as refused:
        tokenize(text)
    assert "'ᴇ'" in refused.value.message and "calculator's 'times ten to the'" in refused.value.hint


@pytest.mark.parametrize("text, name, order", [
    # Mathematica's "Copy As Plain Text" of a subscripted name
    ("Subscript[m, 1]", "m_1", 0), ("Subscript[\\[Theta], 0]", "theta_0", 0), ("Subscript[θ, max]", "theta_max", 0),
    ("Subscript[theta,2]", "theta_2", 0), ("Subscript[θ, 1]'", "theta_1", 1), ("Subscript[x, 2]''", "x_2", 2),
])
def test_mathematicas_subscript_is_the_subscripted_name(text, name, order):
    [token] = tokenize(text)[:-1]
    assert (token.kind, token.value, token.order) == ("name", name, order)


def test_mathematicas_subscript_of_an_unknown_character_is_refused_by_name():
    [bad] = [t for t in tokenize("Subscript[\\[Foo], 1]") if t.kind == "bad"]
    assert "Subscript[\\[Foo], 1]" in bad.error.message and "x_1" in bad.error.hint


@pytest.mark.parametrize("text", ["a -: b", "a−:b"])
def test_asciimaths_division_sign_is_a_quotient(text):
    assert kinds(text) == [("name", "a"), ("op", "/"), ("name", "b")]


@pytest.mark.parametrize("text", ["m*g//3", "a // b"])
def test_a_double_slash_is_refused_naming_its_readings(text):
    # floor division (Python), postfix application (Mathematica), a slash (ASCIIMath): never guessed
    [bad] = [t for t in tokenize(text) if t.kind == "bad"]
    assert bad.error.code == "ambiguous" and "floor division" in bad.error.message and bad.error.hint.startswith("write / for a quotient")


@pytest.mark.parametrize("text", ["R1 // R2", "R1//R2"])
def test_a_double_slash_names_the_french_parallel_and_its_fix(text):
    # R1 // R2 is 'R1 in parallel with R2' in French: "write / for a quotient" alone was the wrong fix
    [bad] = [t for t in tokenize(text) if t.kind == "bad"]
    assert "in parallel" in bad.error.message and "a*b/(a + b)" in bad.error.hint


@pytest.mark.parametrize("text", ["x\u2028y", "x\u2029y", "x\u0085y", "x\x0by", "x\x0cy"])
def test_pasted_line_and_paragraph_separators_are_line_breaks(text):
    # Word, PDFs and web pages paste U+2028/U+2029 where a line ends; they were 'not allowed' characters
    assert kinds(text) == [("name", "x"), ("newline", "\n"), ("name", "y")]


def test_a_comment_sign_is_refused_saying_what_it_is():
    [bad] = [t for t in tokenize("m*g # the weight") if t.kind == "bad"]
    assert "comment" in bad.error.message and "delete the '#'" in bad.error.hint


@pytest.mark.parametrize("text, name", [
    # Unicode's subscript letters are a subscript, as its subscript digits are
    ("vₓ", "v_x"), ("θₘₐₓ", "theta_max"), ("Fₙ", "F_n"), ("aᵦ", "a_beta"), ("v₀ₓ", "v_0_x"), ("xₜ", "x_t"),
])
def test_subscript_letters_are_a_subscript(text, name):
    [token] = tokenize(text)[:-1]
    assert (token.kind, token.value) == ("name", name)


def test_the_subscript_letter_o_is_refused_saying_it_is_not_zero():
    # vₒ for v₀: read as the letter, it named no variable, and the hint said "type the ordinary 'o'"
    with pytest.raises(ExpressionError) as refused:
        tokenize("m vₒ²")
    assert "not the digit zero" in refused.value.message and "v_0" in refused.value.hint


@pytest.mark.parametrize("text, index", [("√(3&x)", 3), ("√(4 & x)", 4), ("√( 2&x)", 2)])
def test_unicodemaths_root_with_an_index_is_that_root(text, index):
    # Word's linear format writes \root 3\of x as √(3&x); the '&' was refused as a LaTeX alignment mark
    assert kinds(text) == [("root", index), ("open", "("), ("name", "x"), ("close", ")")]


def test_unicodemaths_root_of_index_one_is_refused():
    with pytest.raises(ExpressionError) as refused:
        tokenize("√(1&x)")
    assert "index 1" in refused.value.message and "√(3&x)" in refused.value.hint


@pytest.mark.parametrize("text, words", [
    ("x + 0.5…", "give it in full"), ("x + x^2/2 + ⋯", "give it in full"), ("2\u2064½", "mixed number"),
])
def test_what_pasted_text_carries_is_refused_saying_what_to_type(text, words):
    with pytest.raises(ExpressionError) as refused:
        tokenize(text)
    assert words in refused.value.message + "; " + refused.value.hint


def test_a_calculators_radian_mark_is_refused_naming_both_readings():
    # 'ʳ' was refused as a superscript letter with the fix 'write x^r': a TI calculator means radians
    with pytest.raises(ExpressionError) as refused:
        tokenize("sin(0.5ʳ)")
    assert "radian mark" in refused.value.message and "delete the 'ʳ'" in refused.value.hint


@pytest.mark.parametrize("text, value", [("5·9.81", sympy.Rational(981, 20)), ("2·0.5", 1)])
def test_a_raised_dot_before_a_decimal_is_a_product(text, value):
    # 5·9.81 was refused as '5·9': the British decimal 5.9 or a product, though 9.81 has its own point
    tokens = tokenize(text)[:-1]
    assert [t.kind for t in tokens] == ["number", "op", "number"]
    assert tokens[0].value * tokens[2].value == value


@pytest.mark.parametrize("text, expected", [
    # a calculator's root with its index as a superscript (TI's ³√(): the index, not a power of what is before
    ("³√(x)", [("root", 3), ("open", "("), ("name", "x"), ("close", ")")]),
    ("2 ⁴√x", [("number", 2), ("root", 4), ("name", "x")]),
    ("2·³√x", [("number", 2), ("op", "*"), ("root", 3), ("name", "x")]),
    ("x² √y", [("name", "x"), ("sup", 2), ("root", 2), ("name", "y")]),  # set apart from the √: a power
])
def test_a_superscript_index_on_a_root_sign_is_the_roots_index(text, expected):
    assert kinds(text) == expected


@pytest.mark.parametrize("text", ["2³√x", "x³√(y)"])
def test_a_superscript_index_glued_to_an_operand_is_refused_naming_both_readings(text):
    # 2 ³√k was 2³·√k = 8√k; glued, 2³√x could be either
    with pytest.raises(ExpressionError) as refused:
        tokenize(text)
    assert refused.value.code == "ambiguous" and "root of index 3" in refused.value.message


@pytest.mark.parametrize("text", ["x^2²", "θ̇^2 ²", "2^3²", "x^(2)²", "x^{2}²", "θ̇^( 2 )²"])
def test_a_power_given_twice_is_refused(text):
    # θ̇^2² was θ̇^(2²) = θ̇⁴ without a word: the square typed twice, or a power of the power? Its
    # exponent in brackets, x^(2)² (x^{2}² in LaTeX), was read as x⁴ too
    with pytest.raises(ExpressionError) as refused:
        tokenize(text)
    assert refused.value.code == "ambiguous" and "gives the power twice" in refused.value.message


@pytest.mark.parametrize("text", ["x²", "(x^2)²", "x^2 y²", "x^(2) + y²", "x^(n)²"])
def test_a_superscript_after_a_power_that_is_closed_is_still_read(text):
    assert all(t.kind != "bad" for t in tokenize(text))


@pytest.mark.parametrize("text, braced", [
    # without braces TeX's \mathrm, \text, \boldsymbol take one character or one command
    (r"\mathrm l", r"\mathrm{l}"), (r"\text l", r"\text{l}"), (r"\mathbf g", r"\mathbf{g}"),
    (r"\boldsymbol\omega", r"\boldsymbol{\omega}"), (r"\mathrm ll", r"\mathrm{l}l"), (r"\mathrm e^x", r"\mathrm{e}^x"),
    (r"\mathrm 12", r"\mathrm{12}"),
])
def test_a_font_command_without_braces_takes_one_character_as_tex_does(text, braced):
    assert [(t.kind, t.value) for t in tokenize(text)] == [(t.kind, t.value) for t in tokenize(braced)]


# -- red team 22: a phone's smart quotes, a chat assistant's Markdown --

@pytest.mark.parametrize("text, shown", [('θ" = 0', 'θ"'), ("θ” = 0", "θ”"), ('theta" + x', 'theta"'), ("x＂", 'x"'),
                                         ("x_1” + 1", "x_1”")])
def test_a_double_quote_after_a_name_is_refused_naming_the_double_prime_and_the_quotation_mark(text, shown):
    # θ" (″ typed on a keyboard without one; a phone's smart punctuation makes it θ”) was told to delete the
    # quotation marks, which loses the derivative the student meant
    bad = [t for t in tokenize(text) if t.kind == "bad"]
    assert bad and bad[0].error.code == "ambiguous"
    assert shown in bad[0].error.message and "double prime" in bad[0].error.message \
        and "quotation mark" in bad[0].error.message and "''" in bad[0].error.hint


@pytest.mark.parametrize("text", ['"θ" = 0', "“θ” = 0"])
def test_a_double_quote_that_closes_a_quotation_is_still_a_quotation_mark(text):
    with pytest.raises(ExpressionError) as refused:
        [t.error for t in tokenize(text) if t.kind == "bad" and t.error and _raise(t.error)]
    assert "QUOT" in refused.value.message.upper() and refused.value.code != "ambiguous"


def _raise(error):
    raise error


@pytest.mark.parametrize("text, plain", [
    ("**m g + x**", "m g + x"), ("**T = m g**", "T = m g"), ("  **m g**\n", "m g\n"), ("**\\(m g\\)**", "\\(m g\\)"),
    ("**T = m g**.", "T = m g."), ("**m g**。", "m g。"),  # the sentence's full stop after the bold
])
def test_markdown_bold_around_the_whole_answer_is_only_its_look(text, plain):
    assert kinds(text) == kinds(plain)


@pytest.mark.parametrize("text", ["m**2", "**m g** + x**", "**m**2**", "** m g **"])
def test_double_asterisks_that_are_not_bold_around_the_answer_stay_what_they_were(text):
    assert ("op", "^") in kinds(text)


@pytest.mark.parametrize("text, order", [("θ \u0307", 1), ("𝜃 \u0307", 1), ("θ \u0308", 2), ("x \u0307 \u0307", 2),
                                         ("θ\u00a0\u0307", 1),  # on a no-break space, Unicode's preferred base
                                         ("〖𝜃 \u0307〗", 1), ("(θ \u0307)", 1)])
def test_a_combining_dot_on_a_space_after_a_name_is_the_names_spacing_dot(text, order):
    # Unicode's spacing form of a combining mark is the mark on a space: Word's linear format writes θ̇ as 〖𝜃 ̇〗,
    # which was "accent COMBINING DOT ABOVE does not follow a variable name"
    names = [t for t in tokenize(text) if t.kind == "name"]
    assert len(names) == 1 and names[0].order == order and all(t.kind != "bad" for t in tokenize(text))


@pytest.mark.parametrize("text", ["θ  \u0307", "2 \u0307", "( \u0307"])
def test_a_combining_dot_after_a_gap_or_no_name_is_still_refused(text):
    with pytest.raises(ExpressionError) as refused:
        tokenize(text)
    assert "COMBINING DOT ABOVE" in refused.value.message or "COMBINING DIAERESIS" in refused.value.message


@pytest.mark.parametrize("text, plain", [("'diff(y, t)", "diff(y, t)"), ("2*'diff(y,t,2)", "2*diff(y,t,2)")])
def test_maximas_noun_form_of_diff_is_diff(text, plain):
    # STACK asks for 'diff(y, x) in a differential equation; the quote was "a prime can only follow a variable"
    assert kinds(text) == kinds(plain)


# -- red team 22: a list's markers, as a chat assistant or a word processor sets several equations out --

@pytest.mark.parametrize("text, plain", [
    ("1. x = 1\n2. y = 2", "x = 1\ny = 2"), ("1) x = 1\n2) y = 2", "x = 1\ny = 2"),
    ("  1. x = 1\n  2. y = 2\n  3. x = y", "x = 1\ny = 2\nx = y"),
    ("* x = 1\n* y = 2", "x = 1\ny = 2"), ("• x = 1\n• y = 2", "x = 1\ny = 2"), ("• x = 1", "x = 1"),
    ("◦ x = 1\n◦ y = 2", "x = 1\ny = 2"),
])
def test_a_lists_numbers_and_bullets_are_only_its_layout(text, plain):
    # 1. was "a decimal point must be followed by digits", 1) "')' has no matching '('", • "unexpected '•'"
    assert kinds(text) == kinds(plain)


@pytest.mark.parametrize("text", ["- x = 1\n- y = 2", "– x = 1\n– y = 2"])
def test_a_dash_before_every_line_is_refused_naming_bullets_and_minus_signs(text):
    # read as minus signs, "- (m1 + m2) r̈ … = 0" on each line negated its first term: a right answer marked wrong
    with pytest.raises(ExpressionError) as refused:
        tokenize(text)
    assert refused.value.code == "ambiguous" and "bullets" in refused.value.message \
        and "minus sign" in refused.value.message


@pytest.mark.parametrize("text", ["- x = 1", "x = 1\n- y = 2", "2. x", "1. x = 1\n3. y = 2", "x\n- y", "1. x\ny = 2"])
def test_what_is_not_a_whole_list_keeps_its_reading(text):
    tokens = tokenize(text)
    assert any(t.kind in ("op", "bad") and t.text in ("-", "–", ".") for t in tokens)


@pytest.mark.parametrize("text, plain", [
    ("Answer: m g", "m g"), ("answer: T = m g", "T = m g"), ("Final answer: m g", "m g"), ("Tension: m g", "m g"),
    ("**Answer:** m g", "m g"), ("Eq1: x = 1\nEq2: y = 2", "x = 1\ny = 2"), ("ANSWER : m g", "m g"),
    ("Equation of motion: x = 1", "x = 1"), ("Respuesta: m g", "m g"),
])
def test_a_caption_before_the_answer_is_only_its_label(text, plain):
    # "Answer: m g" was "unknown name 'Answer'", as \text{Answer: } before a LaTeX answer is read as a caption
    assert kinds(text) == kinds(plain)


@pytest.mark.parametrize("text", ["mg : l", "m1m2g : (m1+m2)", "x: y", "Answer:m g"])
def test_a_colon_after_anything_but_a_caption_keeps_its_refusal(text):
    # a ratio mg : l must not lose its mg
    assert any(t.kind == "bad" and ":" in t.text for t in tokenize(text))


@pytest.mark.parametrize("text, plain", [("x = ⁻3", "x = -3"), ("⁻x", "-x"), ("x + ⁻y", "x + -y"), ("(⁻x)", "(-x)")])
def test_a_raised_minus_where_no_power_can_be_is_a_calculators_negation(text, plain):
    # a TI calculator's (-) key prints ⁻3: it was "cannot read the superscript '⁻'"
    assert kinds(text) == kinds(plain)


@pytest.mark.parametrize("text, sup", [("x⁻¹", -1), ("x ⁻¹", -1), ("(x)⁻²", -2)])
def test_a_raised_minus_after_an_operand_is_still_a_power(text, sup):
    assert ("sup", sup) in kinds(text)


@pytest.mark.parametrize("text", ["\ufeffm g", "m g\u200b", "\u200em g", "m g\u00ad", " \u200b m g \u2060\n", "m g\u2062"])
def test_an_invisible_character_before_or_after_the_formula_changes_nothing(text):
    # a byte order mark at the start or a zero-width space at the end was "delete it": the student cannot see it
    assert kinds(text) == kinds(text.replace("\ufeff", "").replace("\u200b", "").replace("\u200e", "")
                                .replace("\u00ad", "").replace("\u2060", "").replace("\u2062", ""))


@pytest.mark.parametrize("text", ["m\u200bg", "\u202em g", "m g \u202e", "\u200fm g", "\u2067m g\u2069"])
def test_an_invisible_character_inside_or_one_that_turns_the_display_stays_refused(text):
    # inside it may split a name (m​g); a direction override or isolate shows the formula otherwise than it reads
    with pytest.raises(ExpressionError) as refused:
        tokenize(text)
    assert "invisible character" in refused.value.message
