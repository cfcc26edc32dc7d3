#!/usr/bin/env python3
"""Reference figures for lectern's stiff solvers (tests/ode_stiff.rs, docs/benchmarks/stiff.md),
computed once and committed as tests/data/stiff_reference.json (CI never runs Python):

* scipy's solve_ivp with method Radau (Hairer & Wanner's RADAU5 algorithm in Python), BDF and
  LSODA, each given the analytic Jacobian (as lectern's solvers get theirs): f-evaluations,
  Jacobian evaluations, LU decompositions and the final error, on
  - Van der Pol, mu = 1000, y(0) = (2, 0), t in [0, 3000] (atol = rtol);
  - Robertson to t = 1e5 (atol = 1e-8 rtol) and to t = 1e11 (atol = 1e-10 rtol);
  - HIRES on [0, 321.8122] and OREGO on [0, 360] (atol = rtol);
* reference final states: the Test Set for IVP Solvers (Mazzia & Magherini, Bari) where it has
  one (Robertson at 1e11, HIRES, OREGO); otherwise scipy's Radau at rtol = atol·... = 1e-13
  (Van der Pol at 3000, Robertson at 1e5), cross-checked against LSODA at 1e-12.

Usage: pip install scipy; python3 scripts/scipy_stiff_reference.py > tests/data/stiff_reference.json
"""

import json

import numpy as np
import scipy
from scipy.integrate import solve_ivp

MU = 1000.0


def vdp(t, y):
    return [y[1], MU * (1 - y[0] ** 2) * y[1] - y[0]]


def vdp_jac(t, y):
    return [[0.0, 1.0], [-2 * MU * y[0] * y[1] - 1, MU * (1 - y[0] ** 2)]]


K1, K2, K3 = 0.04, 3e7, 1e4


def rober(t, y):
    return [
        -K1 * y[0] + K3 * y[1] * y[2],
        K1 * y[0] - K3 * y[1] * y[2] - K2 * y[1] ** 2,
        K2 * y[1] ** 2,
    ]


def rober_jac(t, y):
    return [
        [-K1, K3 * y[2], K3 * y[1]],
        [K1, -K3 * y[2] - 2 * K2 * y[1], -K3 * y[1]],
        [0.0, 2 * K2 * y[1], 0.0],
    ]


def hires(t, y):
    y1, y2, y3, y4, y5, y6, y7, y8 = y
    return [
        -1.71 * y1 + 0.43 * y2 + 8.32 * y3 + 0.0007,
        1.71 * y1 - 8.75 * y2,
        -10.03 * y3 + 0.43 * y4 + 0.035 * y5,
        8.32 * y2 + 1.71 * y3 - 1.12 * y4,
        -1.745 * y5 + 0.43 * y6 + 0.43 * y7,
        -280 * y6 * y8 + 0.69 * y4 + 1.71 * y5 - 0.43 * y6 + 0.69 * y7,
        280 * y6 * y8 - 1.81 * y7,
        -280 * y6 * y8 + 1.81 * y7,
    ]


def hires_jac(t, y):
    j = np.zeros((8, 8))
    j[0, 0], j[0, 1], j[0, 2] = -1.71, 0.43, 8.32
    j[1, 0], j[1, 1] = 1.71, -8.75
    j[2, 2], j[2, 3], j[2, 4] = -10.03, 0.43, 0.035
    j[3, 1], j[3, 2], j[3, 3] = 8.32, 1.71, -1.12
    j[4, 4], j[4, 5], j[4, 6] = -1.745, 0.43, 0.43
    j[5, 3], j[5, 4], j[5, 5], j[5, 6], j[5, 7] = 0.69, 1.71, -0.43 - 280 * y[7], 0.69, -280 * y[5]
    j[6, 5], j[6, 6], j[6, 7] = 280 * y[7], -1.81, 280 * y[5]
    j[7, 5], j[7, 6], j[7, 7] = -280 * y[7], 1.81, -280 * y[5]
    return j


def orego(t, y):
    return [
        77.27 * (y[1] + y[0] * (1 - 8.375e-6 * y[0] - y[1])),
        (y[2] - (1 + y[0]) * y[1]) / 77.27,
        0.161 * (y[0] - y[2]),
    ]


def orego_jac(t, y):
    return [
        [77.27 * (1 - 2 * 8.375e-6 * y[0] - y[1]), 77.27 * (1 - y[0]), 0.0],
        [-y[1] / 77.27, -(1 + y[0]) / 77.27, 1 / 77.27],
        [0.161, 0.0, -0.161],
    ]


def run(f, jac, y0, t_end, method, rtol, atol):
    s = solve_ivp(f, (0.0, t_end), y0, method=method, rtol=rtol, atol=atol, jac=jac)
    return s


def tight(f, jac, y0, t_end, atol_scale):
    a = run(f, jac, y0, t_end, "Radau", 1e-13, 1e-13 * atol_scale)
    b = run(f, jac, y0, t_end, "LSODA", 1e-12, 1e-12 * atol_scale)
    ya, yb = a.y[:, -1], b.y[:, -1]
    return ya.tolist(), float(np.max(np.abs(ya - yb) / np.abs(ya)))


def counts(f, jac, y0, t_end, ref, tols, atol_scale):
    rows = []
    ref = np.array(ref)
    for method in ["Radau", "BDF", "LSODA"]:
        for rtol in tols:
            s = run(f, jac, y0, t_end, method, rtol, rtol * atol_scale)
            y = s.y[:, -1]
            rows.append(
                {
                    "method": method,
                    "rtol": rtol,
                    "atol": rtol * atol_scale,
                    "success": bool(s.success),
                    "nfev": int(s.nfev),
                    "njev": int(s.njev),
                    "nlu": int(s.nlu),
                    "max_rel_error": float(np.max(np.abs(y - ref) / np.abs(ref))),
                }
            )
    return rows


def main():
    out = {"scipy": scipy.__version__, "numpy": np.__version__, "problems": {}}
    tols = [1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10]
    cases = []
    ref, agree = tight(vdp, vdp_jac, [2.0, 0.0], 3000.0, 1.0)
    cases.append(("vanderpol-1000", vdp, vdp_jac, [2.0, 0.0], 3000.0, ref, "scipy Radau 1e-13", agree, 1.0, [1e-4, 1e-6, 1e-8]))
    ref, agree = tight(rober, rober_jac, [1.0, 0.0, 0.0], 1e5, 1e-8)
    cases.append(("robertson-1e5", rober, rober_jac, [1.0, 0.0, 0.0], 1e5, ref, "scipy Radau 1e-13", agree, 1e-8, tols))
    cases.append(("robertson-1e11", rober, rober_jac, [1.0, 0.0, 0.0], 1e11,
                  [0.2083340149701255e-7, 0.8333360770334713e-13, 0.9999999791665050], "test set", None, 1e-10, tols))
    cases.append(("hires", hires, hires_jac, [1, 0, 0, 0, 0, 0, 0, 0.0057], 321.8122,
                  [0.7371312573325668e-3, 0.1442485726316185e-3, 0.5888729740967575e-4, 0.1175651343283149e-2,
                   0.2386356198831331e-2, 0.6238968252742796e-2, 0.2849998395185769e-2, 0.2850001604814231e-2],
                  "test set", None, 1.0, tols))
    cases.append(("orego", orego, orego_jac, [1.0, 2.0, 3.0], 360.0,
                  [0.1000814870318523e1, 0.1228178521549917e4, 0.1320554942846706e3], "test set", None, 1.0, tols))
    for name, f, jac, y0, t_end, ref, source, agree, atol_scale, ts in cases:
        out["problems"][name] = {
            "t_end": t_end,
            "reference": ref,
            "reference_source": source,
            "reference_vs_lsoda_1e-12": agree,
            "atol_over_rtol": atol_scale,
            "runs": counts(f, jac, y0, t_end, ref, ts, atol_scale),
        }
    json.dump(out, __import__("sys").stdout, indent=1)


if __name__ == "__main__":
    main()
