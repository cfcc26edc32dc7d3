//! The fixed-size fast path (`ode::fixed`) against the general RK4: the same trajectory bit for
//! bit, the same work and outcome, and a measured order of 4.

use std::f64::consts::TAU;

use lectern::ode::fixed::AsSystem;
use lectern::ode::problem::Problem;
use lectern::ode::study::{loglog_slope, max_error};
use lectern::ode::{
    FixedFn, FixedSystem, Method, Outcome, Solution, solve_fixed, solve_fixed_n, solve_fixed_n_with,
};

fn oscillator() -> impl FixedSystem<2> + Copy {
    FixedFn(|_t: f64, x: &[f64; 2]| [x[1], -x[0]])
}

fn kepler() -> impl FixedSystem<4> + Copy {
    FixedFn(|_t: f64, x: &[f64; 4]| {
        let r2 = x[0] * x[0] + x[1] * x[1];
        let r3 = r2 * r2.sqrt();
        [x[2], x[3], -x[0] / r3, -x[1] / r3]
    })
}

/// Runs both paths and asserts identical times, states (bit for bit), work and outcome.
fn assert_same_trajectory<const N: usize>(
    sys: impl FixedSystem<N> + Copy,
    x0: [f64; N],
    h: f64,
    t_end: f64,
    bound: f64,
) -> Solution {
    let general = solve_fixed(
        &AsSystem::<N, _>(sys),
        Method::Rk4,
        0.0,
        &x0,
        h,
        t_end,
        bound,
    );
    let mut ts = vec![0.0];
    let mut xs = x0.to_vec();
    let fast = solve_fixed_n_with(&sys, 0.0, x0, h, t_end, bound, |t, x| {
        ts.push(t);
        xs.extend_from_slice(x);
    });
    assert_eq!(fast.outcome, general.outcome);
    assert_eq!(fast.steps, general.steps);
    assert_eq!(fast.f_evals, general.f_evals);
    assert_eq!(ts, general.ts);
    let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    assert_eq!(bits(&xs), bits(&general.xs), "states differ");
    let (t_last, x_last) = general.last();
    assert_eq!(fast.t, t_last);
    assert_eq!(bits(&fast.x), bits(x_last));
    general
}

#[test]
fn fixed_rk4_is_bit_identical_to_the_general_rk4() {
    // whole numbers of steps, and an h that needs a shortened last step
    for h in [TAU / 64.0, TAU / 1000.0, 0.0123] {
        let g = assert_same_trajectory(oscillator(), [1.0, 0.0], h, TAU, f64::INFINITY);
        assert!(g.finished() && g.steps > 60);
        let g = assert_same_trajectory(kepler(), [0.4, 0.0, 0.0, 2.0], h, TAU, f64::INFINITY);
        assert!(g.finished());
    }
}

#[test]
fn fixed_rk4_reports_divergence_like_the_general_one() {
    // RK4 on x'' = −x leaves the bound at hω = 3 (beyond its 2.828 limit)
    let g = assert_same_trajectory(oscillator(), [1.0, 0.0], 3.0, 3000.0, 1e6);
    assert!(matches!(g.outcome, Outcome::Diverged { .. }), "{g:?}");
    // h = 1e9 and NaN initial values: data, not a panic
    let g = assert_same_trajectory(oscillator(), [1.0, 0.0], 1e9, 1e10, 1e12);
    assert!(matches!(g.outcome, Outcome::Diverged { .. }), "{g:?}");
    let g = assert_same_trajectory(kepler(), [f64::NAN, 0.0, 0.0, 2.0], 0.1, 1.0, 1e12);
    assert_eq!(g.outcome, Outcome::Diverged { t: 0.0 });
    let fast = solve_fixed_n(&kepler(), 0.0, [0.4, 0.0, 0.0, 2.0], 1e-12, 1e9, 1e12);
    assert!(matches!(fast.outcome, Outcome::Failed { .. }), "{fast:?}");
}

/// Log-log slope of the final error over one period as the step halves.
fn order<const N: usize>(sys: impl FixedSystem<N>, x0: [f64; N], exact: &[f64], n0: usize) -> f64 {
    let points: Vec<(f64, f64)> = (0..4)
        .map(|i| {
            let h = TAU / (n0 << i) as f64;
            let sol = solve_fixed_n(&sys, 0.0, x0, h, TAU, f64::INFINITY);
            assert!(sol.finished());
            (h, max_error(&sol.x, exact))
        })
        .collect();
    let slope = loglog_slope(&points);
    eprintln!("{points:?} slope {slope:.4}");
    slope
}

#[test]
fn fixed_rk4_is_fourth_order_on_oscillator_and_kepler() {
    let osc = order(oscillator(), [1.0, 0.0], &[TAU.cos(), -TAU.sin()], 50);
    assert!((osc - 4.0).abs() < 0.15, "oscillator order {osc}");
    // Kepler e = 0.6 returns to its initial state after one period
    let kep = order(kepler(), [0.4, 0.0, 0.0, 2.0], &[0.4, 0.0, 0.0, 2.0], 1000);
    assert!((kep - 4.0).abs() < 0.15, "Kepler order {kep}");
}

#[test]
fn fixed_path_on_the_native_kepler_matches_the_ron_file_to_round_off() {
    // the shipped expression RHS and the native one describe the same orbit
    let p = Problem::load("slides/problems/kepler.ron").unwrap();
    let h = TAU / 2000.0;
    let general = solve_fixed(&p, Method::Rk4, 0.0, &p.initial, h, TAU, f64::INFINITY);
    let fast = solve_fixed_n(&kepler(), 0.0, [0.4, 0.0, 0.0, 2.0], h, TAU, f64::INFINITY);
    let d = max_error(&fast.x, general.last().1);
    assert!(d < 1e-11, "fast path vs RON expression: {d:e}");
}
