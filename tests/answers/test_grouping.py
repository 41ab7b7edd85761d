"""Wrong answers grouped by equivalence: one row per mistake, however it was written."""

import random
import time

from grader.answers.checker import check_request
from grader.answers.grouping import GroupingCache, fingerprint, group_wrong_answers
from grader.expressions import Namespace, parse_expression

TENSION = {"name": "tension", "kind": "expression", "reference": "g*m/3",
           "variables": {"g": {"dimension": "m*s^-2", "domain": "positive"},
                         "m": {"dimension": "kg", "domain": "positive"},
                         "theta": {"dimension": "angle", "domain": "real"}}}


def checker(calls):
    def equivalent(a, b):
        calls.append((a, b))
        return check_request({"reference": a, "answer": b, "variables": TENSION["variables"]})["verdict"] == "equivalent"
    return equivalent


def test_the_weight_written_three_ways_is_one_group():
    calls = []
    groups = group_wrong_answers(TENSION, [(1, "mg"), (2, "g*m"), (3, "m*g*(sin(theta)^2 + cos(theta)^2)"),
                                           (3, "m g/2")], checker(calls))
    assert [(g.representative, g.submissions, len(g.students)) for g in groups] == [("g*m", 3, 3), ("g*m/2", 1, 1)]
    assert groups[0].forms["mg"] == 1
    assert len(calls) == 1  # only the trigonometric form needed the checker; m*g/2 differs numerically


def test_fingerprints_agree_for_equivalent_forms_and_not_otherwise():
    ns = Namespace.from_spec(TENSION["variables"])
    value = lambda text: fingerprint(parse_expression(text, ns).expr, ns)
    assert value("2*m*g") == value("m*g + g*m")
    assert value("m*g") != value("m*g/2")
    assert value("exp(10000*m)") is None  # overflow: no fingerprint, the checker decides


def test_a_course_of_300_groups_in_well_under_a_second():
    rng = random.Random(7)
    pool = ["mg", "m*g", "g m", "2mg", "m g *2", "g/3", "m*g/2", "mg/2", "m*g/3 + m*g/6", "m+g", "m*g*cos(theta)"]
    answers = [(i, rng.choice(pool)) for i in range(300)] + [(i, f"{i}*m*g") for i in range(2, 300)]
    calls = []
    started = time.perf_counter()
    groups = group_wrong_answers(TENSION, answers, checker(calls))
    assert time.perf_counter() - started < 1.0  # about 0.15 s on one core
    assert len(calls) < 20
    assert groups[0].submissions >= groups[1].submissions
    assert sum(g.submissions for g in groups) == len(answers)


def test_the_cache_recomputes_only_when_the_signature_changes():
    cache, runs = GroupingCache(), []
    compute = lambda: runs.append(1) or ["groups"]
    assert cache.groups(("p", "a"), (1,), compute) == ["groups"]
    cache.groups(("p", "a"), (1,), compute)
    cache.groups(("p", "a"), (2,), compute)
    assert len(runs) == 2
    asked = []
    ask = lambda a, b: asked.append((a, b)) or True
    assert cache.equivalent(TENSION, "a", "b", ask) and cache.equivalent(TENSION, "b", "a", ask)
    assert len(asked) == 1
