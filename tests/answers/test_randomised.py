"""Each student's own numbers (grader.answers.randomised): drawn deterministically from a stored seed."""

from decimal import Decimal

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from grader.answers.randomised import (
    PREVIEW_SEED,
    RandomSpecError,
    draw_parameters,
    fixed_values,
    grid_size,
    is_randomised,
    random_names,
    seed_for,
)

SPEC = {
    "m": {"dimension": "kg", "random": {"min": 0.5, "max": 2.0, "step": 0.1}},
    "k": {"dimension": "kg*s^-2", "choices": [10, 20, 50]},
    "g": {"dimension": "m*s^-2", "value": 9.81},
    "l": {"dimension": "m"},  # no number: stays symbolic
}
SEEDS = range(300)


def on_grid(value: float, random: dict) -> bool:
    k = (Decimal(repr(value)) - Decimal(repr(random["min"]))) / Decimal(repr(random["step"]))
    return k == k.to_integral_value()


@pytest.mark.parametrize("seed", [0, 1, 12345, 2 ** 31 - 1])
def test_the_same_seed_gives_the_same_numbers(seed):
    assert draw_parameters(SPEC, seed) == draw_parameters(dict(reversed(SPEC.items())), seed)


def test_the_draw_is_stable_across_releases():
    # A stored seed must keep meaning the same numbers (the preview, regrades of old draws).
    assert draw_parameters(SPEC, 2024) == {"g": 9.81, "k": 10.0, "m": 1.1}


def test_every_number_is_drawn_except_symbolic_parameters():
    assert set(draw_parameters(SPEC, 7)) == {"m", "k", "g"}
    assert draw_parameters(SPEC, 7)["g"] == 9.81


def test_random_values_lie_on_the_step_grid_within_bounds():
    random = SPEC["m"]["random"]
    values = [draw_parameters(SPEC, seed)["m"] for seed in SEEDS]
    assert all(random["min"] <= v <= random["max"] for v in values)
    assert all(on_grid(v, random) for v in values), "a value off the grid (float drift such as 0.8000000000000002)"
    assert set(values) == {round(0.5 + k * 0.1, 1) for k in range(16)}, "some grid values are never drawn"


def test_choices_pick_one_of_the_listed_values_and_all_of_them_over_many_students():
    values = {draw_parameters(SPEC, seed)["k"] for seed in SEEDS}
    assert values == {10.0, 20.0, 50.0}


def test_different_seeds_give_different_numbers():
    draws = {tuple(sorted(draw_parameters(SPEC, seed).items())) for seed in range(40)}
    assert len(draws) >= 20  # 48 combinations; 40 students share few of them


def test_adding_a_parameter_does_not_change_the_others():
    more = {**SPEC, "a": {"random": {"min": 0, "max": 1, "step": 0.5}}}
    for seed in range(20):
        drawn = draw_parameters(more, seed)
        assert {n: drawn[n] for n in ("m", "k", "g")} == draw_parameters(SPEC, seed)


@given(lo=st.integers(-1000, 1000), count=st.integers(1, 500), step_exp=st.integers(-3, 2),
       seed=st.integers(0, 2 ** 31 - 1))
@settings(max_examples=80, deadline=None)
def test_any_grid_is_respected(lo, count, step_exp, seed):
    step = float(Decimal(1).scaleb(step_exp))
    random = {"min": float(Decimal(lo).scaleb(step_exp)), "step": step,
              "max": float(Decimal(lo + count - 1).scaleb(step_exp))}
    assert grid_size(random) == count
    value = draw_parameters({"x": {"random": random}}, seed)["x"]
    assert random["min"] <= value <= random["max"] and on_grid(value, random)


@pytest.mark.parametrize("random, count", [
    ({"min": 0.5, "max": 2.0, "step": 0.1}, 16),
    ({"min": 1, "max": 1, "step": 1}, 1),
    ({"min": 0, "max": 1, "step": 0.3}, 4),  # 0, 0.3, 0.6, 0.9: max need not be on the grid
])
def test_grid_size(random, count):
    assert grid_size(random) == count


@pytest.mark.parametrize("spec, message", [
    ({"x": {"random": {"min": 0, "max": 1, "step": 0}}}, "step must be positive"),
    ({"x": {"random": {"min": 2, "max": 1, "step": 0.1}}}, "max is less than min"),
    ({"x": {"random": {"min": 0, "max": 1e10, "step": 1e-3}}}, "more than"),
    ({"x": {"random": {"min": "0", "max": 1, "step": 0.1}}}, "must be a number"),
    ({"x": {"choices": []}}, "non-empty list"),
    ({"x": 3}, "must be a table"),
])
def test_specs_that_cannot_be_drawn_from_are_refused(spec, message):
    with pytest.raises(RandomSpecError, match=message):
        draw_parameters(spec, 1)


def test_which_parameters_are_randomised():
    assert random_names(SPEC) == ["k", "m"] and is_randomised(SPEC)
    assert not is_randomised({"g": {"value": 9.81}}) and fixed_values(SPEC) == {"g": 9.81}


def test_the_preview_draw_is_the_draw_of_the_preview_seed():
    assert draw_parameters(SPEC, PREVIEW_SEED) == draw_parameters(SPEC, 0)


@pytest.mark.parametrize("ids", [(1, 2, 3), (7, 2, 3), (1, 2, 4)])
def test_seed_for_is_fixed_by_the_ids_and_the_secret(ids):
    seed = seed_for("secret", *ids)
    assert seed == seed_for("secret", *ids) and 0 <= seed < 2 ** 31
    assert seed != seed_for("other secret", *ids)
    assert len({seed_for("secret", *ids), seed_for("secret", ids[0], ids[1] + 1, ids[2])}) == 2


def test_seed_for_separates_ids_that_would_concatenate_alike():
    assert seed_for("", 1, 23) != seed_for("", 12, 3)


def test_a_parameter_below_another_keeps_the_order_in_every_students_draw():
    spec = {"d": {"random": {"min": 0.1, "max": 0.9, "step": 0.1}, "below": "R"},
            "R": {"random": {"min": 0.2, "max": 1.0, "step": 0.1}}}
    draws = [draw_parameters(spec, seed) for seed in SEEDS]
    assert all(v["d"] < v["R"] for v in draws)
    assert draws == [draw_parameters(spec, seed) for seed in SEEDS]  # reproducible from the seed
    assert len({(v["d"], v["R"]) for v in draws}) > 20


def test_a_below_relation_no_draw_can_keep_is_an_error():
    spec = {"d": {"value": 2.0, "below": "R"}, "R": {"value": 1.0}}
    with pytest.raises(RandomSpecError, match="below"):
        draw_parameters(spec, 1)
