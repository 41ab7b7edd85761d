"""Statements: Markdown with $...$ math, rendered on the server, with raw HTML shown as text."""

from grader.web.student.statement import render_inline, render_statement, statement_problems


def test_inline_and_display_math_become_mathml_inside_markdown():
    html = str(render_statement("A *bead* of mass $m_1$ slides.\n\n$$L = T - V$$"))
    assert "<em>bead</em>" in html
    assert '<math display="inline"><semantics><mrow><msub><mi>m</mi><mn>1</mn></msub>' in html
    assert '<math display="block">' in html


def test_underscores_and_stars_inside_math_stay_math():
    html = str(render_statement("$a_1 * b_2$ and $c_3$"))
    assert "<em>" not in html and html.count("<msub>") == 3


def test_dollar_amounts_and_escaped_dollars_are_text():
    html = str(render_statement(r"It costs \$5, or $ 6 $ maybe."))
    assert "<math" not in html and "$5" in html


def test_raw_html_and_script_links_are_not_obeyed():
    html = str(render_statement('<script>alert(1)</script> [x](javascript:alert(1)) [y](https://example.org)'))
    assert "<script>" not in html and "&lt;script&gt;" in html
    assert 'href="#"' in html and 'href="https://example.org"' in html


def test_a_prompt_renders_without_its_paragraph():
    assert str(render_inline(r"Angular acceleration $\ddot\theta$")).startswith("Angular acceleration <math")


def test_statement_problems_lists_what_cannot_be_shown():
    assert statement_problems(r"fine $\theta$, not fine $\weird{x}$") == ["\\weird"]
