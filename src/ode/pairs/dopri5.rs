//! Dormand–Prince 5(4) (`dopri5`): J. R. Dormand, P. J. Prince, "A family of embedded
//! Runge–Kutta formulae", J. Comput. Appl. Math. 6 (1980) 19–26; Hairer, Nørsett & Wanner,
//! Solving ODEs I, II.5, Table 5.2. Exact rationals, each rounded once to f64.

use super::PairCoefficients;

/// Dormand–Prince 5(4): 7 stages, order 5 with a 4th-order error estimate, first same as last.
pub const DOPRI5: PairCoefficients<7> = PairCoefficients {
    name: "Dormand–Prince 5(4)",
    order: 5,
    est_order: 4,
    fsal: true,
    c: [0.0, 1.0 / 5.0, 3.0 / 10.0, 4.0 / 5.0, 8.0 / 9.0, 1.0, 1.0],
    a: [
        [0.0; 7],
        [1.0 / 5.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
        [3.0 / 40.0, 9.0 / 40.0, 0.0, 0.0, 0.0, 0.0, 0.0],
        [44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0, 0.0, 0.0, 0.0, 0.0],
        [
            19372.0 / 6561.0,
            -25360.0 / 2187.0,
            64448.0 / 6561.0,
            -212.0 / 729.0,
            0.0,
            0.0,
            0.0,
        ],
        [
            9017.0 / 3168.0,
            -355.0 / 33.0,
            46732.0 / 5247.0,
            49.0 / 176.0,
            -5103.0 / 18656.0,
            0.0,
            0.0,
        ],
        B,
    ],
    b: B,
    // fifth- minus fourth-order weights
    e: [
        71.0 / 57600.0,
        0.0,
        -71.0 / 16695.0,
        71.0 / 1920.0,
        -17253.0 / 339200.0,
        22.0 / 525.0,
        -1.0 / 40.0,
    ],
    e3: None,
};

/// Fifth-order weights (also the last row of `a`: first same as last).
const B: [f64; 7] = [
    35.0 / 384.0,
    0.0,
    500.0 / 1113.0,
    125.0 / 192.0,
    -2187.0 / 6784.0,
    11.0 / 84.0,
    0.0,
];
