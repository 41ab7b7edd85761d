"""A pendulum-on-a-surface namespace shared by the expression tests."""

import pytest

from grader.expressions import Namespace, Variable


@pytest.fixture
def ns():
    return Namespace([
        Variable("m", "mass", "positive"),
        Variable("m1", "mass", "positive"),
        Variable("g", "acceleration", "positive"),
        Variable("l", "length", "positive"),
        Variable("r", "length", "positive"),
        Variable("x", "length", "real", "coordinate"),
        Variable("y", "length", "real", "coordinate"),
        Variable("t", "time", "nonnegative", "time"),
        Variable("theta", "angle", "real", "coordinate"),
        Variable("thetadot", "angular_velocity", "real", "velocity"),
        Variable("thetaddot", "angular_acceleration", "real", "acceleration"),
        Variable("rdot", "velocity", "real", "velocity"),
        Variable("phi", "angle", [0, "pi/2"], "coordinate"),
        Variable("lambda_surface", "force", "real", "multiplier"),
        Variable("Q_roll_s", "force", "real", "force"),
    ])
