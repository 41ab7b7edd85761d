"""``grader bench check``: the naive baseline reads every corpus item it is given."""

import pytest

from grader.bench.check import _baseline_verdict


@pytest.mark.parametrize("domain", [["-pi", "pi"], ["0", "pi/2"], [0.5, 3], "positive", "real", "nonnegative"])
def test_the_baseline_reads_every_form_of_domain(domain):
    # an end written "-pi" stopped the whole benchmark (float("-pi")); the baseline's own parse_expr runs on the
    # test's text here, never on a student's
    item = {"reference": "cos(theta)", "answer": "cos(theta)", "variables": {"theta": {"domain": domain}},
            "kind": "expression"}
    assert _baseline_verdict(item) == "equivalent"
