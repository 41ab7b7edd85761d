"""``/login?next=``: only a path on this site, parsed and normalised; no value answers 500."""

from urllib.parse import urlsplit

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from grader.web.auth.redirects import MAX_NEXT_LENGTH, safe_next
from tests.web.conftest_pages import PASSWORD, accounts, form_token  # noqa: F401

# Values as the view receives them (the query string already percent-decoded once).
OFF_SITE = [
    "/\t/evil.example/",  # /%09/evil.example/: browsers drop the tab and read //evil.example
    "/\n/evil.example/",  # %0A: a header injection, and a 500 before
    "/\r\nSet-Cookie: x=1",
    "/\x00/evil.example",
    "\t//evil.example",
    "//evil.example",
    "//evil.example/x",
    "///evil.example",
    "\\\\evil.example",
    "/\\evil.example",
    "\\/evil.example",
    "/\\/evil.example",
    "https://evil.example/",
    "HTTPS://evil.example",
    "http:/evil.example",
    "http:evil.example",
    "javascript:alert(1)",
    "JavaScript:alert(1)",
    "data:text/html,<script>alert(1)</script>",
    " //evil.example",
    "evil.example",
    "problems",
    "",
    "/" + "a" * MAX_NEXT_LENGTH,
    "//[::1",  # urlsplit raises on an unbalanced IPv6 host
    "/[::1]//x\x7f",
]
SAME_SITE = [
    ("/problems", "/problems"),
    ("/problems/sphere?tab=answers&x=1", "/problems/sphere?tab=answers&x=1"),
    ("/instructor/", "/instructor/"),
    ("/", "/"),
    ("/%2F%2Fevil.example", "/%2F%2Fevil.example"),  # encoded twice: a path segment, not a host
    ("/%09/evil.example", "/%09/evil.example"),
    ("/problems//sphere", "/problems/sphere"),
    ("/problems/./sphere", "/problems/sphere"),
    ("/../../etc/passwd", "/etc/passwd"),
    ("/a/b/..", "/a/"),
    ("/.//evil.example", "/evil.example"),  # dot segments cannot turn a path into a host
    ("/problèmes/a b", "/probl%C3%A8mes/a%20b"),
    ("/\u3002evil.example", "/%E3%80%82evil.example"),
    ("/\uff0f\uff0fevil.example", "/%EF%BC%8F%EF%BC%8Fevil.example"),  # fullwidth solidus: just text
    ("/x?next=https://evil.example", "/x?next=https://evil.example"),
    ("/x#frag", "/x"),
]


@pytest.mark.parametrize("target", OFF_SITE)
def test_anything_but_a_path_on_this_site_is_refused(target):
    assert safe_next(target) == ""


@pytest.mark.parametrize(("target", "expected"), SAME_SITE)
def test_a_path_on_this_site_is_kept_normalised(target, expected):
    assert safe_next(target) == expected


@pytest.mark.parametrize("target", [t for t, _ in SAME_SITE] + OFF_SITE)
def test_the_answer_has_neither_host_nor_scheme_nor_control_characters(target):
    result = safe_next(target)
    parts = urlsplit(result)
    assert not parts.scheme and not parts.netloc and not result.startswith("//")
    assert all(0x20 < ord(c) < 0x7f and c != "\\" for c in result)
    assert safe_next(result) == result  # normalised: a second pass changes nothing


def test_non_text_is_refused():
    assert safe_next(None) == "" and safe_next(b"/problems") == ""  # type: ignore[arg-type]


# Raw query strings (as a link would carry them) and where signing in must then lead.
RAW_QUERIES = [
    ("/%09/evil.example/", "/problems"), ("/%0A/evil.example/", "/problems"),
    ("/%0D%0ASet-Cookie:%20x=1", "/problems"), ("%2F%2Fevil.example", "/problems"),
    ("/%5Cevil.example", "/problems"), ("%5C%5Cevil.example", "/problems"),
    ("https:%2F%2Fevil.example", "/problems"), ("javascript:alert(1)", "/problems"),
    ("//%5B::1", "/problems"), ("/" + "a" * 5000, "/problems"),
    ("/%E2%80%AE", "/%E2%80%AE"), ("/%FF%FE", "/%FF%FE"),  # odd but local: kept
]


@pytest.mark.parametrize(("raw", "expected"), RAW_QUERIES)
def test_signing_in_with_a_hostile_next_stays_on_the_site(client, accounts, raw, expected):
    token = form_token(client.get("/login?next=" + raw).get_data(as_text=True))
    response = client.post("/login?next=" + raw, data={"username": "ada@example.org", "password": PASSWORD,
                                                       "csrf_token": token})
    assert response.status_code == 302 and response.headers["Location"] == expected
    # Signed in now, the sign-in page sends the visitor straight on, to the same place.
    again = client.get("/login?next=" + raw)
    assert again.status_code == 302 and again.headers["Location"] == expected


def test_a_nul_in_next_is_refused_like_any_nul_in_a_query_and_goes_nowhere(client, accounts):
    # grader/web/text_input.py: a NUL in any query string or form field is a 400, never a redirect.
    for response in (client.get("/login?next=/%00"),
                     client.post("/login?next=/%00", data={"username": "ada@example.org", "password": PASSWORD})):
        assert response.status_code == 400 and "Location" not in response.headers


def test_a_safe_next_still_comes_back_after_signing_in(client, accounts):
    token = form_token(client.get("/login?next=/problems/yoyo%3Ftab=1").get_data(as_text=True))
    response = client.post("/login?next=/problems/yoyo%3Ftab=1",
                           data={"username": "ada@example.org", "password": PASSWORD, "csrf_token": token})
    assert response.headers["Location"] == "/problems/yoyo?tab=1"


@settings(max_examples=300, deadline=None)
@given(st.lists(st.sampled_from(list("/\\:.%@?#&=aZ09 \t\n\r\x00\x7fé。／[]") + ["//", "http:", "javascript:"]),
                max_size=20).map("".join) | st.text(max_size=60))
def test_any_text_gives_a_same_site_path_or_nothing(target):
    result = safe_next(target)
    parts = urlsplit(result)
    assert result == "" or (result.startswith("/") and not result.startswith("//"))
    assert not parts.scheme and not parts.netloc
    assert all(0x20 < ord(c) < 0x7f and c != "\\" for c in result)
