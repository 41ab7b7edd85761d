"""Build the labelled answer corpus (``*.jsonl`` beside this file): ``python tests/answers/corpus/build.py``.

Each line is a ``grader check --jsonl`` request plus the truth:
``{"id", "problem", "question", "reference", "answer", "variables", "kind", "expected", "tags"}``
with ``expected`` one of ``equivalent``, ``not_equivalent``, ``invalid`` and tags such as
``typical``, ``float64_hostile``, ``near_miss``, ``domain``, ``dimension``, ``slip``, ``hostile``.
A ``feedback`` list (instructor messages) and ``expect_feedback`` (a feedback code that must
appear) are given where the item tests them.

The references are the problems' answers in ``problems/`` (pendulum tension
``m l thetadot^2 + m g cos(theta)``, half-Atwood ``m1 m2 g/(m1+m2)``, yo-yo ``m g/3``, sphere
``m g (3 cos(theta) - 2)``, rolling with ``I = beta m R^2``) and their equations of motion. Every
label was decided by hand from the mathematics, never by running the checker.
"""

from __future__ import annotations

import json
from pathlib import Path

HERE = Path(__file__).parent

POS = "positive"
PI_DOMAIN = [-3.1416, 3.1416]


def var(dimension, domain="real", kind=None):
    spec = {"dimension": dimension, "domain": domain}
    if kind:
        spec["kind"] = kind
    return spec


PENDULUM = {
    "m": var("mass", POS), "g": var("acceleration", POS), "l": var("length", POS),
    "theta": var("angle", PI_DOMAIN), "thetadot": var("angular_velocity"),
}
PENDULUM_EOM = {
    "g": var("acceleration", POS), "l": var("length", POS), "m": var("mass", POS),
    "theta": var("angle", PI_DOMAIN, "coordinate"), "thetadot": var("angular_velocity", "real", "velocity"),
    "thetaddot": var("angular_acceleration", "real", "acceleration"),
}
ATWOOD = {"m1": var("mass", POS), "m2": var("mass", POS), "g": var("acceleration", POS)}
# A very light block on the table and a very heavy hanging one: float64 cancels in g - a.
ATWOOD_EXTREME = {"m1": var("mass", [1e-7, 1e-5]), "m2": var("mass", [1e5, 1e7]), "g": var("acceleration", POS)}
ATWOOD_SYSTEM = {
    "m1": var("mass", POS), "m2": var("mass", POS), "g": var("acceleration", POS),
    "xddot": var("acceleration", "real", "acceleration"), "yddot": var("acceleration", "real", "acceleration"),
    "T": var("force", "real", "force"),
}
YOYO = {"m": var("mass", POS), "g": var("acceleration", POS), "R": var("length", POS)}
YOYO_EOM = {"m": var("mass", POS), "g": var("acceleration", POS), "R": var("length", POS),
            "sddot": var("acceleration", "real", "acceleration")}
SPHERE = {"m": var("mass", POS), "g": var("acceleration", POS), "R": var("length", POS),
          "theta": var("angle", PI_DOMAIN)}
# Near the top of the sphere: tiny angles, where 1 - cos(theta) cancels in float64.
SPHERE_SMALL = {"R": var("length", POS), "theta": var("angle", [1e-9, 1e-7])}
ROLLING = {"m": var("mass", POS), "g": var("acceleration", POS), "R": var("length", POS),
           "alpha": var("angle", [0, 1.5708]), "beta": var("dimensionless", [0.01, 1])}
ROLLING_EOM = {**ROLLING, "sddot": var("acceleration", "real", "acceleration")}

EQ, NE, INV = "equivalent", "not_equivalent", "invalid"

items: list[dict] = []


def add(problem, question, reference, variables, entries, kind="expression", feedback=None, state=None):
    for entry in entries:
        answer, expected, *rest = entry
        tags = rest[0] if rest else []
        item = {
            "problem": problem, "question": question, "reference": reference, "answer": answer,
            "variables": variables, "kind": kind, "expected": expected,
            "tags": tags if isinstance(tags, list) else [tags],
        }
        if len(rest) > 1:
            item["expect_feedback"] = rest[1]
        if feedback:
            item["feedback"] = feedback
        if state:
            item["state"] = state
        items.append(item)


# -- pendulum: tension ------------------------------------------------------------------------
PENDULUM_FEEDBACK = [
    {"expr": "m*g*cos(theta)", "message": "That is the tension of a bob at rest."},
    {"expr": "m*l*thetadot^2/2 + m*g*cos(theta)/2", "message": "This is the multiplier, not the tension."},
]
add("pendulum", "tension", "m*l*thetadot^2 + m*g*cos(theta)", PENDULUM, [
    ("m*l*thetadot^2 + m*g*cos(theta)", EQ, "typical"),
    ("m l thetadot^2 + m g cos theta", EQ, "typical"),
    ("m(l thetadot^2 + g cos(theta))", EQ, "typical"),
    ("m*(g*cos(theta) + l*thetadot**2)", EQ, "typical"),
    ("mgcos(theta) + ml thetadot^2", EQ, "typical"),
    ("m·l·θ̇² + m·g·cos θ", EQ, "typical"),
    ("m l \\dot\\theta^2 + m g \\cos\\theta", EQ, "typical"),
    ("m*l*theta_dot^2 + m*g*cos(theta)", EQ, "typical"),
    ("m*l*dot(theta)^2 + m*g*cos(theta)", EQ, "typical"),
    ("m*g*cos(theta) + m*l*thetadot*thetadot", EQ, "typical"),
    ("m*(l*thetadot^2 + g*(1 - 2*sin(theta/2)^2))", EQ, "typical"),
    ("m*l*thetadot^2 + m*g*(cos(theta/2)^2 - sin(theta/2)^2)", EQ, "typical"),
    ("m*l*thetadot^2 + m*g*sin(theta + pi/2)", EQ, "typical"),
    ("m*l*thetadot^2 + m*g*cos(-theta)", EQ, "typical"),
    ("m*l*thetadot^2 + m*g*(2*cos(theta/2)^2 - 1)", EQ, "typical"),
    ("m*l*thetadot^2 + m*g/sec(theta)", EQ, "typical"),
    ("m*l*thetadot^2 + m*g*cos(theta)*(sin(theta)^2 + cos(theta)^2)", EQ, "typical"),
    ("(m*l^2*thetadot^2 + m*g*l*cos(theta))/l", EQ, "typical"),
    ("m*l*thetadot^2 + m*g + m*g*(cos(theta) - 1)", EQ, ["typical", "float64_hostile"]),
    ("m*l*thetadot^2 + m*g - 2*m*g*sin(theta/2)^2", EQ, "typical"),
    ("2*l*(m*thetadot^2/2 + m*g*cos(theta)/(2*l))", EQ, "typical"),
    ("m*l*thetadot^2 + m*g*cos(theta) + 0*m*g", EQ, "typical"),
    ("0.5*m*l*thetadot^2*2 + m*g*cos(theta)", EQ, "typical"),
    ("m*l*thetadot^2 + m*g*sqrt(1 - sin(theta)^2)", NE, ["domain"]),
    ("m*l*thetadot^2 - m*g*cos(theta)", NE, ["typical", "slip"], "term_sign"),
    ("-m*l*thetadot^2 - m*g*cos(theta)", NE, ["typical", "slip"], "sign"),
    ("m*g*cos(theta)", NE, ["typical", "slip"], "instructor"),
    ("m*l*thetadot^2/2 + m*g*cos(theta)/2", NE, ["typical", "slip"], "instructor"),
    ("m*l*thetadot^2", NE, ["typical", "slip"], "missing_term"),
    ("m*l*thetadot^2 + m*g*sin(theta)", NE, ["typical", "slip"], "sin_cos"),
    ("2*m*l*thetadot^2 + 2*m*g*cos(theta)", NE, ["typical", "slip"], "factor"),
    ("m*l*thetadot^2 + m*g*cos(theta) + m*g", NE, ["typical", "slip"], "extra_term"),
    ("m*l*thetadot^2 + m*g", NE, ["typical"]),
    ("m*l^2*thetadot^2 + m*g*cos(theta)", NE, ["dimension"], "dimension"),
    ("m*l*thetadot + m*g*cos(theta)", NE, ["dimension"], "dimension"),
    ("m*thetadot^2 + m*g*cos(theta)", NE, ["dimension"], "dimension"),
    ("m*l*thetadot^2 + g*cos(theta)", NE, ["dimension"], "dimension"),
    ("l*thetadot^2 + g*cos(theta)", NE, ["dimension"], "dimension"),
    ("m*l*thetadot^2 + m*g*cos(m)", NE, ["dimension"], "dimension"),
    ("m*l*thetadot^2 + m*g*cos(theta)*(1 + 10^-9)", NE, ["near_miss"]),
    ("m*l*thetadot^2 + m*g*cos(theta) + m*g/10^9", NE, ["near_miss"]),
    ("m*l*thetadot^2*1.000000001 + m*g*cos(theta)", NE, ["near_miss"]),
    ("m*l*thetadot^2 + 0.999999999*m*g*cos(theta)", NE, ["near_miss"]),
    ("m*l*thetadot^2 + m*g*cos(theta + 10^-9)", NE, ["near_miss"]),
    ("m*l*thetadot^2 + m*g*cos(theta)", EQ, ["typical"]),
    ("m*l*thetadot^2 + m*g*cos(theta", INV, ["syntax"]),
    ("m*l*thetadot^2 + M*g*cos(theta)", INV, ["syntax"]),
    ("m*l*omega^2 + m*g*cos(theta)", INV, ["syntax"]),
    ("m*l*thetadot^2 + m*g*cos(theta) = T", INV, ["syntax"]),
    ("", INV, ["syntax"]),
    ("m*l*thetadot^2 +* m*g*cos(theta)", INV, ["syntax"]),
], feedback=PENDULUM_FEEDBACK)

# lowest point, released from rest at theta0: T = m g (3 - 2 cos theta0)
add("pendulum", "tension_lowest", "m*g*(3 - 2*cos(theta0))",
    {"m": var("mass", POS), "g": var("acceleration", POS), "theta0": var("angle", [0.01, 3.1])}, [
    ("3mg - 2mg cos(theta0)", EQ, "typical"),
    ("m*g + 2*m*g*(1 - cos(theta0))", EQ, "typical"),
    ("m*g*(1 + 4*sin(theta0/2)^2)", EQ, "typical"),
    ("m*g*(3 - 2*sqrt(1 - sin(theta0)^2))", NE, "domain"),  # theta0 may exceed pi/2
    ("m*g*(3 - 2*cos(theta0))*(1 + 10^-9)", NE, "near_miss"),
    ("m*g*(3 - 2*sin(theta0))", NE, ["typical", "slip"], "sin_cos"),
    ("m*g*(3 + 2*cos(theta0))", NE, ["typical", "slip"], "term_sign"),
    ("m*g*(1 - 2*cos(theta0))", NE, ["typical"]),
    ("3*m*g", NE, ["typical", "slip"], "missing_term"),
    ("m*g*(3 - 2*cos(theta0)) + theta0", NE, ["dimension"], "dimension"),
])

# -- half-Atwood ------------------------------------------------------------------------------
ATWOOD_FEEDBACK = [{"expr": "m2*g", "message": "That would be the tension if m2 hung at rest."}]
T_ATWOOD = "m1*m2*g/(m1 + m2)"
tension_forms = [
    "m1 m2 g/(m1 + m2)", "m1*m2*g/(m2 + m1)", "g/(1/m1 + 1/m2)", "m1*g/(1 + m1/m2)",
    "m2*g/(1 + m2/m1)", "m2*(g - m2*g/(m1 + m2))", "m1*(m2*g/(m1 + m2))", "m2*g - m2^2*g/(m1 + m2)",
    "m2*g*(1 - m2/(m1 + m2))", "m1*g - m1^2*g/(m1 + m2)", "(m1*m2*g)/(m1+m2)", "\\frac{m_1 m_2 g}{m_1 + m_2}",
    "m₁m₂g/(m₁+m₂)", "g*m1*m2*(m1+m2)^-1", "m1*m2*g*(m1 - m2)/(m1^2 - m2^2)", "m1 m2 g / (m1 + m2)",
    "2*m1*m2*g/(2*m1 + 2*m2)", "(m1+m2)^2*m1*m2*g/(m1+m2)^3",
]
add("half_atwood", "tension", T_ATWOOD, ATWOOD,
    [(t, EQ, "typical") for t in tension_forms]
    + [(t, EQ, ["float64_hostile"]) for t in ("m2*(g - m2*g/(m1 + m2))", "m2*g - m2^2*g/(m1 + m2)",
                                               "m1*g - m1^2*g/(m1 + m2)")]
    + [
        ("m2*g", NE, ["typical", "slip"], "instructor"),
        ("m1*g", NE, "typical"),
        ("m1*m2*g/(m1 - m2)", NE, "typical"),
        ("m2*g/(m1 + m2)", NE, ["dimension"], "dimension"),
        ("m1*m2*g/(m1 + m2)^2", NE, ["dimension"], "dimension"),
        ("m1*m2*g/(m1 + m2 + g)", NE, ["dimension"], "dimension"),
        ("2*m1*m2*g/(m1 + m2)", NE, ["typical", "slip"], "factor"),
        ("m1*m2*g/(2*(m1 + m2))", NE, ["typical", "slip"], "factor"),
        ("-m1*m2*g/(m1 + m2)", NE, ["typical", "slip"], "sign"),
        ("m2*(g + m2*g/(m1 + m2))", NE, "typical"),
        ("m1*m2*g/(m1 + m2)*(1 + 10^-9)", NE, "near_miss"),
        ("m1*m2*g/(m1 + m2 + m1/10^9)", NE, "near_miss"),
        ("m1*m2*g/(m1 + m2) + m1*g/10^9", NE, "near_miss"),
        ("m1*m2*9.81/(m1 + m2)", NE, ["dimension"], "dimension"),
        ("m1*m2*g/(m1 + m2", INV, "syntax"),
        ("m1*m2*g/(m1 + m3)", INV, "syntax"),
        ("m1*m2*g/(m1 + m2) = T", INV, "syntax"),
    ], feedback=ATWOOD_FEEDBACK)
add("half_atwood", "tension_extreme_masses", T_ATWOOD, ATWOOD_EXTREME, [
    ("m2*(g - m2*g/(m1 + m2))", EQ, ["float64_hostile"]),
    ("m2*g - m2^2*g/(m1 + m2)", EQ, ["float64_hostile"]),
    ("m2*g*(1 - m2/(m1 + m2))", EQ, ["float64_hostile"]),
    ("m1*m2*g/(m1 + m2)", EQ, "typical"),
    ("m1*g", NE, ["near_miss"]),  # off by the relative term m1/(m1+m2) ~ 1e-12
    ("m1*g*(1 - m1/m2)", NE, ["near_miss"]),  # the first-order expansion, off by ~1e-24
    ("m2*g - m2^2*g/(m1 + m2) + m1*g/10^9", NE, ["near_miss"]),
])

A_ATWOOD = "m2*g/(m1 + m2)"
add("half_atwood", "acceleration", A_ATWOOD, ATWOOD, [
    ("m2 g/(m1+m2)", EQ, "typical"),
    ("g/(1 + m1/m2)", EQ, "typical"),
    ("g - m1*g/(m1 + m2)", EQ, ["typical", "float64_hostile"]),
    ("g*(1 - m1/(m1 + m2))", EQ, ["typical", "float64_hostile"]),
    ("m2*g*(m1 + m2)^(-1)", EQ, "typical"),
    ("g*m2/(m2 + m1)", EQ, "typical"),
    ("(m2*g)/(m1+m2)", EQ, "typical"),
    ("g", NE, ["typical", "slip"], "instructor"),
    ("m2*g/m1", NE, ["typical", "slip"], "instructor"),
    ("m1*g/(m1 + m2)", NE, "typical"),
    ("m2*g/(m1 - m2)", NE, "typical"),
    ("(m2 - m1)*g/(m1 + m2)", NE, "typical"),
    ("m2*g/(m1 + m2)*(1 + 10^-9)", NE, "near_miss"),
    ("m2*g/(m1 + m2)^2", NE, ["dimension"], "dimension"),
    ("m2*g", NE, ["dimension"], "dimension"),
    ("-m2*g/(m1 + m2)", NE, ["typical", "slip"], "sign"),
    ("m2*g/(2*(m1 + m2))", NE, ["typical", "slip"], "factor"),
], feedback=[{"expr": "g", "message": "m2 does not fall freely."},
             {"expr": "m2*g/m1", "message": "The total mass belongs in the denominator."}])
add("half_atwood", "acceleration_m1", A_ATWOOD, ATWOOD, [
    ("m2*g/(m1 + m2)", EQ, "typical"),
    ("g - g*m1/(m2 + m1)", EQ, ["typical", "float64_hostile"]),
    ("m1*g/(m1 + m2)", NE, "typical"),
])
add("half_atwood", "normal_force", "m1*g", ATWOOD, [
    ("m1 g", EQ, "typical"), ("g*m1", EQ, "typical"), ("m1*g*(m1 + m2)/(m1 + m2)", EQ, "typical"),
    ("m2*g", NE, "typical"), ("(m1 + m2)*g", NE, "typical"), ("m1*g - m1*m2*g/(m1 + m2)", NE, "typical"),
    ("m1", NE, ["dimension"], "dimension"),
])

# -- yo-yo ------------------------------------------------------------------------------------
add("yoyo", "tension", "m*g/3", YOYO, [
    ("mg/3", EQ, "typical"), ("m g / 3", EQ, "typical"), ("(1/3) m g", EQ, "typical"), ("m*g*3^-1", EQ, "typical"),
    ("m*g - 2*m*g/3", EQ, "typical"), ("m*(g - 2*g/3)", EQ, "typical"), ("\\frac{mg}{3}", EQ, "typical"),
    ("\\frac{1}{3}mg", EQ, "typical"), ("m*g/(1 + 2)", EQ, "typical"), ("m*g*(1/2)/(3/2)", EQ, "typical"),
    ("0.5*m*g/1.5", EQ, "typical"), ("m*(g - 2/3*g)", EQ, "typical"),
    ("m g (1 - 2/3)", EQ, "typical"), ("g*m/3", EQ, "typical"), ("m*g/3*(R/R)", EQ, "typical"),
    ("m*g*(sin(R/R)^2 + cos(1)^2)/3", EQ, "typical"),
    ("m*g", NE, ["typical", "slip"], "instructor"),
    ("2*m*g/3", NE, ["typical", "slip"], "factor"),
    ("m*g/2", NE, "typical"), ("m*g/6", NE, ["typical", "slip"], "factor"),
    ("-m*g/3", NE, ["typical", "slip"], "sign"),
    ("m*g/3 + m*g/10^9", NE, ["near_miss"]), ("0.333333333*m*g", NE, ["near_miss"], "close"),
    ("0.3333333333333333*m*g", NE, ["near_miss"], "close"),
    ("m*g*0.33", NE, "near_miss"),
    ("m*g*R/3", NE, ["dimension"], "dimension"), ("g/3", NE, ["dimension"], "dimension"),
    ("m/3", NE, ["dimension"], "dimension"), ("m*g/3 + R", NE, ["dimension"], "dimension"),
    ("m*g/3 + m", NE, ["dimension"], "dimension"), ("m*g^2/3", NE, ["dimension"], "dimension"),
    ("m*g/3 +", INV, "syntax"), ("m*g/0", INV, "syntax"), ("mg/3 m", NE, ["dimension"], "dimension"),
    ("m*g/3 + x", INV, "syntax"), ("T", INV, "syntax"),
], feedback=[{"expr": "m*g", "message": "The yo-yo accelerates, so the tension is less than its weight."}])
add("yoyo", "acceleration", "2*g/3", YOYO, [
    ("2g/3", EQ, "typical"), ("g - g/3", EQ, "typical"), ("g/(1 + 1/2)", EQ, "typical"),
    ("(2/3)*g", EQ, "typical"), ("g/1.5", EQ, "typical"), ("g*m/(m + m/2)", EQ, "typical"),
    ("g", NE, "typical"), ("g/3", NE, ["typical", "slip"], "factor"), ("g/2", NE, "typical"),
    ("-2*g/3", NE, ["typical", "slip"], "sign"), ("0.667*g", NE, ["near_miss"], "close"),
    ("2*g/3*(1 - 10^-9)", NE, "near_miss"), ("2*m*g/3", NE, ["dimension"], "dimension"),
])
add("yoyo", "angular_acceleration", "2*g/(3*R)", YOYO, [
    ("2g/(3R)", EQ, "typical"), ("(2/3)*g/R", EQ, "typical"), ("2*g*R^-1/3", EQ, "typical"),
    ("g/(3*R/2)", EQ, "typical"), ("2*g/3/R", EQ, "typical"),
    ("2*g*R/3", NE, ["dimension"], "dimension"), ("2*g/3", NE, ["dimension"], "dimension"),
    ("g/(3*R)", NE, ["typical", "slip"], "factor"), ("2*g/(3*R) + 10^-9*g/R", NE, "near_miss"),
])

# -- sphere: normal force -----------------------------------------------------------------------
N_SPHERE = "m*g*(3*cos(theta) - 2)"
add("sphere", "normal_force", N_SPHERE, SPHERE, [
    ("mg(3cos θ - 2)", EQ, "typical"), ("3 m g cos(theta) - 2 m g", EQ, "typical"),
    ("m*g*(3*cos(theta) - 2)", EQ, "typical"), ("3mg\\cos\\theta - 2mg", EQ, "typical"),
    ("m*g*cos(theta) - 2*m*g*(1 - cos(theta))", EQ, "typical"),
    ("m*g*(1 - 6*sin(theta/2)^2)", EQ, ["typical", "float64_hostile"]),
    ("m*g*(3*cos(theta) - 2*sin(theta)^2 - 2*cos(theta)^2)", EQ, "typical"),
    ("m*g*(3*sin(pi/2 - theta) - 2)", EQ, "typical"),
    ("m*g*(6*cos(theta/2)^2 - 5)", EQ, "typical"),
    ("-m*g*(2 - 3*cos(theta))", EQ, "typical"),
    ("m*g*(3*cos(-theta) - 2)", EQ, "typical"),
    ("3*m*g*(cos(theta) - 2/3)", EQ, "typical"),
    ("m*g*(3*cos(theta) - 2)*(sin(theta)^2 + cos(theta)^2)", EQ, "typical"),
    ("m g cos(theta) - 2 m g + 2 m g cos(theta)", EQ, "typical"),
    ("m*g*(3*sqrt(1 - sin(theta)^2) - 2)", NE, ["domain"]),
    ("m*g*(3*abs(cos(theta)) - 2)", NE, ["domain"]),
    ("m*g*cos(theta)", NE, ["typical", "slip"], "instructor"),
    ("m*g*(3*cos(theta) + 2)", NE, ["typical", "slip"], "term_sign"),
    ("m*g*(2 - 3*cos(theta))", NE, ["typical", "slip"], "sign"),
    ("3*m*g*cos(theta)", NE, ["typical", "slip"], "missing_term"),
    ("m*g*(3*sin(theta) - 2)", NE, ["typical", "slip"], "sin_cos"),
    ("m*g*(2*cos(theta) - 2)", NE, "typical"),
    ("m*g*(3*cos(theta) - 1)", NE, "typical"),
    ("2*m*g*(3*cos(theta) - 2)", NE, ["typical", "slip"], "factor"),
    ("m*g*(3*cos(theta) - 2) + 10^-9*m*g", NE, "near_miss"),
    ("m*g*(3*cos(theta) - 2.000000001)", NE, "near_miss"),
    ("m*g*(3*cos(theta) - 2)*R", NE, ["dimension"], "dimension"),
    ("g*(3*cos(theta) - 2)", NE, ["dimension"], "dimension"),
    ("m*g*(3*cos(theta) - 2*R)", NE, ["dimension"], "dimension"),
    ("m*g*(3*cos(theta*m) - 2)", NE, ["dimension"], "dimension"),
    ("m*g*(3*cos(theta) - 2", INV, "syntax"), ("m*g*(3*cos(phi) - 2)", INV, "syntax"),
    ("m*g*(3*cos() - 2)", INV, "syntax"),
], feedback=[{"expr": "m*g*cos(theta)", "message": "The particle moves on a circle: it needs a centripetal force."}])
add("sphere", "separation_cos", "2/3", {"m": var("mass", POS)}, [
    ("2/3", EQ, "typical"), ("0.6666666666666666666666666666666666666666666666666667", NE, "near_miss"),
    ("1 - 1/3", EQ, "typical"), ("4/6", EQ, "typical"), ("0.667", NE, ["near_miss"], "close"),
    ("1/3", NE, "typical"), ("cos(2/3)", NE, "typical"), ("sqrt(4/9)", EQ, "typical"),
    ("acos(2/3)", NE, "typical"), ("2/3*m", NE, ["dimension"], "dimension"),
])
add("sphere", "separation_drop", "R/3", {"R": var("length", POS)}, [
    ("R/3", EQ, "typical"), ("R - 2R/3", EQ, "typical"), ("R*(1 - 2/3)", EQ, "typical"),
    ("R - R*2/3", EQ, "typical"), ("2R/3", NE, "typical"), ("R/3 + 1", NE, ["dimension"], "dimension"),
])
# Small angles near the top: R(1 - cos theta) against forms that float64 cannot evaluate there.
add("sphere", "drop_small_angle", "R*(1 - cos(theta))", SPHERE_SMALL, [
    ("2*R*sin(theta/2)^2", EQ, ["float64_hostile"]),
    ("R - R*cos(theta)", EQ, ["float64_hostile"]),
    ("R*sin(theta)^2/(1 + cos(theta))", EQ, ["float64_hostile"]),
    ("R*(1 - cos(theta))", EQ, "typical"),
    ("R*theta^2/2", NE, ["near_miss"]),  # the small-angle approximation: off by ~theta^2/12 relative
    ("R*(1 - cos(theta)) + R*theta^3", NE, ["near_miss"]),
    ("R*theta", NE, "typical"),
    ("R*(1 - cos(theta))*(1 + 10^-9)", NE, "near_miss"),
])

# -- rolling down an incline, I = beta m R^2 -----------------------------------------------------
add("incline_general", "acceleration", "g*sin(alpha)/(1 + beta)", ROLLING, [
    ("g sin(alpha)/(1 + beta)", EQ, "typical"), ("g*sin(alpha)/(beta + 1)", EQ, "typical"),
    ("\\frac{g\\sin\\alpha}{1+\\beta}", EQ, "typical"), ("g sin α/(1+β)", EQ, "typical"),
    ("g*sin(alpha) - beta*g*sin(alpha)/(1 + beta)", EQ, "typical"),
    ("m*g*R^2*sin(alpha)/(m*R^2 + beta*m*R^2)", EQ, "typical"),
    ("g*sqrt(1 - cos(alpha)^2)/(1 + beta)", EQ, ["domain"]),  # alpha in [0, pi/2]: sin >= 0
    ("g*tan(alpha)*cos(alpha)/(1 + beta)", EQ, "typical"),
    ("2*g*sin(alpha/2)*cos(alpha/2)/(1 + beta)", EQ, "typical"),
    ("g*cos(pi/2 - alpha)/(1+beta)", EQ, "typical"),
    ("g*sin(alpha)", NE, ["typical", "slip"], "instructor"),
    ("g*cos(alpha)/(1 + beta)", NE, ["typical", "slip"], "sin_cos"),
    ("g*sin(alpha)/(1 - beta)", NE, "typical"),
    ("g*sin(alpha)*(1 + beta)", NE, "typical"),
    ("g*sin(alpha)/beta", NE, "typical"),
    ("g*sin(alpha)/(1 + beta)*(1 + 10^-9)", NE, "near_miss"),
    ("g*sin(alpha)/(1 + beta + 10^-9)", NE, "near_miss"),
    ("m*g*sin(alpha)/(1 + beta)", NE, ["dimension"], "dimension"),
    ("g*sin(alpha)/(1 + R)", NE, ["dimension"], "dimension"),
    ("g*sin(alpha)/(1 + beta", INV, "syntax"),
], feedback=[{"expr": "g*sin(alpha)", "message": "That is the acceleration of a body sliding without friction."}])
add("incline_general", "friction_force", "beta*m*g*sin(alpha)/(1 + beta)", ROLLING, [
    ("beta m g sin(alpha)/(1+beta)", EQ, "typical"),
    ("m*g*sin(alpha) - m*g*sin(alpha)/(1 + beta)", EQ, ["typical", "float64_hostile"]),
    ("m*g*sin(alpha)*(1 - 1/(1 + beta))", EQ, ["typical", "float64_hostile"]),
    ("m*g*sin(alpha)/(1 + 1/beta)", EQ, "typical"),
    ("β m g sin α/(1+β)", EQ, "typical"),
    ("m*(g*sin(alpha) - g*sin(alpha)/(1 + beta))", EQ, "typical"),
    ("m*g*sin(alpha)/(1 + beta)", NE, ["typical"], "instructor"),
    ("beta*m*g*cos(alpha)/(1 + beta)", NE, ["typical", "slip"], "sin_cos"),
    ("-beta*m*g*sin(alpha)/(1 + beta)", NE, ["typical", "slip"], "sign"),
    ("beta*m*g*sin(alpha)", NE, "typical"),
    ("beta*m*g*sin(alpha)/(1 + beta) + m*g/10^9", NE, "near_miss"),
    ("beta*g*sin(alpha)/(1 + beta)", NE, ["dimension"], "dimension"),
], feedback=[{"expr": "m*g*sin(alpha)/(1 + beta)", "message": "That is m times the acceleration."}])
add("incline_general", "normal_force", "m*g*cos(alpha)", ROLLING, [
    ("m g cos(alpha)", EQ, "typical"), ("m*g*sqrt(1 - sin(alpha)^2)", EQ, ["domain"]),
    ("m*g*sin(pi/2 - alpha)", EQ, "typical"), ("m*g/sec(alpha)", EQ, "typical"),
    ("m*g*(1 - 2*sin(alpha/2)^2)", EQ, "typical"),
    ("m*g*sin(alpha)", NE, ["typical", "slip"], "sin_cos"), ("m*g", NE, "typical"),
    ("m*g*cos(alpha)/(1 + beta)", NE, "typical"), ("-m*g*cos(alpha)", NE, ["typical", "slip"], "sign"),
    ("m*g*cos(alpha) + 10^-9*m*g", NE, "near_miss"), ("m*cos(alpha)", NE, ["dimension"], "dimension"),
    ("m*g*cos(alpha*R)", NE, ["dimension"], "dimension"),
])
# the specific bodies: disk beta = 1/2, ring beta = 1, solid sphere 2/5, spherical shell 2/3
for body, beta in (("disk", "1/2"), ("ring", "1"), ("solid_sphere", "2/5"), ("spherical_shell", "2/3")):
    variables = {k: v for k, v in ROLLING.items() if k != "beta"}
    a = f"g*sin(alpha)/(1 + {beta})"
    add(f"incline_{body}", "acceleration", a, variables, [
        (a, EQ, "typical"),
        (f"g*sin(alpha)*(1 - {beta}/(1 + {beta}))", EQ, "typical"),
        ("g*sin(alpha)", NE, "typical"),
        (f"g*cos(alpha)/(1 + {beta})", NE, ["typical", "slip"], "sin_cos"),
        (f"g*sin(alpha)/(1 + {beta})*(1 + 10^-9)", NE, "near_miss"),
    ])
add("incline_disk", "acceleration_value", "2*g*sin(alpha)/3", {k: v for k, v in ROLLING.items() if k != "beta"}, [
    ("2g sin(alpha)/3", EQ, "typical"), ("g*sin(alpha)/1.5", EQ, "typical"),
    ("g*sin(alpha)/(1 + 1/2)", EQ, "typical"), ("0.6667*g*sin(alpha)", NE, ["near_miss"], "close"),
    ("g*sin(alpha)/2", NE, "typical"),
])

# -- equations of motion ------------------------------------------------------------------------
add("pendulum", "equation_of_motion", "thetaddot = -g/l*sin(theta)", PENDULUM_EOM, [
    ("thetaddot = -g/l*sin(theta)", EQ, "typical"),
    ("thetaddot + (g/l) sin(theta) = 0", EQ, "typical"),
    ("l thetaddot = -g sin theta", EQ, "typical"),
    ("m l^2 thetaddot + m g l sin(theta) = 0", EQ, "typical"),
    ("l*thetaddot + g*sin(theta) = 0", EQ, "typical"),
    ("-l*thetaddot = g*sin(theta)", EQ, "typical"),
    ("\\ddot\\theta = -\\frac{g}{l}\\sin\\theta", EQ, "typical"),
    ("θ̈ + g/l sin θ = 0", EQ, "typical"),
    ("2*m*l*thetaddot = -2*m*g*sin(theta)", EQ, "typical"),
    ("m*l^2*thetaddot = -m*g*l*sin(theta)", EQ, "typical"),
    ("thetaddot + g/l*sin(theta)", EQ, "typical"),  # read as "... = 0"
    ("g*sin(theta) = -l*thetaddot", EQ, "typical"),
    ("thetaddot = -g/l*2*sin(theta/2)*cos(theta/2)", EQ, "typical"),
    ("thetaddot = g/l*sin(theta)", NE, ["typical", "slip"], "term_sign"),
    ("thetaddot = -g/l*cos(theta)", NE, ["typical", "slip"], "sin_cos"),
    ("thetaddot = -g/l*theta", NE, ["typical"]),
    ("thetaddot = -l/g*sin(theta)", NE, ["dimension"], "dimension"),
    ("thetaddot = -g*sin(theta)", NE, ["dimension"], "dimension"),
    ("thetaddot*cos(theta) = -g/l*sin(theta)*cos(theta)", NE, ["typical"]),  # factor depends on the state
    ("thetaddot*thetadot = -g/l*sin(theta)*thetadot", NE, ["typical"]),
    ("thetaddot = -g/l*sin(theta) + thetadot^2", NE, ["typical", "slip"], "extra_term"),
    ("thetaddot = 0", NE, ["typical", "slip"], "missing_term"),
    ("thetaddot = -g/l*sin(theta)*(1 + 10^-9)", NE, "near_miss"),
    ("thetaddot*(1 + 10^-9) = -g/l*sin(theta)", NE, "near_miss"),
    ("thetaddot = -g/l*sin(theta", INV, "syntax"),
    ("thetaddot == -g/l*sin(theta) = 0", INV, "syntax"),
], kind="equation")
add("pendulum", "equation_of_motion_by_name", "thetaddot = -g/l*sin(theta)",
    {k: {kk: vv for kk, vv in v.items() if kk != "kind"} for k, v in PENDULUM_EOM.items()}, [
    ("m l^2 thetaddot + m g l sin(theta) = 0", EQ, "typical"),
    ("thetaddot*cos(theta) = -g/l*sin(theta)*cos(theta)", NE, "typical"),
    ("l thetaddot = g sin theta", NE, "typical"),
], kind="equation")
add("half_atwood", "equation_of_motion", "(m1 + m2)*yddot = m2*g",
    {**ATWOOD, "yddot": var("acceleration", "real", "acceleration")}, [
    ("(m1+m2) yddot = m2 g", EQ, "typical"), ("yddot = m2*g/(m1 + m2)", EQ, "typical"),
    ("m1*yddot + m2*yddot - m2*g = 0", EQ, "typical"), ("m2*(g - yddot) = m1*yddot", EQ, "typical"),
    ("yddot/g = m2/(m1 + m2)", EQ, "typical"),
    ("m2*yddot = m2*g", NE, "typical"), ("(m1 + m2)*yddot = m1*g", NE, "typical"),
    ("(m1 - m2)*yddot = m2*g", NE, "typical"), ("(m1 + m2)*yddot = -m2*g", NE, ["typical", "slip"], "term_sign"),
    ("(m1 + m2)*yddot = m2*g*(1 + 10^-9)", NE, "near_miss"),
    ("(m1 + m2)*yddot = m2", NE, ["dimension"], "dimension"),
], kind="equation")
add("half_atwood", "equations_with_tension",
    "m1*xddot = -T; m2*yddot = m2*g - T; xddot + yddot = 0", ATWOOD_SYSTEM, [
    ("m1*xddot = -T; m2*yddot = m2*g - T; xddot + yddot = 0", EQ, "typical"),
    ("xddot = -yddot; m2*yddot = m2*g - T; m1*xddot + T = 0", EQ, "typical"),
    ("m1*xddot + T = 0\nm2*yddot + T = m2*g\nyddot = -xddot", EQ, "typical"),
    ("m1*xddot - m2*yddot = -m2*g; m2*yddot = m2*g - T; xddot + yddot = 0", EQ, "typical"),
    ("T = -m1*xddot; T = m2*(g - yddot); xddot = -yddot", EQ, "typical"),
    ("m1*xddot = T; m2*yddot = m2*g - T; xddot + yddot = 0", NE, "typical"),
    ("m1*xddot = -T; m2*yddot = m2*g + T; xddot + yddot = 0", NE, "typical"),
    ("m1*xddot = -T; m2*yddot = m2*g - T", NE, "typical"),
    ("m1*xddot = -T; m2*yddot = m2*g - T; xddot = yddot", NE, "typical"),
    ("m1*xddot = -T; m2*yddot = m2*g - T; m1*xddot - m2*yddot = -m2*g", NE, "typical"),
    ("m1*xddot = -T; m2*yddot = m2*g - T*(1 + 10^-9); xddot + yddot = 0", NE, "near_miss"),
    ("m1*xddot = -T; m2*yddot = m2*g - T; xddot + yddot = g", NE, ["dimension"]),
], kind="equation")
add("yoyo", "equation_of_motion", "3*sddot = 2*g", YOYO_EOM, [
    ("sddot = 2g/3", EQ, "typical"), ("3/2 m sddot = m g", EQ, "typical"),
    ("m*sddot + m*sddot/2 = m*g", EQ, "typical"), ("sddot - 2*g/3 = 0", EQ, "typical"),
    ("sddot = g", NE, "typical"), ("sddot = g/3", NE, "typical"), ("sddot = 2*g/3*(1 + 10^-9)", NE, "near_miss"),
    ("sddot = 2*g/3*R", NE, ["dimension"], "dimension"),
], kind="equation")
add("incline_general", "equation_of_motion", "(1 + beta)*sddot = g*sin(alpha)", ROLLING_EOM, [
    ("sddot = g sin(alpha)/(1+beta)", EQ, "typical"), ("m*(1 + beta)*sddot = m*g*sin(alpha)", EQ, "typical"),
    ("m*sddot + beta*m*R^2*sddot/R^2 = m*g*sin(alpha)", EQ, "typical"),
    ("sddot + beta*sddot - g*sin(alpha) = 0", EQ, "typical"),
    ("sddot = g*sin(alpha)", NE, "typical"), ("(1 + beta)*sddot = g*cos(alpha)", NE, ["typical", "slip"], "sin_cos"),
    ("(1 - beta)*sddot = g*sin(alpha)", NE, "typical"),
    ("(1 + beta)*sddot = g*sin(alpha) + 10^-9*g", NE, "near_miss"),
    ("(1 + beta)*sddot = m*g*sin(alpha)", NE, ["dimension"], "dimension"),
], kind="equation")

# -- hostile input: must be rejected cleanly (fast, no crash, nothing executed) -----------------
HOSTILE = [
    ("__import__('os').system('echo pwned')", INV),
    ("exec('import os')", INV),
    ("eval('1+1')", INV),
    ("lambda: m", INV),
    ("m.__class__.__mro__", INV),
    ("globals()", INV),
    ("open('/etc/passwd').read()", INV),
    ("9^9^9^9", INV),
    ("9**9**9", INV),
    ("10^10^10", INV),
    ("2^2^2^2^2^2", INV),
    ("m^(10^100)", INV),
    ("(m*g)^(10^9)", INV),
    ("10^1000000*m*g", INV),
    ("1" * 1500 + "*m*g", INV),
    ("(" * 5000 + "m*g" + ")" * 5000, INV),
    ("((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((m*g))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))", INV),
    ("m*g/3 + " * 400 + "0", INV),
    ("sin(" * 300 + "m" + ")" * 300, INV),
    ("-" * 1000 + "m*g", INV),
    ("m" * 100000, INV),
    ("m*g\x00/3", INV),
    ("m*g/3; import os", INV),
    ("m*g/3 # comment", INV),
    ("factorial(10^6)", INV),
    ("gamma(m)", INV),
    ("Integral(m, m)", INV),
    ("m*g/3 if 1 else 0", INV),
    ("[m*g/3]", EQ),  # square brackets group, like parentheses
    ("{m: g}", INV),
    ("'m*g/3'", INV),
    ("\\input{/etc/passwd}", INV),
    ("\\def\\x{m}", INV),
    ("m*g/3 \u202e", INV),
    ("ｍ*g/3", INV),
    ("1/0", INV),
    ("0^(-1)*m*g", INV),
    ("m*g*log(0)", INV),
    ("\ud800", INV),
    ("m*g/3" + " " * 3000, INV),
    ("exp(exp(exp(exp(exp(m/m)))))*m*g", INV),  # too large for any finite evaluation: undecided
    ("m*g/3*exp(exp(exp(exp(R/R))))", NE),
    ("(m*g/3)^1000/(m*g/3)^999", EQ),
    ("sin(sin(sin(sin(sin(sin(sin(sin(sin(sin(R/R))))))))))*m*g", NE),
    ("m*g*sqrt(-1)", INV),  # the parser refuses non-real numbers
    ("m*g*log(-R/R)", INV),
    ("m*g/(R - R)", INV),
    ("m*g*(R/R)^(10^6)", INV),
    ("m*g/3 + 0*(R/R)^999", EQ),
    ("m*g/3*(1 + (R/R - 1)^999)", EQ),
]
add("yoyo", "tension_hostile", "m*g/3", YOYO, [(answer, expected, "hostile") for answer, expected in HOSTILE])


# -- notation, functions, powers, the whole domain, equations by the right rule, alternatives ----------
# (issue 11, items 6-11). Appended after the older items so their ids stay the same.
DOUBLE_PENDULUM = {"m": var("mass", POS), "g": var("acceleration", POS), "l": var("length", POS),
                   **{f"theta{i}": var("angle", PI_DOMAIN) for i in (1, 2)},
                   **{f"theta{i}dot": var("angular_velocity") for i in (1, 2)},
                   **{f"theta{i}ddot": var("angular_acceleration") for i in (1, 2)}}
add("double_pendulum", "kinetic_energy_upper", "m*l^2*theta1dot^2/2", DOUBLE_PENDULUM, [
    ("m l² θ̇₁²/2", EQ, "notation"),
    ("m l^2 θ₁̇^2/2", EQ, "notation"),
    ("m*l^2*theta_1dot^2/2", EQ, "notation"),
    ("m l^2 dot{θ}_1^2/2", EQ, "notation"),
    ("\\frac{1}{2} m l^2 \\dot{\\theta}_1^2", EQ, "notation"),
    ("\\frac{1}{2} m \\ell^2 \\dot\\theta_1^2", EQ, "notation"),
    ("m ℓ² θ̇₁²/2", EQ, "notation"),
    ("m l^2 θ˙₁^2/2", EQ, "notation"),
    ("m l^2 θ̇₂^2/2", NE, "notation"),
    ("m l^2 θ̇₁/2", NE, ["notation", "dimension"], "dimension"),
    ("m l^2 θ̇̇̇₁^2/2", INV, "notation"),
])
add("double_pendulum", "tangential_force_upper", "m*l*theta1ddot", DOUBLE_PENDULUM, [
    ("m ℓ θ̈₁", EQ, "notation"),
    ("m l \\ddot{\\theta}_{1}", EQ, "notation"),
    ("m l ddot(θ)_1", EQ, "notation"),
    ("m*l*theta_1''", EQ, "notation"),
    ("m l θ¨₁", EQ, "notation"),
    ("m l θ̈₂", NE, "notation"),
])
PLANE = {"m": var("mass", POS), "x": var("length"), "xdot": var("velocity"), "xddot": var("acceleration"),
         "y": var("length"), "ydot": var("velocity"), "yddot": var("acceleration")}
add("plane", "force_sum", "m*(xddot + yddot)", PLANE, [
    ("m(ẍ + ÿ)", EQ, "notation"),
    ("m(x\u0308 + y\u0308)", EQ, "notation"),
    ("m ẍ + m ÿ", EQ, "notation"),
    ("mẍ + mÿ", EQ, "notation"),
    ("m(ẍ + ẏ)", NE, ["notation", "dimension"], "dimension"),
])

NUMBER = {"x": var("dimensionless"), "y": var("dimensionless"), "u": var("dimensionless", [0.1, 0.9])}
for reference, entries in [
    ("asinh(x)", [("log(x + sqrt(x^2 + 1))", EQ), ("arsinh(x)", EQ), ("ln(x + sqrt(1 + x²))", EQ),
                  ("log(x + sqrt(x^2 - 1))", NE), ("sinh(x)", NE)]),
    ("acosh(1 + x^2)", [("arcosh(1 + x²)", EQ), ("log(1 + x^2 + sqrt((1 + x^2)^2 - 1))", EQ),
                        ("acos(1 + x^2)", NE)]),
    ("atanh(u)", [("log((1 + u)/(1 - u))/2", EQ), ("artanh(u)", EQ), ("log((1 + u)/(1 - u))", NE)]),
    ("sech(x)", [("1/cosh(x)", EQ), ("2/(exp(x) + exp(-x))", EQ), ("1/sinh(x)", NE)]),
    ("csch(u)", [("1/sinh(u)", EQ), ("2/(e^u - e^(-u))", EQ), ("1/cosh(u)", NE)]),
    ("coth(u)", [("cosh(u)/sinh(u)", EQ), ("1/tanh(u)", EQ), ("tanh(u)", NE)]),
    ("csc(u)", [("cosec(u)", EQ), ("1/sin(u)", EQ), ("sec(u)", NE)]),
    ("atan2(y, x)", [("arctan2(y, x)", EQ), ("atan2(x, y)", NE), ("atan2(x)", INV), ("atan2 x", INV)]),
    ("asin(u) + acos(u)", [("pi/2", EQ), ("arcsin(u) + arccos(u)", EQ), ("asin(u) - acos(u)", NE)]),
    ("atan(u)", [("arctan(u)", EQ), ("asin(u/sqrt(1 + u^2))", EQ), ("atan(u + 0.5)", NE),
                 ("asin(u + 0.25)", NE), ("acos(0.5 - u)", NE)]),
    ("sign(x)", [("sgn(x)", EQ), ("x/abs(x)", EQ), ("abs(x)/x", EQ), ("-sign(x)", NE)]),
    ("log(x^2 + 1)/log(10)", [("log10(x^2 + 1)", EQ), ("ln(x^2 + 1)", NE), ("log10(x^2 + 2)", NE)]),
    ("asin(u)", [("asin(3/2)", INV), ("sin^-1(u)", EQ)]),
]:
    add("functions", reference.split("(")[0], reference, NUMBER,
        [(answer, expected, "function") for answer, expected in entries])

POWERS = {"x": var("dimensionless"), "y": var("dimensionless", POS), "n": var("dimensionless")}
for reference, entries in [
    ("x", [("sqrt(x)^2", NE), ("exp(log(x))", NE), ("(x^(1/3))^3", NE), ("x^(1/2)*x^(1/2)", NE),
           ("(x^3)^(1/3)", NE), ("abs(x)", NE), ("x^1", EQ), ("(x^3)^(1/3)*sign(x)^2", NE)]),
    ("abs(x)", [("sqrt(x^2)", EQ), ("(x^2)^(1/2)", EQ), ("(x^4)^(1/4)", EQ), ("x", NE)]),
    ("y", [("sqrt(y)^2", EQ), ("exp(log(y))", EQ), ("(y^3)^(1/3)", EQ), ("y^(1/2)*y^(1/2)", EQ)]),
    ("(x^2)^n", [("x^(2*n)", NE), ("abs(x)^(2*n)", EQ)]),
    ("log(x^2)", [("2*log(x)", NE), ("2*log(abs(x))", EQ)]),
    ("(x^3)^(1/3)", [("x", NE), ("(x^(1/3))^3", EQ)]),  # both defined exactly for x >= 0, and equal there
]:
    add("powers", "real_powers", reference, POWERS, [(answer, expected, "power") for answer, expected in entries])

REAL = {"x": var("dimensionless")}
for reference, entries in [
    ("acosh(x/5)", [("log(x/5 + sqrt(x^2/25 - 1))", EQ), ("log(x/5 + sqrt(x^2/25 + 1))", NE)]),
    ("sqrt(x - 5)", [("sqrt(2*x - 10)/sqrt(2)", EQ), ("sqrt(x - 6)", NE), ("sqrt(x - 5)*(1 + 10^-9)", NE)]),
    ("sqrt(x - 5)*sqrt(x + 5)", [("sqrt(x^2 - 25)", NE)]),
    ("log(x - 100)", [("log(2*x - 200) - log(2)", EQ), ("log(x - 101)", NE)]),
]:
    add("domain_scale", "defined_far_from_zero", reference, REAL,
        [(answer, expected, "domain_scale") for answer, expected in entries])

POLAR = {"g": var("acceleration", POS), "r": var("length", POS, "coordinate"),
         "rdot": var("velocity", "real", "velocity"), "rddot": var("acceleration", "real", "acceleration"),
         "thetadot": var("angular_velocity", "real", "velocity"), "x": var("dimensionless", "real", "coordinate")}
add("polar", "radial_equation", "rddot = r*thetadot^2 - g", POLAR, [
    ("r^2 rddot = r^3 thetadot^2 - g r^2", EQ, "state_factor"),
    ("(rddot - r thetadot^2 + g)/r = 0", EQ, "state_factor"),
    ("(1 + x^2)(rddot - r thetadot^2 + g) = 0", EQ, "state_factor"),
    ("x (rddot - r thetadot^2 + g) = 0", NE, "state_factor"),
    ("thetadot (rddot - r thetadot^2 + g) = 0", NE, "state_factor"),
    ("rddot = r thetadot^2 + g", NE, "typical"),
], kind="equation")
add("pendulum", "equation_of_motion_small_swings", "thetaddot = -g/l*sin(theta)",
    {**PENDULUM_EOM, "theta": var("angle", [-1.5, 1.5], "coordinate")}, [
    ("thetaddot*cos(theta) = -g/l*sin(theta)*cos(theta)", EQ, "state_factor"),  # cos > 0 on [-1.5, 1.5]
    ("(2 + cos(theta)) (l thetaddot + g sin(theta)) = 0", EQ, "state_factor"),
    ("thetaddot*thetadot = -g/l*sin(theta)*thetadot", NE, "state_factor"),
], kind="equation")
add("polynomial", "root", "x^2 = 1", {"x": var("dimensionless", POS, "coordinate")}, [
    ("x - 1 = 0", EQ, "factored"),
    ("(x - 1)(x + 1) = 0", EQ, "factored"),
    ("x^2 - x = 0", EQ, "factored"),       # x (x - 1): x > 0 adds no root
    ("x = 2", NE, "factored"),
    ("x + 1 = 0", NE, "factored"),         # no root at all for x > 0
], kind="equation")

HOOP = {"g": var("acceleration", POS), "a": var("length", POS), "omega": var("angular_velocity", [5, 10])}
add("hoop", "equilibrium", "acos(g/(omega^2*a))", HOOP, [
    ("acos(g/(a ω²))", EQ, "alternatives"),
    ("-acos(g/(ω² a))", EQ, "alternatives"),       # the mirror equilibrium, accepted as an alternative
    ("-arccos(g/(a*omega^2))", EQ, "alternatives"),
    ("asin(g/(ω² a))", NE, "alternatives"),
    ("pi - acos(g/(omega^2 a))", NE, "alternatives"),
])
items[-5:] = [{**item, "alternatives": ["-acos(g/(omega^2*a))"]} for item in items[-5:]]


# -- textbook scenes (tests/mechanics/scenes): bigger answers than the paper's ------------------------
# References as the engine derives them; every answer form below was rewritten and labelled by hand.
DOUBLE = {"g": var("acceleration", POS), "l1": var("length", POS), "l2": var("length", POS),
          "m1": var("mass", POS), "m2": var("mass", POS),
          "theta1": var("angle", PI_DOMAIN, "coordinate"), "theta2": var("angle", PI_DOMAIN, "coordinate"),
          "theta1dot": var("angular_velocity", "real", "velocity"),
          "theta2dot": var("angular_velocity", "real", "velocity")}
add("textbook", "double_pendulum_tension_lower",
    "m1*m2*(g*cos(theta1)*cos(theta1 - theta2) + l1*theta1dot**2*cos(theta1 - theta2) + l2*theta2dot**2)"
    "/(m1 + m2*sin(theta1 - theta2)**2)", DOUBLE, [
        ("m1 m2 (cos(θ₁ - θ₂)(g cos θ₁ + l1 θ̇₁²) + l2 θ̇₂²)/(m1 + m2 sin²(θ₁ - θ₂))", EQ, "textbook"),
        ("m1 m2 (cos(θ₁ - θ₂)(g cos θ₁ + l1 θ̇₁²) + l2 θ̇₂²)/(m1 + m2 - m2 cos(θ₁ - θ₂)^2)", EQ, "textbook"),
        ("m1*m2*(g*cos(theta1) + l1*theta1dot^2)*(cos(theta1)*cos(theta2) + sin(theta1)*sin(theta2))"
         "/(m1 + m2*sin(theta1 - theta2)^2) + m1*m2*l2*theta2dot^2/(m1 + m2*sin(theta1 - theta2)^2)", EQ, "textbook"),
        ("m1 m2 (cos(θ₁ - θ₂)(g cos θ₁ + l1 θ̇₁²) + l2 θ̇₂²)/(m1 + m2 cos²(θ₁ - θ₂))", NE, "textbook"),
        ("m1 m2 cos(θ₁ - θ₂)(g cos θ₁ + l1 θ̇₁²)/(m1 + m2 sin²(θ₁ - θ₂))", NE, "textbook"),
        ("m1 m2 (cos(θ₁ - θ₂)(g cos θ₁ - l1 θ̇₁²) + l2 θ̇₂²)/(m1 + m2 sin²(θ₁ - θ₂))", NE, "textbook"),
    ])
add("textbook", "double_pendulum_tension_upper",
    "m1*(g*m1*cos(theta1) + g*m2*cos(theta1) + l1*m1*theta1dot**2 + l1*m2*theta1dot**2"
    " + l2*m2*theta2dot**2*cos(theta1 - theta2))/(m1 + m2*sin(theta1 - theta2)**2)", DOUBLE, [
        ("m1 ((m1 + m2)(g cos θ₁ + l1 θ̇₁²) + m2 l2 θ̇₂² cos(θ₁ - θ₂))/(m1 + m2 sin²(θ₁ - θ₂))", EQ, "textbook"),
        ("m1*(m1 + m2)*(g*cos(theta1) + l1*theta1dot^2)/(m1 + m2*sin(theta1 - theta2)^2)"
         " + m1*m2*l2*theta2dot^2*cos(theta1 - theta2)/(m1 + m2*sin(theta1 - theta2)^2)", EQ, "textbook"),
        ("m1 (m1 (g cos θ₁ + l1 θ̇₁²) + m2 l2 θ̇₂² cos(θ₁ - θ₂))/(m1 + m2 sin²(θ₁ - θ₂))", NE, "textbook"),
        ("m1 ((m1 + m2)(g cos θ₁ + l1 θ̇₁²) + m2 l2 θ̇₂² cos(θ₁ + θ₂))/(m1 + m2 sin²(θ₁ - θ₂))", NE, "textbook"),
    ])
WEDGE = {"M": var("mass", POS), "m": var("mass", POS), "g": var("acceleration", POS),
         "alpha": var("angle", [0.05, 1.5])}
add("textbook", "wedge_normal_force", "M*g*m*cos(alpha)/(M + m*sin(alpha)**2)", WEDGE, [
    ("M m g cos α/(M + m sin²α)", EQ, "textbook"),
    ("M m g cos(α)/(M + m - m cos(α)^2)", EQ, "textbook"),
    ("m g cos(α)/(1 + (m/M) sin(α)^2)", EQ, "textbook"),
    ("m g cos α", NE, "textbook"),
    ("M m g cos α/(M + m sin α)", NE, "textbook"),
])
add("textbook", "wedge_acceleration", "-g*m*sin(alpha)*cos(alpha)/(M + m*sin(alpha)**2)", WEDGE, [
    ("-m g sin(2α)/(2(M + m sin²α))", EQ, "textbook"),
    ("-g m sin α cos α/(M + m sin(α)^2)", EQ, "textbook"),
    ("m g sin α cos α/(M + m sin²α)", NE, "textbook"),
    ("-m g sin α cos α/(M + m)", NE, "textbook"),
])
ORBIT = {"g": var("acceleration", POS), "m1": var("mass", POS), "m2": var("mass", POS),
         "omega0": var("angular_velocity", POS), "r": var("length", POS, "coordinate"), "r0": var("length", POS)}
add("textbook", "orbit_radial_acceleration", "(-g*m2*r**3 + m1*omega0**2*r0**4)/(r**3*(m1 + m2))", ORBIT, [
    ("(m1 ω0² r0⁴/r³ - m2 g)/(m1 + m2)", EQ, "textbook"),
    ("(m1 omega0^2 r0^4 - m2 g r^3)/(r^3 (m1 + m2))", EQ, "textbook"),
    ("(m1 ω0² r0²/r - m2 g)/(m1 + m2)", NE, "textbook"),
    ("(m1 ω0² r0⁴/r³ + m2 g)/(m1 + m2)", NE, "textbook"),
])
add("textbook", "orbit_tension", "m1*m2*(g*r**3 + omega0**2*r0**4)/(r**3*(m1 + m2))", ORBIT, [
    ("m1 m2 (g + ω0² r0⁴/r³)/(m1 + m2)", EQ, "textbook"),
    ("m1*m2*g/(m1 + m2) + m1*m2*omega0^2*r0^4/(r^3*(m1 + m2))", EQ, "textbook"),
    ("m1 m2 (g - ω0² r0⁴/r³)/(m1 + m2)", NE, "textbook"),
])
add("textbook", "orbit_radial_speed_squared",
    "-(r - r0)*(2*g*m2*r**2 - m1*omega0**2*r*r0**2 - m1*omega0**2*r0**3)/(r**2*(m1 + m2))", ORBIT, [
        ("(m1 ω0² r0² (1 - r0²/r²) - 2 m2 g (r - r0))/(m1 + m2)", EQ, "textbook"),
        ("(m1*omega0^2*r0^2*(r - r0)*(r + r0)/r^2 - 2*m2*g*(r - r0))/(m1 + m2)", EQ, "textbook"),
        ("(m1 ω0² r0² (1 - r0²/r²) + 2 m2 g (r - r0))/(m1 + m2)", NE, "textbook"),
        ("(m1 ω0² r0² (1 - r0/r) - 2 m2 g (r - r0))/(m1 + m2)", NE, "textbook"),
    ])
PULLEY = {"M": var("mass", POS), "m1": var("mass", POS), "m2": var("mass", POS), "g": var("acceleration", POS),
          "R": var("length", POS), "L": var("length", POS)}
add("textbook", "massive_pulley_acceleration", "2*g*(m1 - m2)/(M + 2*m1 + 2*m2)", PULLEY, [
    ("g (m1 - m2)/(m1 + m2 + M/2)", EQ, "textbook"),
    ("(m1 - m2) g/(m1 + m2 + 0.5 M)", EQ, "textbook"),
    ("g (m1 - m2)/(m1 + m2 + M)", NE, "textbook"),
    ("g (m2 - m1)/(m1 + m2 + M/2)", NE, "textbook"),
])
add("textbook", "massive_pulley_tension_left", "g*m1*(M + 4*m2)/(M + 2*m1 + 2*m2)", PULLEY, [
    ("m1 g - 2 m1 g (m1 - m2)/(M + 2 m1 + 2 m2)", EQ, "textbook"),
    ("m1 g (M + 4 m2)/(M + 2(m1 + m2))", EQ, "textbook"),
    ("m1 g (M + 2 m2)/(M + 2 m1 + 2 m2)", NE, "textbook"),
])
HOOP_MOTION = {"a": var("length", POS), "g": var("acceleration", POS), "m": var("mass", POS),
               "omega": var("angular_velocity", POS), "theta": var("angle", PI_DOMAIN, "coordinate"),
               "thetadot": var("angular_velocity", "real", "velocity"),
               "thetaddot": var("angular_acceleration", "real", "acceleration")}
add("textbook", "hoop_drive_torque", "2*a**2*m*omega*thetadot*sin(theta)*cos(theta)", HOOP_MOTION, [
    ("m a² ω θ̇ sin(2θ)", EQ, "textbook"),
    ("2 m a^2 omega thetadot sin theta cos theta", EQ, "textbook"),
    ("2 m a² ω θ̇ sin θ", NE, "textbook"),
])
add("textbook", "hoop_speed_squared",
    "(a*omega**2*sin(theta)**2 - a*omega**2*sin(3/10)**2 + 2*g*cos(theta) - 2*g*cos(3/10))/a", HOOP_MOTION, [
        ("ω²(sin²θ - sin²(0.3)) + 2g/a (cos θ - cos(0.3))", EQ, "textbook"),
        ("omega^2*(cos(0.3)^2 - cos(theta)^2) + 2*g*(cos(theta) - cos(0.3))/a", EQ, "textbook"),
        ("ω²(sin²θ - sin²(0.3)) + 2g/a (cos(0.3) - cos θ)", NE, "textbook"),
    ])
add("textbook", "hoop_equation_of_motion", "thetaddot = (a*omega**2*cos(theta) - g)*sin(theta)/a", HOOP_MOTION, [
    ("a θ̈ = (a ω² cos θ - g) sin θ", EQ, "textbook"),
    ("θ̈ = ω² sin θ cos θ - g/a sin θ", EQ, "textbook"),
    ("m a² θ̈ = m a (a ω² cos θ - g) sin θ", EQ, "textbook"),
    ("θ̈ = ω² sin θ cos θ + g/a sin θ", NE, "textbook"),
], kind="equation")
LADDER = {"g": var("acceleration", POS), "l": var("length", POS), "m": var("mass", POS),
          "theta": var("angle", [0, 1.5708], "coordinate"), "theta0": var("angle", [0.1, 1.5])}
add("textbook", "ladder_wall_force", "3*g*m*(3*sin(theta) - 2*sin(theta0))*cos(theta)/4", LADDER, [
    ("(3/4) m g cos θ (3 sin θ - 2 sin θ0)", EQ, "textbook"),
    ("9/4 m g sin θ cos θ - 3/2 m g sin(theta0) cos θ", EQ, "textbook"),
    ("9/8 m g sin(2θ) - 3/2 m g sin(theta0) cos(theta)", EQ, "textbook"),
    ("(3/4) m g sin θ (3 cos θ - 2 sin θ0)", NE, "textbook"),
    ("(3/4) m g cos θ (3 sin θ - 2 sin θ0) + m g/10^6", NE, "textbook"),
])



# -- equations of motion as a system, mixed by a state-dependent matrix ------------------------------
# The reference solves for the accelerations; a student's unsolved Euler-Lagrange equations
# M(q) qddot = F(q, qdot) are the same system because the mass matrix is invertible everywhere. A
# row multiplied by something that can vanish (thetadot, cos(theta) on (-pi, pi)) is not. Labels
# from the mixing matrix's determinant, worked by hand.
DOUBLE_EOM = {**DOUBLE, "theta1ddot": var("angular_acceleration", "real", "acceleration"),
              "theta2ddot": var("angular_acceleration", "real", "acceleration")}
DOUBLE_SOLVED = (
    "theta1ddot = (-g*(2*m1 + m2)*sin(theta1) - m2*g*sin(theta1 - 2*theta2) - 2*sin(theta1 - theta2)*m2*"
    "(theta2dot^2*l2 + theta1dot^2*l1*cos(theta1 - theta2)))/(l1*(2*m1 + m2 - m2*cos(2*theta1 - 2*theta2))); "
    "theta2ddot = 2*sin(theta1 - theta2)*(theta1dot^2*l1*(m1 + m2) + g*(m1 + m2)*cos(theta1) + "
    "theta2dot^2*l2*m2*cos(theta1 - theta2))/(l2*(2*m1 + m2 - m2*cos(2*theta1 - 2*theta2)))")
# dL/dtheta1 and dL/dtheta2 divided by l1 and m2 l2: det M = l1 l2 (m1 + m2 sin^2(theta1 - theta2)) > 0
UPPER = "(m1 + m2) l1 θ̈₁ + m2 l2 cos(θ₁ - θ₂) θ̈₂ + m2 l2 θ̇₂² sin(θ₁ - θ₂) + (m1 + m2) g sin θ₁"
LOWER = "l2 θ̈₂ + l1 cos(θ₁ - θ₂) θ̈₁ - l1 θ̇₁² sin(θ₁ - θ₂) + g sin θ₂"
add("textbook", "double_pendulum_equations_of_motion", DOUBLE_SOLVED, DOUBLE_EOM, [
    (f"{UPPER} = 0; {LOWER} = 0", EQ, ["system_factor", "textbook"]),
    (f"{LOWER} = 0; {UPPER} = 0", EQ, ["system_factor", "textbook"]),
    (f"l1 ({UPPER}) = 0; m2 l2 ({LOWER}) = 0", EQ, ["system_factor", "textbook"]),  # d/dt dL/dqdot - dL/dq
    (f"(m1 + m2) l1 θ̈₁ + m2 l2 cos(θ₁ - θ₂) θ̈₂ = -m2 l2 θ̇₂² sin(θ₁ - θ₂) - (m1 + m2) g sin θ₁; "
     f"l2 θ̈₂ + l1 cos(θ₁ - θ₂) θ̈₁ = l1 θ̇₁² sin(θ₁ - θ₂) - g sin θ₂", EQ, ["system_factor", "textbook"]),
    # the solved first row with the unsolved second: det = l2 > 0
    (f"{DOUBLE_SOLVED.split(';')[0]}; {LOWER} = 0", EQ, ["system_factor", "textbook"]),
    (f"{UPPER} = 0; {LOWER.replace('- l1 θ̇₁²', '+ l1 θ̇₁²')} = 0", NE, ["system_factor", "textbook"]),
    (f"{UPPER.replace('(m1 + m2) l1 θ̈₁', 'm1 l1 θ̈₁')} = 0; {LOWER} = 0", NE, ["system_factor", "textbook"]),
    (f"{UPPER} = 0; {LOWER.replace('cos(θ₁ - θ₂)', 'cos(θ₁ + θ₂)')} = 0", NE, ["system_factor", "textbook"]),
    (f"θ̇₁ ({UPPER}) = 0; {LOWER} = 0", NE, ["system_factor", "textbook"]),          # thetadot1 = 0 loses a row
    (f"{UPPER} = 0; cos(θ₁ - θ₂) ({LOWER}) = 0", NE, ["system_factor", "textbook"]),  # zero at a right angle
    (f"{UPPER} = 0; {UPPER} = 0", NE, ["system_factor", "textbook"]),
], kind="equation")
ORBIT_EOM = {**ORBIT, "rdot": var("velocity", "real", "velocity"),
             "rddot": var("acceleration", "real", "acceleration"),
             "phidot": var("angular_velocity", "real", "velocity"),
             "phiddot": var("angular_acceleration", "real", "acceleration")}
# L = (m1 + m2) rdot^2/2 + m1 r^2 phidot^2/2 - m2 g r: the radial equation and d/dt(m1 r^2 phidot) = 0
add("textbook", "orbit_equations_of_motion",
    "rddot = (m1*r*phidot^2 - m2*g)/(m1 + m2); phiddot = -2*rdot*phidot/r", ORBIT_EOM, [
        ("(m1 + m2) rddot = m1 r phidot^2 - m2 g; m1 r^2 phiddot + 2 m1 r rdot phidot = 0", EQ,
         ["system_factor", "textbook"]),
        ("(m1 + m2) r̈ - m1 r φ̇² + m2 g = 0; r φ̈ + 2 ṙ φ̇ = 0", EQ, ["system_factor", "textbook"]),
        ("m1 r^2 phiddot + 2 m1 r rdot phidot = 0; (m1 + m2) rddot = m1 r phidot^2 - m2 g", EQ,
         ["system_factor", "textbook"]),
        ("(m1 + m2) rddot = m1 r phidot^2 + m2 g; m1 r^2 phiddot + 2 m1 r rdot phidot = 0", NE,
         ["system_factor", "textbook"]),
        ("m1 rddot = m1 r phidot^2 - m2 g; m1 r^2 phiddot + 2 m1 r rdot phidot = 0", NE,
         ["system_factor", "textbook"]),  # the hanging block's inertia forgotten
        ("(m1 + m2) rddot = m1 r phidot^2 - m2 g; m1 r^2 phiddot + m1 r rdot phidot = 0", NE,
         ["system_factor", "textbook"]),
        ("(m1 + m2) rddot = m1 r phidot^2 - m2 g; rdot (m1 r^2 phiddot + 2 m1 r rdot phidot) = 0", NE,
         ["system_factor", "textbook"]),  # zero at the turning points, rdot = 0
    ], kind="equation")

ELASTIC = {"g": var("acceleration", POS), "k": var("stiffness", POS), "m": var("mass", POS), "L": var("length", POS),
           "r": var("length", POS, "coordinate"), "rdot": var("velocity", "real", "velocity"),
           "rddot": var("acceleration", "real", "acceleration"), "theta": var("angle", PI_DOMAIN, "coordinate"),
           "thetadot": var("angular_velocity", "real", "velocity"),
           "thetaddot": var("angular_acceleration", "real", "acceleration")}
SPRING = "rddot = r thetadot^2 + g cos(theta) - k (r - L)/m; thetaddot = -(g sin(theta) + 2 rdot thetadot)/r"
RADIAL = "m rddot - m r thetadot^2 - m g cos(theta) + k (r - L)"     # the first row times m
ANGULAR = "m r^2 thetaddot + 2 m r rdot thetadot + m g r sin(theta)"  # the second times m r^2
add("elastic_pendulum", "equations_of_motion", SPRING, ELASTIC, [
    (f"{RADIAL} = 0; {ANGULAR} = 0", EQ, "system_factor"),
    (f"{ANGULAR} = 0; {RADIAL} = 0", EQ, "system_factor"),
    ("rddot = r thetadot^2 + g cos(theta) - k (r - L)/m; r thetaddot + 2 rdot thetadot + g sin(theta) = 0", EQ,
     "system_factor"),
    (f"{RADIAL} + r cos(theta) ({ANGULAR})/r^2 = 0; {ANGULAR} = 0", EQ, "system_factor"),  # det unchanged
    (f"(2 + cos(theta)) ({RADIAL}) = 0; {ANGULAR} = 0", EQ, "system_factor"),
    (f"(1 + r^2/L^2) ({RADIAL}) = 0; {ANGULAR} = 0", EQ, "system_factor"),
    (f"{RADIAL} + ({ANGULAR})/r = 0; {RADIAL} - ({ANGULAR})/r = 0", EQ, "system_factor"),  # det = -2 m^2 r
    (f"thetadot ({RADIAL}) = 0; {ANGULAR} = 0", NE, "system_factor"),
    (f"thetadot^2 ({RADIAL}) = 0; {ANGULAR} = 0", NE, "system_factor"),
    (f"cos(theta) ({RADIAL}) = 0; {ANGULAR} = 0", NE, "system_factor"),
    (f"(r - L) ({RADIAL}) = 0; {ANGULAR} = 0", NE, "system_factor"),       # zero at the natural length
    (f"{RADIAL} + ({ANGULAR})/r = 0; sin(theta) ({RADIAL}) + cos(theta) ({ANGULAR})/r = 0", NE,
     "system_factor"),                                                     # det = m^2 r (cos - sin)
    (f"{RADIAL} = 0; {ANGULAR.replace('+ 2 m r', '- 2 m r')} = 0", NE, "system_factor"),
    (f"{RADIAL} = 0; {ANGULAR.replace(' + m g r sin(theta)', '')} = 0", NE, "system_factor"),
    (f"{RADIAL} = 0; {RADIAL} = 0", NE, "system_factor"),
    (f"{RADIAL} = 0; r ({RADIAL}) = 0", NE, "system_factor"),
], kind="equation")
add("elastic_pendulum", "equations_of_motion_small_swings", SPRING,
    {**ELASTIC, "theta": var("angle", [-1.5, 1.5], "coordinate")}, [
    (f"cos(theta) ({RADIAL}) = 0; {ANGULAR} = 0", EQ, "system_factor"),   # cos > 0 on [-1.5, 1.5]
    (f"thetadot ({RADIAL}) = 0; {ANGULAR} = 0", NE, "system_factor"),
], kind="equation")
KEPLER = {"k": var("kg*m^3/s^2", POS), "m": var("mass", POS), "r": var("length", POS, "coordinate"),
          "rdot": var("velocity", "real", "velocity"), "rddot": var("acceleration", "real", "acceleration"),
          "thetadot": var("angular_velocity", "real", "velocity"),
          "thetaddot": var("angular_acceleration", "real", "acceleration")}
add("central_force", "equations_of_motion", "rddot = r thetadot^2 - k/(m r^2); thetaddot = -2 rdot thetadot/r",
    KEPLER, [
        ("m rddot - m r thetadot^2 + k/r^2 = 0; m r^2 thetaddot + 2 m r rdot thetadot = 0", EQ, "system_factor"),
        ("r^2 rddot = r^3 thetadot^2 - k/m; r thetaddot + 2 rdot thetadot = 0", EQ, "system_factor"),
        ("m r^2 rddot - m r^3 thetadot^2 + k = 0; m r^2 thetaddot = -2 m r rdot thetadot", EQ, "system_factor"),
        ("m rddot = m r thetadot^2 + k/r^2; m r^2 thetaddot + 2 m r rdot thetadot = 0", NE, "system_factor"),
        ("m rddot = m r thetadot^2 - k/r^2; m r^2 thetaddot + m r rdot thetadot = 0", NE, "system_factor"),
        ("m rddot = m r thetadot^2 - k/r^2; rdot (r thetaddot + 2 rdot thetadot) = 0", NE, "system_factor"),
    ], kind="equation")


# -- Leibniz notation: dθ/dt, d²x/dt², \frac{d\theta}{dt}, d/dt(θ) (leibniz.jsonl) ----------------------
# Read as the dotted variable only where d, dt and the d-words mean nothing else; with d and t declared
# the same letters are a quotient of products. Appended after the older items so their ids stay the same.
def leibniz_items() -> None:
    add("leibniz", "pendulum_tension", "m*l*thetadot^2 + m*g*cos(theta)", PENDULUM, [
        ("m l (dθ/dt)^2 + m g cos θ", EQ, "notation"),
        ("m l (dθ/dt)² + m g cos θ", EQ, "notation"),
        ("m*l*(dtheta/dt)^2 + m*g*cos(theta)", EQ, "notation"),
        ("m l (d theta/dt)^2 + m g cos(theta)", EQ, "notation"),
        ("m l (d(θ)/dt)^2 + m g cos θ", EQ, "notation"),
        ("m l (dθ/dt)(dθ/dt) + m g cos θ", EQ, "notation"),
        ("m l \\left(\\frac{d\\theta}{dt}\\right)^2 + m g \\cos\\theta", EQ, "notation"),
        ("m l \\left(\\frac{\\mathrm{d}\\theta}{\\mathrm{d}t}\\right)^{2} + m g \\cos\\theta", EQ, "notation"),
        ("m l \\left(\\dfrac{d\\theta}{dt}\\right)^2 + m g \\cos\\theta", EQ, "notation"),
        ("m l (d/dt θ)^2 + m g cos θ", EQ, "notation"),
        ("m l (d/dt(θ))^2 + m g cos θ", EQ, "notation"),
        ("m l (dθ/dt)^2 - m g cos θ", NE, ["notation", "slip"]),
        ("m l dθ/dt + m g cos θ", NE, ["notation", "dimension"], "dimension"),
        ("m l^2 (dθ/dt)^2 + m g cos θ", NE, ["notation", "dimension"], "dimension"),
        ("m l dθ/dt² + m g cos θ", INV, "notation"),          # orders disagree: d on top, dt² below
        ("m l d²θ/dt² + m g cos θ", INV, "notation"),         # no thetaddot in this problem
        ("m l (dθ/dx)^2 + m g cos θ", INV, "notation"),       # not a time derivative
        ("m l d/dt θ^2 + m g cos θ", INV, "notation"),        # d/dt of θ², or (d/dt θ)²?
        ("m l d/dt(θ^2) + m g cos θ", NE, ["notation", "dimension"], "dimension"),  # 2 m l θ θ̇: a momentum
    ])
    add("leibniz", "pendulum_equation_of_motion", "thetaddot = -g/l*sin(theta)", PENDULUM_EOM, [
        ("d²θ/dt² = -g/l sin θ", EQ, "notation"),
        ("d^2θ/dt^2 + (g/l) sin θ = 0", EQ, "notation"),
        ("d^2 theta/dt^2 + g/l sin(theta) = 0", EQ, "notation"),
        ("\\frac{d^2\\theta}{dt^2} = -\\frac{g}{l}\\sin\\theta", EQ, "notation"),
        ("\\frac{\\mathrm{d}^2\\theta}{\\mathrm{d}t^2} + \\frac{g}{l}\\sin\\theta = 0", EQ, "notation"),
        ("m l² d²θ/dt² + m g l sin θ = 0", EQ, "notation"),
        ("d/dt θ̇ = -g/l sin θ", EQ, "notation"),
        ("dθ̇/dt + g/l sin θ = 0", EQ, "notation"),
        ("\\frac{d}{dt}\\dot{\\theta} = -\\frac{g}{l}\\sin\\theta", EQ, "notation"),
        ("d²θ/dt² = g/l sin θ", NE, ["notation", "slip"], "term_sign"),
        ("d²θ/dt² = -g/l cos θ", NE, ["notation", "slip"], "sin_cos"),
        ("(dθ/dt)^2 = -g/l sin θ", NE, "notation"),
        ("dθ/dt = -g/l sin θ", NE, ["notation", "dimension"], "dimension"),
        ("d²θ/dt = -g/l sin θ", INV, "notation"),             # orders disagree
    ], kind="equation")
    add("leibniz", "plane_force_sum", "m*(xddot + yddot)", PLANE, [
        ("m(d²x/dt² + d²y/dt²)", EQ, "notation"),
        ("m d^2x/dt^2 + m d^2y/dt^2", EQ, "notation"),
        ("m\\left(\\frac{d^2x}{dt^2} + \\frac{d^2y}{dt^2}\\right)", EQ, "notation"),
        ("m (d/dt ẋ + d/dt ẏ)", EQ, "notation"),
        ("m(d²x/dt² - d²y/dt²)", NE, "notation"),
        ("m(d²x/dt² + dy/dt)", NE, ["notation", "dimension"], "dimension"),
    ])
    # t declared as the time: still the derivative; t declared as a length: refused.
    timed = {"m": var("mass", POS), "x": var("length"), "xdot": var("velocity"), "t": var("time", "nonnegative")}
    add("leibniz", "momentum_with_time_declared", "m*xdot", timed, [
        ("m dx/dt", EQ, "notation"), ("m d x/d t", EQ, "notation"), ("m \\frac{dx}{dt}", EQ, "notation"),
        ("m x/t", NE, "notation"),
    ])
    add("leibniz", "momentum_with_t_a_length", "m*xdot",
        {"m": var("mass", POS), "x": var("length"), "xdot": var("velocity"), "t": var("length", POS)}, [
        ("m dx/dt", INV, "notation"), ("m xdot", EQ, "notation"),
    ])
    # d (a length) and t declared: the same letters are the quotient of products d·x/(d·t) = x/t.
    quotient = {"d": var("length", POS), "x": var("length"), "t": var("time", POS), "xdot": var("velocity")}
    add("leibniz", "declared_d_and_t_are_a_quotient", "x/t", quotient, [
        ("d x/(d t)", EQ, "notation"), ("(d x)/(d t)", EQ, "notation"), ("\\frac{d x}{d t}", EQ, "notation"),
        ("\\frac{dx}{dt}", EQ, "notation"), ("xdot", NE, "notation"),
    ])


leibniz_items()



# -- more mixing matrices of the spring pendulum, appended so that the ids above stay the same ---------
# Determinants positive for all lengths, which a box of finite r cannot show: r/L is taken onto [0, 1].
add("elastic_pendulum", "equations_of_motion_all_lengths", SPRING, ELASTIC, [
    (f"(r^2 - r L + L^2) ({RADIAL}) = 0; {ANGULAR} = 0", EQ, "system_factor"),  # no real root in r/L
    # det = m^2 r ((2 + sin) r/L - 2 (1 + r^2/L^2)): discriminant (2 + sin)^2 - 16 < 0, never zero
    (f"(2 + sin(theta)) ({RADIAL}) + 2 ({ANGULAR})/r = 0; (1 + r^2/L^2) ({RADIAL}) + ({ANGULAR})/L = 0", EQ,
     "system_factor"),
    (f"(r^2 - 3 r L + L^2) ({RADIAL}) = 0; {ANGULAR} = 0", NE, "system_factor"),  # zero at r/L = (3 +- sqrt 5)/2
], kind="equation")


# -- Leibniz, continued: d/dt of a bracketed derivative is the second derivative (leibniz.jsonl) --------
add("leibniz", "pendulum_equation_of_motion_nested", "thetaddot = -g/l*sin(theta)", PENDULUM_EOM, [
    ("d/dt(dθ/dt) = -g/l sin θ", EQ, "notation"),
    ("\\frac{d}{dt}\\left(\\frac{d\\theta}{dt}\\right) + \\frac{g}{l}\\sin\\theta = 0", EQ, "notation"),
    ("d/dt(d/dt(θ)) + g/l sin θ = 0", EQ, "notation"),
    ("d/dt(dθ/dt) = g/l sin θ", NE, ["notation", "slip"], "term_sign"),
    ("d/dt(dθ/dt)^2 = -g/l sin θ", INV, "notation"),      # the derivative of θ̇², or (θ̈)²?
], kind="equation")
# A factor whose zero theta = 1/3 is inside [-1.5, 1.5] but is no float.
add("pendulum", "equation_of_motion_small_swings_factor", "thetaddot = -g/l*sin(theta)",
    {**PENDULUM_EOM, "theta": var("angle", [-1.5, 1.5], "coordinate")}, [
    ("(3 theta - 1)(l thetaddot + g sin(theta)) = 0", NE, "state_factor"),
    ("(3 theta - 5)(l thetaddot + g sin(theta)) = 0", EQ, "state_factor"),   # zero at 5/3, outside
], kind="equation")
# Mixing determinants that are products: proved or refused factor by factor.
add("elastic_pendulum", "equations_of_motion_products", SPRING, ELASTIC, [
    (f"(r^2 - r L + L^2)(10 theta^2 + 1) ({RADIAL}) = 0; {ANGULAR} = 0", EQ, "system_factor"),
    (f"(3 theta - 1)^2 ({RADIAL}) = 0; {ANGULAR} = 0", NE, "system_factor"),    # zero at theta = 1/3
    (f"(2 + cos(theta))^3 ({RADIAL}) = 0; r ({ANGULAR}) = 0", EQ, "system_factor"),
], kind="equation")

# -- notation of other hands, appended so that the ids above stay the same (notation.jsonl) -----------
# Logarithms to a base: log_2 x was read as log(2)·x and graded wrong against log base 2.
LOGS = {"a": var("dimensionless", POS), "x": var("dimensionless")}
add("notation", "logarithm_base_2", "log(a)/log(2)", LOGS, [
    ("log_2 a", EQ, "notation"), ("log_{2}(a)", EQ, "notation"), ("log2(a)", EQ, "notation"),
    ("\\log_2 a", EQ, "notation"), ("\\log_{2}(a)", EQ, "notation"), ("ln(a)/ln(2)", EQ, "notation"),
    ("log_10 a", NE, "notation"), ("log(a)", NE, "notation"), ("log_b a", INV, "notation"),
])
add("notation", "logarithm_base_10", "log(a)/log(10)", LOGS, [
    ("log10(a)", EQ, "notation"), ("log_{10} a", EQ, "notation"), ("\\log_{10}(a)", EQ, "notation"),
    ("lg a", EQ, "notation"), ("log_2 a", NE, "notation"),
])
add("notation", "log_of_two_times", "a*log(2)", LOGS, [
    ("a log2", EQ, "notation"), ("a ln2", EQ, "notation"), ("a ln 2", EQ, "notation"),
    ("log2(a)", NE, "notation"),                       # called, it is the logarithm to base 2 of a
])
# Absolute values between bars.
add("notation", "absolute_value", "abs(x) + 2*abs(x - a)", LOGS, [
    ("|x| + 2|x - a|", EQ, "notation"), ("\\left|x\\right| + 2\\left|x - a\\right|", EQ, "notation"),
    ("\\lvert x\\rvert + 2 \\lvert a - x \\rvert", EQ, "notation"), ("abs(x) + 2|a - x|", EQ, "notation"),
    ("|x + 2(x - a)|", NE, "notation"), ("x + 2|x - a|", NE, "notation"), ("|x| + 2|x - a", INV, "notation"),
])
add("notation", "nested_absolute_value", "abs(abs(x) - a)", LOGS, [
    ("||x| - a|", EQ, "notation"), ("|a - |x||", EQ, "notation"), ("|x - a|", NE, "notation"),
])
# The cube root over the reals, defined for negative numbers.
add("notation", "real_cube_root", "sign(x)*abs(x)**(1/3)", LOGS, [
    ("cbrt(x)", EQ, "notation"), ("-cbrt(-x)", EQ, "notation"), ("x^(1/3)", NE, ["notation", "domain"]),
])
# Vulgar fractions and the typographic signs of word processors.
add("notation", "vulgar_fractions", "3*x/4 + a/2", LOGS, [
    ("¾x + ½a", EQ, "notation"), ("¾ x + a·½", EQ, "notation"), ("x∙¾ + a ⁄ 2", EQ, "notation"),
    ("¾x – ½a", NE, "notation"), ("1½ x", INV, "notation"),
])
# Other traditions' names of functions, and the products of variables they collide with.
add("notation", "regional_function_names", "tan(x) + atan(x) + cot(x)", LOGS, [
    ("tg x + arctg x + ctg x", EQ, "notation"), ("tg(x) + arctg(x) + cotg(x)", EQ, "notation"),
    ("tg x + arctg x - ctg x", NE, "notation"),
])
add("notation", "lg_is_a_product_of_declared_letters", "sqrt(l*g)",
    {"l": var("length", POS), "g": var("acceleration", POS)}, [
    ("sqrt(lg)", EQ, "notation"), ("√(lg)", EQ, "notation"), ("sqrt(log10(g))", NE, ["notation", "dimension"]),
])

# The quantity's name before the answer, and a full stop after it, as written on paper.
add("notation", "labelled_answer", "m*g*(3*cos(theta) - 2)",
    {"m": var("mass", POS), "g": var("acceleration", POS), "theta": var("angle", PI_DOMAIN)}, [
    ("N = m g (3 cos θ - 2)", EQ, "notation"), ("N(θ) = mg(3cosθ - 2)", EQ, "notation"),
    ("F_N = 3mg cos θ - 2mg.", EQ, "notation"), ("N = m g (3 cos θ + 2)", NE, "notation"),
    ("m = 3 m g cos θ - 2 m g", INV, "notation"),          # an equation in m, not a label
    ("m g (3 cos θ - 2) N", INV, "notation"),              # a unit: named, not guessed
])


def build() -> dict[str, int]:
    by_problem: dict[str, list[dict]] = {}
    for n, item in enumerate(items):
        item = {"id": f"{item['problem']}/{item['question']}/{n:04d}", **item}
        by_problem.setdefault(item["problem"], []).append(item)
    # Only the files built here are rewritten: other corpus files (other_graders_stack, redteam_2026_11,
    # equations_redteam) are written by hand or by their own scripts and must survive a rebuild.
    for problem, rows in by_problem.items():
        with open(HERE / f"{problem}.jsonl", "w", encoding="utf-8") as f:
            for row in rows:
                f.write(json.dumps(row) + "\n")
    return {problem: len(rows) for problem, rows in by_problem.items()}


if __name__ == "__main__":
    counts = build()
    print(json.dumps(counts), sum(counts.values()), "items")
