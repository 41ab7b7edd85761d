"""Shared variables of the answer-checker tests: the problems' parameters, as requests carry them."""

import pytest

PENDULUM = {
    "m": {"dimension": "mass", "domain": "positive"},
    "g": {"dimension": "acceleration", "domain": "positive"},
    "l": {"dimension": "length", "domain": "positive"},
    "theta": {"dimension": "angle", "domain": [-3.1416, 3.1416]},
    "thetadot": {"dimension": "angular_velocity", "domain": "real"},
    "thetaddot": {"dimension": "angular_acceleration", "domain": "real"},
}
ATWOOD = {
    "m1": {"dimension": "mass", "domain": "positive"},
    "m2": {"dimension": "mass", "domain": "positive"},
    "g": {"dimension": "acceleration", "domain": "positive"},
}
ROLLING = {
    "m": {"dimension": "mass", "domain": "positive"},
    "g": {"dimension": "acceleration", "domain": "positive"},
    "R": {"dimension": "length", "domain": "positive"},
    "alpha": {"dimension": "angle", "domain": [0, 1.5708]},
    "beta": {"dimension": "dimensionless", "domain": [0.01, 1]},
}


@pytest.fixture
def pendulum():
    return PENDULUM


@pytest.fixture
def atwood():
    return ATWOOD


@pytest.fixture
def rolling():
    return ROLLING
