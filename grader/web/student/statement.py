"""A problem statement as HTML: Markdown with ``$...$`` (inline) and ``$$...$$`` (display) math.

Math spans are cut out before Markdown sees them (so ``_`` and ``*`` inside math stay math), turned
into MathML on the server (:mod:`grader.web.student.mathml`), and put back afterwards. Raw HTML in
the statement is shown as text, not obeyed: scene files are uploaded and are untrusted. Markdown's
output then goes through ``nh3`` (the Ammonia sanitizer) on an allow-list of tags, attributes and URL
schemes; it parses the HTML first, so a scheme hidden in entities (``javascript&#58;``) or split by
control characters is judged as the browser would read it. The MathML is put back only after that,
and only into text: it comes from our own converter, which escapes everything it copies.

>>> str(render_statement("Find $x^2$."))[:45]
'<p>Find <math display="inline"><semantics><mr'
"""

from __future__ import annotations

import re
from functools import lru_cache
from html import escape

import markdown
import nh3
from markupsafe import Markup

from grader.web.student.mathml import to_mathml, unsupported

__all__ = ["render_inline", "render_math", "render_statement", "render_text", "sanitize", "statement_problems"]

# $$...$$ first, then $...$ that neither starts nor ends with a space (so "costs $5 or $6" is text);
# a backslash-escaped \$ is a literal dollar.
_MATH = re.compile(r"(?<!\\)\$\$(.+?)(?<!\\)\$\$|(?<![\\$])\$(?!\s)((?:\\\$|[^$])+?)(?<![\s\\])\$(?!\$)", re.S)
_SLOT = "LAGRADEMATHSLOT{}X"
_SLOT_PATTERN = re.compile(r"LAGRADEMATHSLOT(\d+)X")

# What Markdown (with sane_lists) writes, and nothing else: no script, style, frame, form or SVG, no
# event handler or style attribute. Links and images keep only these schemes or a relative URL.
ALLOWED_TAGS = frozenset({
    "p", "br", "hr", "em", "strong", "code", "pre", "blockquote", "ul", "ol", "li",
    "h1", "h2", "h3", "h4", "h5", "h6", "a", "img",
})
ALLOWED_ATTRIBUTES = {"a": {"href", "title"}, "img": {"src", "alt", "title"}, "ol": {"start"}}
ALLOWED_URL_SCHEMES = frozenset({"http", "https", "mailto"})


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

    html = sanitize(_markdown().convert(_MATH.sub(cut, text or "").replace(r"\$", "$")))
    # Slots left in the text become MathML; a slot the author typed that names no formula stays text.
    html = _SLOT_PATTERN.sub(lambda m: spans[int(m.group(1))] if int(m.group(1)) < len(spans) else m.group(0),
                             html)
    return Markup(html)


def sanitize(html: str) -> str:
    """``html`` reduced to the statement allow-list (tags, attributes, URL schemes).

    >>> sanitize('<a href="javascript&#58;alert(1)" onclick="x()">x</a><img src=x onerror=alert(1)>')
    '<a rel="noopener noreferrer">x</a><img src="x">'
    """
    return nh3.clean(html, tags=set(ALLOWED_TAGS), attributes={k: set(v) for k, v in ALLOWED_ATTRIBUTES.items()},
                     url_schemes=set(ALLOWED_URL_SCHEMES), attribute_filter=_no_math_in_attributes,
                     strip_comments=True, link_rel="noopener noreferrer")


def _no_math_in_attributes(tag: str, attribute: str, value: str) -> str:
    # Math put into an attribute (a link "($x$)", a title) would be markup inside quotes: keep the slot out
    # of attributes, so only text nodes are filled with MathML.
    return _SLOT_PATTERN.sub("", value)


def render_inline(text: str) -> Markup:
    """A one-line text with Markdown and math (an answer's prompt), without the enclosing paragraph."""
    html = str(render_statement(text or ""))
    if html.startswith("<p>") and html.endswith("</p>") and html.count("<p>") == 1:
        html = html[3:-4]
    return Markup(html)


@lru_cache(maxsize=1024)
def render_text(text: str) -> Markup:
    """A message (feedback, a verdict's reason, a scene error) as safe HTML: its ``$...$`` as MathML,
    everything else as plain text. No Markdown: in "m*g*l" or "lambda_surface" outside math the
    stars and underscores are what was typed, not emphasis; line breaks are kept by the page's CSS.

    >>> str(render_text("Check $N$ & <b>"))[:56]
    'Check <math display="inline"><semantics><mrow><mi>N</mi>'
    >>> str(render_text("costs $5 or $6 & <b>"))
    'costs $5 or $6 &amp; &lt;b&gt;'
    """
    text = text or ""
    parts, last = [], 0
    for match in _MATH.finditer(text):
        parts.append(escape(text[last:match.start()].replace(r"\$", "$")))
        display, inline = match.group(1), match.group(2)
        tex = (display if display is not None else inline).replace(r"\$", "$")
        parts.append(to_mathml(tex, display=display is not None))
        last = match.end()
    parts.append(escape(text[last:].replace(r"\$", "$")))
    return Markup("".join(parts))


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
