"""``GET /instructor/docs/scene-format``: the scene-file format, served by the app itself.

The page is ``docs/scene-format.md`` of the checkout the app runs from, rendered like a problem
statement (Markdown, no raw HTML, then the ``nh3`` allow-list of :mod:`grader.web.student.statement`)
plus tables and fenced code, which the format's reference needs. Instructors read it while writing
scene files, so it is linked from their navigation and from the scene forms.
"""

from __future__ import annotations

import re
from functools import lru_cache
from pathlib import Path

import markdown
import nh3
from flask import abort, render_template
from markupsafe import Markup

from grader.web.auth.session import INSTRUCTOR_ROLES, login_required
from grader.web.instructor import bp
from grader.web.policy import Action, current_principal, require
from grader.web.student.statement import ALLOWED_ATTRIBUTES, ALLOWED_TAGS, ALLOWED_URL_SCHEMES

SCENE_FORMAT = Path(__file__).resolve().parents[3] / "docs" / "scene-format.md"
_TAGS = ALLOWED_TAGS | {"table", "thead", "tbody", "tr", "th", "td", "div"}
_ATTRIBUTES = {**ALLOWED_ATTRIBUTES, **{f"h{n}": {"id"} for n in range(1, 7)}, "th": {"align"}, "td": {"align"}}


def render_document(text: str) -> Markup:
    """Markdown ``text`` (raw HTML shown as text) with tables and fenced code, as sanitised HTML.

    >>> html = str(render_document("| a |\\n|---|\\n| <b>1</b> |"))
    >>> html.startswith('<div class="table-wrap" tabindex="0" role="region" aria-label="Table 1"><table>')
    True
    >>> "<td>&lt;b&gt;1&lt;/b&gt;</td>" in html, html.endswith("</table></div>")
    (True, True)
    """
    md = markdown.Markdown(extensions=["sane_lists", "tables", "fenced_code", "toc"], output_format="html")
    md.preprocessors.deregister("html_block")
    md.inlinePatterns.deregister("html")
    html = nh3.clean(md.convert(text), tags=set(_TAGS), attributes={k: set(v) for k, v in _ATTRIBUTES.items()},
                     url_schemes=set(ALLOWED_URL_SCHEMES), strip_comments=True, link_rel="noopener noreferrer")
    # Wide tables scroll on their own, and a scrolling region must be reachable by keyboard.
    count = iter(range(1, html.count("<table>") + 1))
    html = re.sub("<table>", lambda _: f'<div class="table-wrap" tabindex="0" role="region" aria-label="Table '
                                       f'{next(count)}"><table>', html).replace("</table>", "</table></div>")
    return Markup(html)


@lru_cache(maxsize=4)
def _rendered(path: Path, mtime_ns: int) -> Markup:
    return render_document(path.read_text(encoding="utf-8"))


@bp.get("/docs/scene-format")
@login_required(INSTRUCTOR_ROLES)
def scene_format():
    require(current_principal(), Action.CREATE, None)  # the format is for those who write scene files
    try:
        body = _rendered(SCENE_FORMAT, SCENE_FORMAT.stat().st_mtime_ns)
    except OSError:
        abort(404, "The scene-format documentation is not installed with this copy of lagrade "
                   "(it is docs/scene-format.md in the source).")
    return render_template("instructor/docs.html", body=body, title="Scene files")
