#!/usr/bin/env python3
"""Reference figures for lectern's adaptive-pair tests and docs/benchmarks/ode.md, computed once
and committed as tests/data/ode_reference.json (CI never runs Python):

* exact solutions in 40-digit arithmetic (mpmath) for the hard cases:
  - the pendulum θ'' = −sin θ from 179° at rest: θ(t) = 2 asin(k sn(K − t | k²)),
    ω(t) = −2k cn(K − t | k²), k = sin(θ₀/2) (Jacobi elliptic functions), cross-checked against
    mpmath's Taylor-series ODE solver over the first time unit;
  - Kepler orbits (GM = 1, a = 1, from perihelion) at any time via Kepler's equation
    E − e sin E = t: x = cos E − e, y = √(1−e²) sin E, v = (−sin E, √(1−e²) cos E)/(1 − e cos E);
* scipy's solve_ivp(method="DOP853") (Hairer's DOP853 in Python) on the same problems and
  tolerances: f-evaluations and final errors, the independent implementation the tests and the
  benchmark report compare with.

Usage: pip install scipy mpmath; python3 scripts/scipy_reference.py > tests/data/ode_reference.json
"""

import json
import math

import numpy as np
import scipy
from mpmath import mp, mpf, asin, ellipfun, ellipk, sin, cos, sqrt, findroot, odefun, pi

mp.dps = 40


def kepler_exact(e, t):
    e, t = mpf(e), mpf(t)
    E = findroot(lambda E: E - e * sin(E) - t, t)
    d = 1 - e * cos(E)
    b = sqrt(1 - e * e)
    return [cos(E) - e, b * sin(E), -sin(E) / d, b * cos(E) / d]


def pendulum_exact(theta0, t):
    k = sin(mpf(theta0) / 2)
    m = k * k
    u = ellipk(m) - mpf(t)
    return [2 * asin(k * ellipfun("sn", u, m=m)), -2 * k * ellipfun("cn", u, m=m)]


def kepler_rhs(t, y):
    r3 = (y[0] * y[0] + y[1] * y[1]) ** 1.5
    return [y[2], y[3], -y[0] / r3, -y[1] / r3]


def pendulum_rhs(t, y):
    return [y[1], -math.sin(y[0])]


def dop853(rhs, y0, t_end, exact, tols):
    rows = []
    for tol in tols:
        sol = scipy.integrate.solve_ivp(
            rhs, (0.0, t_end), y0, method="DOP853", rtol=tol, atol=tol
        )
        err = max(abs(float(a) - float(b)) for a, b in zip(sol.y[:, -1], exact))
        rows.append({"tol": tol, "nfev": int(sol.nfev), "error": err})
    return rows


def as_floats(v):
    return [float(x) for x in v]


def main():
    theta0 = 179 * math.pi / 180  # as the problem file writes it: 3.12413936106985
    theta0_file = 3.12413936106985
    # cross-check the elliptic-function solution against a Taylor-series integration
    taylor = odefun(lambda t, y: [y[1], -sin(y[0])], 0, [mpf(theta0_file), mpf(0)])
    check = max(abs(a - b) for a, b in zip(taylor(1), pendulum_exact(theta0_file, 1)))
    assert check < mpf("1e-30"), check

    tols = [10.0**-k for k in range(3, 14)]
    pend = pendulum_exact(theta0_file, 10)
    kep06 = kepler_exact("0.6", 2 * pi)
    kep09_times = [61.0, float(20 * pi)]
    kep09 = [kepler_exact("0.9", t) for t in kep09_times]
    e9 = 0.9
    kep09_y0 = [1 - e9, 0.0, 0.0, math.sqrt((1 + e9) / (1 - e9))]
    out = {
        "generated_by": "scripts/scipy_reference.py",
        "scipy": scipy.__version__,
        "pendulum": {
            "theta0": theta0_file,
            "t_end": 10.0,
            "exact": as_floats(pend),
            "taylor_check": float(check),
            "scipy_dop853": dop853(pendulum_rhs, [theta0_file, 0.0], 10.0, pend, tols),
        },
        "kepler_e06": {
            "initial": [0.4, 0.0, 0.0, 2.0],
            "t_end": float(2 * pi),
            "exact": as_floats(kep06),
            "scipy_dop853": dop853(kepler_rhs, [0.4, 0.0, 0.0, 2.0], float(2 * pi), kep06, tols),
        },
        "kepler_e09": {
            "initial": kep09_y0,
            "times": kep09_times,
            "exact": [as_floats(v) for v in kep09],
            "scipy_dop853": dop853(kepler_rhs, kep09_y0, float(20 * pi), kep09[1], tols),
        },
    }
    print(json.dumps(out, indent=1))


if __name__ == "__main__":
    main()
