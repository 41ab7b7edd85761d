"""Statements: Markdown with $...$ math, rendered on the server, with raw HTML shown as text."""

import re
from html.parser import HTMLParser

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from grader.web.student.statement import ALLOWED_TAGS, render_inline, render_statement, render_text, statement_problems


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
    assert ">x</a>" in html and "javascript" not in html and 'href="https://example.org"' in html


def test_a_prompt_renders_without_its_paragraph():
    assert str(render_inline(r"Angular acceleration $\ddot\theta$")).startswith("Angular acceleration <math")


def test_statement_problems_lists_what_cannot_be_shown():
    assert statement_problems(r"fine $\theta$, not fine $\weird{x}$") == ["\\weird"]


# Known XSS vectors, as an author could put them in a statement (scene files are uploaded, untrusted).
XSS_VECTORS = [
    "[x](javascript:alert(1))",
    "[x](JaVaScRiPt:alert(1))",
    "[x](javascript&#58;alert(1))",  # decimal entity for ':'
    "[x](javascript&#x3A;alert(1))",  # hex entity
    "[x](javascript&colon;alert(1))",  # named entity
    "[x](javascript&#0000058alert(1))",  # zero-padded, no semicolon
    "[x](&#106;avascript:alert(1))",
    "[x](&#x6A;&#x61;&#x76;&#x61;&#x73;&#x63;&#x72;&#x69;&#x70;&#x74;&#x3a;alert(1))",
    "[x](javas&#99;ript:alert(1))",
    "[x](java&#9;script:alert(1))",  # a tab inside the scheme, which browsers drop
    "[x](java&Tab;script:alert(1))",
    "[x](java&#x0A;script:alert(1))",
    "[x](&NewLine;javascript:alert(1))",
    "[x](&#x20;javascript:alert(1))",
    "[x](\x01javascript:alert(1))",  # a control character before the scheme
    "[x](<javascript:alert(1)>)",
    "[x](javascript:alert(1) \"title\")",
    "[x](data:text/html;base64,PHNjcmlwdD5hbGVydCgxKTwvc2NyaXB0Pg==)",
    "[x](DATA&colon;text/html,<script>alert(1)</script>)",
    "[x](vbscript:msgbox(1))",
    "[x](VBScript&#58;msgbox(1))",
    "![i](javascript:alert(1))",
    '![i](x" onerror="alert(1))',
    '![i](x "t\\" onerror=\\"alert(1)")',
    "[x][r]\n\n[r]: javascript:alert(1)",
    '[x][r]\n\n[r]: javascript&#58;alert(1) "t"',
    "![i][r]\n\n[r]: data:image/svg+xml;base64,PHN2ZyBvbmxvYWQ9YWxlcnQoMSk+",
    "<javascript:alert(1)>",
    "<script>alert(1)</script>",
    "<img src=x onerror=alert(1)>",
    "<svg onload=alert(1)>",
    "<svg><script>alert(1)</script></svg>",
    '<iframe src="javascript:alert(1)"></iframe>',
    "<style>*{background:url(javascript:alert(1))}</style>",
    "<div>\n<script>alert(1)</script>\n</div>",  # a raw HTML block
    '<a href="javascript:alert(1)">x</a>',
    "<details open ontoggle=alert(1)>",
    '<form><button formaction="javascript:alert(1)">x</button></form>',
    '<object data="javascript:alert(1)"></object>',
    "<math><mtext><table><mglyph><style><img src=x onerror=alert(1)>",  # mutation XSS
    "<!-- --><script>alert(1)</script>",
    '<p style="background:url(javascript:alert(1))">x</p>',
    "$x$ <img src=x onerror=alert(1)>",
    "[$x$](javascript:alert(1))",
    '[x]($" onmouseover="alert(1)$)',  # math inside a link target
    '![i](https://example.org/a.png "$" onerror="alert(1)$")',  # math inside a title
    r"$\text{<script>alert(1)</script>}$",
    r'$\mathrm{" onload="alert(1)}$',
    "LAGRADEMATHSLOT0X [x](javascript:alert(1))",  # a forged math slot
]
MATHML_TAGS = {"math", "semantics", "annotation", "mrow", "mi", "mn", "mo", "mtext", "msub", "msup",
               "msubsup", "mfrac", "msqrt", "mroot", "mover", "munder", "munderover", "mspace", "mstyle",
               "merror", "mtable", "mtr", "mtd", "mpadded", "mphantom"}
URL_ATTRIBUTES = {"href", "src", "action", "formaction", "data", "xlink:href", "background", "poster"}
SAFE_SCHEMES = {"http", "https", "mailto"}


class _Elements(HTMLParser):
    """Every start tag of a fragment with its attributes (values entity-decoded, as a browser reads them)."""

    def __init__(self):
        super().__init__(convert_charrefs=True)
        self.elements: list[tuple[str, list[tuple[str, str | None]]]] = []

    def handle_starttag(self, tag, attrs):
        self.elements.append((tag, attrs))

    handle_startendtag = handle_starttag


def _scheme(url: str) -> str | None:
    # As the URL standard reads it: leading C0 controls and spaces go, tabs and newlines anywhere go.
    cleaned = re.sub(r"[\t\n\r]", "", url).lstrip("".join(map(chr, range(0x21))))
    found = re.match(r"([a-zA-Z][a-zA-Z0-9+.\-]*):", cleaned)
    return found.group(1).lower() if found else None


def _script_vectors(html: str) -> list[str]:
    """What in ``html`` a browser could run: unknown tags, handlers, style, or a URL with a bad scheme."""
    parser = _Elements()
    parser.feed(html)
    parser.close()
    found = []
    for tag, attrs in parser.elements:
        if tag not in ALLOWED_TAGS | MATHML_TAGS:
            found.append(f"<{tag}>")
        for name, value in attrs:
            if name.startswith("on") or name in {"style", "srcdoc"}:
                found.append(f"{tag}[{name}]")
            elif name in URL_ATTRIBUTES and _scheme(value or "") not in SAFE_SCHEMES | {None}:
                found.append(f"{tag}[{name}={value!r}]")
    return found


@pytest.mark.parametrize("render", [render_statement, render_inline, render_text], ids=["statement", "inline", "text"])
@pytest.mark.parametrize("vector", XSS_VECTORS)
def test_no_xss_vector_survives_rendering(render, vector):
    html = str(render(vector))
    assert _script_vectors(html) == []
    assert "<script" not in html.lower()  # as text it shows as "&lt;script"


def test_the_corpus_check_itself_sees_script():
    # The checker above must catch what the sanitizer removes, or every vector would pass vacuously.
    assert _script_vectors('<a href="java&#9;script&#58;x">x</a><img src=x onerror=y><svg>') == [
        "a[href='java\\tscript:x']", "img[onerror]", "<svg>"]


@pytest.mark.parametrize(("text", "tag", "attribute", "url"), [
    ("[a](https://example.org/x?y=1&z=2)", "a", "href", "https://example.org/x?y=1&z=2"),
    ("[a](http://example.org)", "a", "href", "http://example.org"),
    ("[m](mailto:teacher@example.org)", "a", "href", "mailto:teacher@example.org"),
    ("<teacher@example.org>", "a", "href", "mailto:teacher@example.org"),
    ("<https://example.org/notes>", "a", "href", "https://example.org/notes"),
    ("[r](/problems/sphere)", "a", "href", "/problems/sphere"),
    ("[r](notes.html#part-2)", "a", "href", "notes.html#part-2"),
    ("[top](#top)", "a", "href", "#top"),
    ("[r][ref]\n\n[ref]: https://example.org/ref", "a", "href", "https://example.org/ref"),
    ("![figure](figures/incline.png)", "img", "src", "figures/incline.png"),
    ("![figure](https://example.org/a.png)", "img", "src", "https://example.org/a.png"),
])
def test_legitimate_links_and_images_survive(text, tag, attribute, url):
    parser = _Elements()
    parser.feed(str(render_statement(text)))
    assert (tag, url) in [(t, dict(attrs).get(attribute)) for t, attrs in parser.elements]


def test_math_and_markdown_still_render_next_to_a_removed_vector():
    html = str(render_statement("A *bead* $m_1$ <img src=x onerror=alert(1)> [x](javascript&#58;alert(1))"))
    assert "<em>bead</em>" in html and "<msub><mi>m</mi><mn>1</mn></msub>" in html
    assert _script_vectors(html) == []


_FRAGMENTS = ["[x](", ")", "![i](", "<", ">", "javascript", "&#58;", "&colon;", "&#x3A;", ":", "&Tab;", "\t", "\n",
              "data", "vbscript", "$", "$$", "x", '"', "'", " ", "onerror=", "alert(1)", "<img src=x ", "<svg ",
              "<script>", "[r]: ", "[y][r]", "\\", "`", "*", "&", "#", "/"]


@settings(max_examples=200, deadline=None)
@given(st.lists(st.sampled_from(_FRAGMENTS), max_size=25).map("".join))
def test_no_mix_of_vector_fragments_yields_script(text):
    assert _script_vectors(str(render_statement(text))) == []


@pytest.mark.parametrize("message, maths", [
    ("The tension $T$ must be less than the weight $mg$.", 2),
    (r"Check $\dot\theta^2$ and $m\ell\dot\theta^2$.", 2),
    ("$$T = m g$$ is the weight, not the tension", 1),
    ("no math at all", 0),
])
def test_a_message_shows_its_math_as_mathml_and_no_dollar_sign(message, maths):
    html = str(render_text(message))
    assert html.count("<math") == maths
    assert "$" not in re.sub(r"<annotation[^>]*>.*?</annotation>", "", html)


@pytest.mark.parametrize("message, shown", [
    ("m*g*l and lambda_surface are not emphasis", "m*g*l and lambda_surface are not emphasis"),
    ("costs $5 or $6", "costs $5 or $6"),
    ("a <b>bold</b> & <script>x</script>", "a &lt;b&gt;bold&lt;/b&gt; &amp; &lt;script&gt;x&lt;/script&gt;"),
])
def test_a_message_outside_its_math_is_plain_text(message, shown):
    assert str(render_text(message)) == shown
