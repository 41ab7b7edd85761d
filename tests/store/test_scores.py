"""The one score: per attempt (verdict x late factor), per answer (best or latest), per problem
(weighted mean of its answers), per assignment (the sum), and the gradebook built from them."""

from __future__ import annotations

from datetime import datetime, timedelta

import pytest

from grader.store.models import Assignment, ProblemVersion, Submission, Verdict
from grader.store.scores import answer_weight, problem_score

DUE = datetime(2026, 12, 8, 17, 0)
REFERENCES = [{"name": "a"}, {"name": "b"}]


def _version(references=REFERENCES) -> ProblemVersion:
    return ProblemVersion(references=references, problem=None)


def _attempt(number: int, answer: str, score: float | None, *, late: timedelta = timedelta(0)) -> Submission:
    """Attempt ``number`` at ``answer``; graded with ``score`` (None: still queued)."""
    submission = Submission(id=number, answer_name=answer, received_at=DUE - timedelta(hours=1) + late,
                            status="queued" if score is None else "done", grading_round=1)
    if score is not None:
        submission.verdicts = [Verdict(grading_round=1, score=score, verdict="x")]
    return submission


def _assignment(policy: str, penalty: float = 0.25) -> Assignment:
    return Assignment(opens_at=DUE - timedelta(days=7), due_at=DUE, closes_at=DUE + timedelta(days=5),
                      late_penalty_per_day=penalty, score_policy=policy)


@pytest.mark.parametrize("policy, scores, expected", [
    ("best", [1.0, 0.0], 1.0),  # right, then wrong: the best stays
    ("latest", [1.0, 0.0], 0.0),  # the latest graded one counts
    ("best", [0.0, 0.5], 0.5),  # partial credit from feedback
    ("latest", [0.0, 1.0, None], 1.0),  # a pending attempt does not count yet
])
def test_an_answer_scores_by_the_policy(policy, scores, expected):
    attempts = [_attempt(i, "a", s) for i, s in enumerate(scores, start=1)]
    result = problem_score(_version([{"name": "a"}]), attempts, _assignment(policy))
    assert result.score == expected
    assert result.answers["a"].attempts == len(scores)
    assert result.answers["a"].pending == sum(s is None for s in scores)


@pytest.mark.parametrize("policy, expected", [("best", 0.75), ("latest", 0.5)])
def test_late_attempts_keep_what_the_penalty_leaves(policy, expected):
    attempts = [_attempt(1, "a", 1.0, late=timedelta(hours=2)),  # 1 day late: 0.75
                _attempt(2, "a", 1.0, late=timedelta(hours=26))]  # 2 days late: 0.5
    result = problem_score(_version([{"name": "a"}]), attempts, _assignment(policy))
    assert result.score == expected
    assert result.late_days == (1 if policy == "best" else 2)


def test_an_on_time_wrong_answer_loses_to_a_late_right_one_under_best():
    attempts = [_attempt(1, "a", 0.0), _attempt(2, "a", 1.0, late=timedelta(hours=2))]
    assert problem_score(_version([{"name": "a"}]), attempts, _assignment("best")).score == 0.75


@pytest.mark.parametrize("references, expected", [
    (REFERENCES, 0.5),  # equal weights: (1 + 0) / 2
    ([{"name": "a", "weight": 3}, {"name": "b"}], 0.75),  # (3*1 + 1*0) / 4
    ([{"name": "a", "weight": 0}, {"name": "b"}], 0.0),  # a weightless answer counts nothing
])
def test_a_problem_scores_the_weighted_mean_of_its_answers(references, expected):
    attempts = [_attempt(1, "a", 1.0), _attempt(2, "b", 0.0)]
    assert problem_score(_version(references), attempts, _assignment("best")).score == expected


def test_an_untried_answer_scores_zero_and_outside_assignments_nothing_is_late():
    attempts = [_attempt(1, "a", 1.0, late=timedelta(days=3))]
    result = problem_score(_version(), attempts)  # practice: best, never late
    assert result.score == 0.5 and result.late_days == 0


@pytest.mark.parametrize("weight, expected", [(2, 2.0), (0.5, 0.5), (-1, 1.0), ("x", 1.0), (None, 1.0)])
def test_a_weight_that_is_not_a_nonnegative_number_counts_as_one(weight, expected):
    assert answer_weight({"name": "a", "weight": weight}) == expected


def test_scores_are_rounded_once_so_every_view_shows_the_same_number():
    attempts = [_attempt(1, "a", 1.0), _attempt(2, "b", 1.0), _attempt(3, "c", 0.0)]
    references = [{"name": "a"}, {"name": "b"}, {"name": "c"}]
    assert problem_score(_version(references), attempts).score == 0.6667
