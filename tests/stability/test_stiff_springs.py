"""A stiff spring beside a soft one: two unit masses on springs of k = 1e4 N/m and 1e-2 N/m.

Their frequencies are 6 orders of magnitude apart in stiffness (ω = 100 and 0.1 rad/s). Each must
keep its own harmonic motion x_i = A_i cos(ω_i t) to 1e-8 of its amplitude: the soft one must not be spoiled by the steps
the stiff one forces, nor the stiff one lose amplitude or phase over ~160 of its periods.
"""

from __future__ import annotations

import numpy as np

from grader.mechanics.scene import parse_scene
from grader.simulate.trajectory import simulate_scene

SPRINGS = parse_scene('''
id = "springs"
[parameters]
m = { dimension = "mass", domain = "positive", value = 1.0 }
k1 = { dimension = "stiffness", domain = "positive", value = 1e4 }
k2 = { dimension = "stiffness", domain = "positive", value = 1e-2 }
[coordinates]
x1 = { dimension = "length" }
x2 = { dimension = "length" }
[energy]
kinetic = "m/2*(x1dot^2 + x2dot^2)"
potential = "k1/2*x1^2 + k2/2*x2^2"
[initial]
x1 = 0.01
x2 = 0.5
x1dot = 0
x2dot = 0
''', source="springs.toml")


def test_each_spring_keeps_its_own_harmonic_motion():
    motion = simulate_scene(SPRINGS, t_end=10.0, samples=401)
    t = motion.t
    np.testing.assert_allclose(motion.q[:, 0], 0.01 * np.cos(100 * t), rtol=0, atol=1e-8 * 0.01)
    np.testing.assert_allclose(motion.q[:, 1], 0.5 * np.cos(0.1 * t), rtol=0, atol=1e-8 * 0.5)
    np.testing.assert_allclose(motion.qdot[:, 1], -0.05 * np.sin(0.1 * t), rtol=0, atol=1e-8 * 0.05)
