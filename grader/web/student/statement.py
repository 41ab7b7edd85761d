"""A problem statement as HTML: Markdown with ``$...$`` (inline) and ``$$...$$`` (display) math.

Math spans are cut out before Markdown sees them (so ``_`` and ``*`` inside math stay math), turned
into MathML on the server (:mod:`grader.web.student.mathml`), and put back afterwards. Raw HTML in
the statement is shown as text, not obeyed: scene files are uploaded and are untrusted.

>>> str(render_statement("Find $x^2$."))[:45]
'<p>Find <math display="inline"><semantics><mr'
"""

from __future__ import annotations

import re
from functools import lru_cache

import markdown
from markupsafe import Markup

from grader.web.student.mathml import to_mathml, unsupported

__all__ = ["render_inline", "render_math", "render_statement", "statement_problems"]

# $$...$$ first, then $...$ that neither starts nor ends with a space (so "costs $5 or $6" is text);
# a backslash-escaped \$ is a literal dollar.
_MATH = re.compile(r"(?<!\\)\$\$(.+?)(?<!\\)\$\$|(?<![\\$])\$(?!\s)((?:\\\$|[^$])+?)(?<![\s\\])\$(?!\$)", re.S)
_SLOT = "LAGRADEMATHSLOT{}X"
# Links and images keep only harmless schemes: "javascript:" in a statement must not become a link.
_URL_ATTRIBUTE = re.compile(r'(href|src)="(?!https?:|mailto:|#|/(?!/)|[^":]*(?:"|$))[^"]*"', re.I)


def _markdown() -> markdown.Markdown:
    md = markdown.Markdown(extensions=["sane_lists"], output_format="html")
    # No raw HTML from the statement: without these two, "<script>" would pass straight through.
    md.preprocessors.deregister("html_block")
    md.inlinePatterns.deregister("html")
    return md


@lru_cache(maxsize=512)
def render_statement(text: str) -> Markup:
    """The statement ``text`` (Markdown + math) as safe HTML."""
    spans: list[str] = []

    def cut(match: re.Match) -> str:
        display, inline = match.group(1), match.group(2)
        tex = (display if display is not None else inline).replace(r"\$", "$")
        spans.append(to_mathml(tex, display=display is not None))
        return _SLOT.format(len(spans) - 1)

    html = _markdown().convert(_MATH.sub(cut, text or "").replace(r"\$", "$"))
    html = _URL_ATTRIBUTE.sub(r'\1="#"', html)
    html = re.sub(r"LAGRADEMATHSLOT(\d+)X", lambda m: spans[int(m.group(1))], html)
    return Markup(html)


def render_inline(text: str) -> Markup:
    """A one-line text with Markdown and math (an answer's prompt), without the enclosing paragraph."""
    html = str(render_statement(text or ""))
    if html.startswith("<p>") and html.endswith("</p>") and html.count("<p>") == 1:
        html = html[3:-4]
    return Markup(html)


def render_math(tex: str | None, display: bool = False) -> Markup:
    """One LaTeX formula (e.g. sympy's ``latex()`` of an answer) as MathML, or nothing."""
    return Markup(to_mathml(tex, display=display)) if tex else Markup("")


def statement_problems(text: str) -> list[str]:
    """LaTeX commands in the statement's math that will show as errors, for the draft review."""
    found: list[str] = []
    for match in _MATH.finditer(text or ""):
        tex = match.group(1) if match.group(1) is not None else match.group(2)
        found += [c for c in unsupported(tex) if c not in found]
    return found
