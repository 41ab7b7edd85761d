"""``grader bench isolation``: does one user's abuse slow everyone else's ``POST /check``?"""

from __future__ import annotations

__all__ = ["pathological_scene"]


def pathological_scene(links: int = 3, slug: str | None = None) -> str:
    """A valid scene the engine is slow on: a chain of ``links`` pendulums in absolute angles.

    Two links derive in about two seconds; three take over a minute (the coupled mass matrix is
    inverted symbolically), so with three links every derivation runs into its time limit.
    """
    terms = []
    for k in range(links):
        xdot = " + ".join(f"cos(q{i})*q{i}dot" for i in range(k + 1))
        ydot = " + ".join(f"sin(q{i})*q{i}dot" for i in range(k + 1))
        terms.append(f"({xdot})^2 + ({ydot})^2")
    coordinates = "\n".join(f'q{i} = {{ dimension = "angle" }}' for i in range(links))
    potential = " + ".join(f"{links - i}*cos(q{i})" for i in range(links))
    return f'''id = "{slug or f'chain{links}'}"
title = "A chain of {links} pendulums"
statement = "Equal bobs of mass $m$ on light rods of length $l$, each hanging from the one above."
[parameters]
m = {{ dimension = "mass", domain = "positive" }}
g = {{ dimension = "acceleration", domain = "positive" }}
l = {{ dimension = "length", domain = "positive" }}
[coordinates]
{coordinates}
[energy]
kinetic = "m*l^2/2*({' + '.join(terms)})"
potential = "-m*g*l*({potential})"
[[answers]]
name = "first"
prompt = "Angular acceleration of the top link"
expr = "q0ddot"
dimension = "angular_acceleration"
'''
