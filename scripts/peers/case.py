"""The colliding elastic rings of Gray, Monaghan & Swift (2001) as gsph's cases/rings.toml
defines it, shared by the peer scripts (PySPH, LAMMPS SMD) and the metrics.

Two rings r_i = 0.03, r_o = 0.04 m, each the square lattice x, y = -r_o + i dx
(numpy.mgrid[-ro:ro:dx, -ro:ro:dx]) kept where r_i^2 <= x^2 + y^2 < r_o^2; left ring
centred at (0, 0) moving +x, right ring at (0.082, 0) moving -x, both at 0.059 c0.
"""

import math

import numpy as np

RHO0 = 1.0
E = 1.0e7
NU = 0.3975
G = E / (2.0 * (1.0 + NU))
K = E / (3.0 * (1.0 - 2.0 * NU))
C0 = math.sqrt(K / RHO0)  # 4032.3891927275595 m/s
U0 = 0.059 * C0  # 237.910962370926 m/s
R_IN = 0.03
R_OUT = 0.04
SEPARATION = 0.082  # between the ring centres
HDX = 1.5  # h = 1.5 dx
DT = 1.0e-8
T_END = 5.0e-5
T_OUT = (1.0e-5, 5.0e-5)  # the metric times
TIMING_STEPS = 1000
DX_CHOICES = (1.0e-3, 5.0e-4, 2.5e-4)
# Monaghan artificial viscosity and Monaghan/Gray artificial stress (PySPH's example values).
AV_ALPHA = 1.0
AV_BETA = 1.0
AS_EPS = 0.3
AS_N = 4


def ring(dx):
    """One ring's lattice sites (x, y) about its centre, as PySPH's example builds them."""
    x, y = np.mgrid[-R_OUT:R_OUT:dx, -R_OUT:R_OUT:dx]
    x = x.ravel()
    y = y.ravel()
    d = x * x + y * y
    keep = np.flatnonzero((R_IN * R_IN <= d) * (d < R_OUT * R_OUT))
    return x[keep], y[keep]


def particles(dx):
    """Both rings: x, y, vx, vy, m, body (0 left, 1 right), left ring first."""
    x, y = ring(dx)
    n = x.size
    xs = np.concatenate([x, x + SEPARATION])
    ys = np.concatenate([y, y])
    body = np.concatenate([np.zeros(n, dtype=np.int32), np.ones(n, dtype=np.int32)])
    vx = np.where(body == 0, U0, -U0)
    vy = np.zeros_like(xs)
    m = np.full(xs.size, RHO0 * dx * dx)
    return xs, ys, vx, vy, m, body


def expected_count(dx):
    """Particle count of both rings (17,592 at dx = 5e-4)."""
    return 2 * ring(dx)[0].size
