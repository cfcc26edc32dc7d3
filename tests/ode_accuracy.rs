//! Accuracy and stability of the integrators, measured on the shipped problem files.
//! Every expected number comes from a float64 reference computation (see comments).

use std::f64::consts::PI;

use lectern::ode::problem::Problem;
use lectern::ode::study::{convergence, max_error, reference};
use lectern::ode::{
    Adaptive, FnSystem, Method, Outcome, Scheme, Stepper, Tableau, solve_adaptive, solve_fixed,
    solve_fixed_final, solve_implicit_adaptive,
};

fn problem(name: &str) -> Problem {
    Problem::load(format!("slides/problems/{name}.ron")).unwrap()
}

fn tableau(name: &str) -> Tableau {
    Tableau::load(format!("slides/tableaux/{name}.ron")).unwrap()
}

/// Step sizes for the convergence runs: n0, 2 n0, 4 n0, … steps per period.
fn hs(n0: usize, count: usize) -> Vec<f64> {
    (0..count).map(|i| 2.0 * PI / (n0 << i) as f64).collect()
}

fn measured_order(p: &Problem, scheme: Scheme<'_>, n0: usize) -> f64 {
    // one period: the oscillator's exact solution, Kepler's initial state
    let t_end = 2.0 * PI;
    let exact = p.exact(t_end).unwrap_or_else(|| p.initial.clone());
    let c = convergence(p, scheme, p.t0, &p.initial, t_end, &exact, &hs(n0, 4));
    eprintln!(
        "{} / {}: {:?} slope {:.4}",
        p.name,
        scheme.label(),
        c.points,
        c.slope
    );
    c.slope
}

#[test]
fn convergence_orders_on_oscillator_and_kepler() {
    let osc = problem("harmonic");
    let kep = problem("kepler");
    let rk4 = tableau("rk4");
    for (p, n_euler, n_mid, n_rk4) in [(&osc, 2000, 200, 50), (&kep, 200_000, 4000, 1000)] {
        let e = measured_order(p, Scheme::Method(Method::Euler), n_euler);
        assert!((e - 1.0).abs() < 0.1, "{}: Euler order {e}", p.name);
        let m = measured_order(p, Scheme::Method(Method::Midpoint), n_mid);
        assert!((m - 2.0).abs() < 0.1, "{}: midpoint order {m}", p.name);
        let r = measured_order(p, Scheme::Method(Method::Rk4), n_rk4);
        assert!((r - 4.0).abs() < 0.15, "{}: RK4 order {r}", p.name);
        // the same RK4 typed as a tableau file: the same method, summed in another order, so
        // the slopes agree up to round-off at the finest steps
        let rt = measured_order(p, Scheme::Tableau(&rk4), n_rk4);
        assert!(
            (rt - r).abs() < 1e-2,
            "{}: RK4 tableau order {rt} vs {r}",
            p.name
        );
    }
}

#[test]
fn the_notes_typo_rk4_is_not_fourth_order() {
    let typo = tableau("rk4-typo");
    assert_eq!(typo.order(), 1);
    assert_eq!(tableau("rk4").order(), 4);
    for (p, n) in [(problem("harmonic"), 200), (problem("kepler"), 4000)] {
        let order = measured_order(&p, Scheme::Tableau(&typo), n);
        assert!(order < 1.2, "{}: typo'd RK4 measured order {order}", p.name);
    }
}

#[test]
fn other_shipped_tableaux_have_their_orders() {
    let osc = problem("harmonic");
    for (name, order) in [("ralston", 2.0), ("kutta3", 3.0), ("three-eighths", 4.0)] {
        let t = tableau(name);
        assert_eq!(t.order() as f64, order, "{name}");
        let measured = measured_order(&osc, Scheme::Tableau(&t), 100);
        assert!((measured - order).abs() < 0.15, "{name}: {measured}");
    }
}

#[test]
fn dormand_prince_error_falls_with_tolerance() {
    let kep = problem("kepler");
    let mut last = (f64::INFINITY, 0u64);
    for tol in [1e-4, 1e-6, 1e-8, 1e-10] {
        let opts = Adaptive {
            rtol: tol,
            atol: tol,
            ..Adaptive::default()
        };
        let sol = solve_adaptive(&kep, 0.0, &kep.initial, 2.0 * PI, opts);
        assert!(sol.finished());
        let err = max_error(sol.last().1, &kep.initial);
        eprintln!(
            "dopri5 tol {tol:e}: error {err:.3e}, {} f-evals, {} accepted, {} rejected",
            sol.f_evals, sol.steps, sol.rejected
        );
        assert!(
            err < last.0 / 5.0,
            "tol {tol}: error {err} did not fall from {}",
            last.0
        );
        assert!(sol.f_evals > last.1);
        assert!(err < 1e3 * tol, "tol {tol}: error {err}");
        last = (err, sol.f_evals);
    }
}

/// Radius of the oscillator's state after `steps` steps of size h.
fn radius_after(method: Method, h: f64, steps: usize) -> f64 {
    let osc = problem("harmonic");
    let sol = solve_fixed_final(
        &osc,
        Scheme::Method(method),
        0.0,
        &[1.0, 0.0],
        h,
        h * steps as f64,
        f64::INFINITY,
    );
    let x = sol.last().1;
    x[0].hypot(x[1])
}

#[test]
fn rk4_stability_limit_on_the_imaginary_and_real_axes() {
    // |R(iy)| for RK4 crosses 1 at y = 2√2 = 2.8284
    let r_in = radius_after(Method::Rk4, 2.82, 2000);
    let r_out = radius_after(Method::Rk4, 2.83, 2000);
    eprintln!("RK4 radius after 2000 steps: hω = 2.82 → {r_in:.6}, 2.83 → {r_out:.6}");
    assert!(r_in <= 1.0, "hω = 2.82 must stay bounded, radius {r_in}");
    assert!(r_out > 1.01, "hω = 2.83 must grow, radius {r_out}");
    let limit = Tableau::rk4().real_axis_limit();
    eprintln!("RK4 real-axis limit {limit:.6}");
    assert!((limit + 2.7853).abs() < 1e-4, "real-axis limit {limit}");
    assert!((tableau("rk4").real_axis_limit() - limit).abs() < 1e-9);
    assert!((Tableau::euler().real_axis_limit() + 2.0).abs() < 1e-9);
}

#[test]
fn euler_spirals_out_by_sqrt_one_plus_h2w2_per_step() {
    let osc = problem("harmonic");
    let h = 0.1;
    let sol = solve_fixed(&osc, Method::Euler, 0.0, &[1.0, 0.0], h, 63.0 * h, 1e12);
    assert_eq!(sol.steps, 63);
    let growth = (1.0 + h * h).sqrt();
    for i in 1..sol.len() {
        let (a, b) = (sol.state(i - 1), sol.state(i));
        let ratio = b[0].hypot(b[1]) / a[0].hypot(a[1]);
        assert!((ratio - growth).abs() < 1e-14, "step {i}: {ratio}");
    }
    let r = sol.last().1[0].hypot(sol.last().1[1]);
    eprintln!("Euler radius after 63 steps of h = 0.1: {r:.6}");
    assert!((r - 1.3681).abs() < 1e-4, "radius after one revolution {r}");
}

#[test]
fn euler_on_fast_decay_is_stable_only_below_two_over_lambda() {
    let p = problem("dahlquist"); // λ = −100
    let run = |h: f64| {
        let sol = solve_fixed(&p, Method::Euler, 0.0, &[1.0], h, 200.0 * h, 1e12);
        sol.last().1[0].abs()
    };
    assert!(run(0.019) < 1e-8, "h = 0.019 must decay");
    assert!(run(0.021) > 1e8, "h = 0.021 must grow");
}

#[test]
fn symplectic_euler_keeps_energy_bounded_at_h_omega_1_9() {
    let osc = problem("harmonic");
    let h = 1.9;
    let periods = 1000.0;
    let energy = |x: &[f64]| 0.5 * (x[0] * x[0] + x[1] * x[1]);
    let e0 = energy(&osc.initial);
    let max_dev = |m: Method| {
        let sol = solve_fixed(&osc, m, 0.0, &osc.initial, h, periods * 2.0 * PI, 1e12);
        let devs: Vec<f64> = (0..sol.len())
            .map(|i| (energy(sol.state(i)) - e0).abs() / e0)
            .collect();
        let tenth = devs.len() / 10;
        let first = devs[..tenth].iter().cloned().fold(0.0, f64::max);
        let last = devs[devs.len() - tenth..]
            .iter()
            .cloned()
            .fold(0.0, f64::max);
        (sol.outcome, first, last)
    };
    let (outcome, first, last) = max_dev(Method::SymplecticEuler);
    eprintln!(
        "symplectic Euler hω = 1.9: max relative energy error first 100 periods {first:.4}, last 100 {last:.4}"
    );
    assert_eq!(outcome, Outcome::Finished);
    assert!(
        last <= first * 1.001 && last < 20.0,
        "energy error grows: {first} → {last}"
    );
    // explicit Euler at the same h leaves for Neptune
    let (outcome, _, _) = max_dev(Method::Euler);
    assert!(matches!(outcome, Outcome::Diverged { .. }), "{outcome:?}");
}

/// The first `count` times θ crosses zero downwards, refined to full RK4 accuracy by
/// bisecting the length of a final partial step.
fn pendulum_crossings(p: &Problem, h: f64, count: usize) -> Vec<f64> {
    let mut stepper = Stepper::new(Method::Rk4, 2);
    let mut x = p.initial.clone();
    let mut t = 0.0;
    let mut out = Vec::new();
    while out.len() < count {
        let mut y = x.clone();
        stepper.step(p, t, &mut y, h).unwrap();
        if x[0] > 0.0 && y[0] <= 0.0 {
            let (mut lo, mut hi) = (0.0, h);
            for _ in 0..60 {
                let mid = 0.5 * (lo + hi);
                let mut z = x.clone();
                stepper.step(p, t, &mut z, mid).unwrap();
                if z[0] > 0.0 { lo = mid } else { hi = mid }
            }
            out.push(t + 0.5 * (lo + hi));
        }
        x = y;
        t += h;
    }
    out
}

#[test]
fn pendulum_from_179_degrees_has_period_3_90107_times_2pi() {
    // T / 2π = 1 / AGM(1, cos(θ0/2)) = 3.901065160 for θ0 = 179°, g/L = 1
    let p = problem("pendulum");
    let c = pendulum_crossings(&p, 1e-3, 2);
    // θ falls through zero going down at T/4; the next downward crossing is one period later
    let period = c[1] - c[0];
    let ratio = period / (2.0 * PI);
    eprintln!("pendulum period / 2π = {ratio:.8}");
    assert!((ratio - 3.90107).abs() < 1e-4, "{ratio}");
    assert!((ratio - 3.901065160389089).abs() < 1e-7, "{ratio}");
}

#[test]
fn implicit_euler_is_stable_on_very_stiff_decay() {
    let sys = FnSystem::new(1, |_t, x: &[f64], d: &mut [f64]| d[0] = -1e6 * x[0]);
    let sol = solve_fixed(&sys, Method::ImplicitEuler, 0.0, &[1.0], 0.1, 10.0, 1e12);
    assert_eq!(sol.outcome, Outcome::Finished);
    for i in 1..sol.len() {
        let (a, b) = (sol.state(i - 1)[0], sol.state(i)[0]);
        assert!(b.abs() <= a.abs() && b >= 0.0, "step {i}: {a} → {b}");
    }
    assert!((sol.state(1)[0] - 1.0 / (1.0 + 1e5)).abs() < 1e-15);
    let implicit_mid = solve_fixed(&sys, Method::ImplicitMidpoint, 0.0, &[1.0], 0.1, 10.0, 1e12);
    assert_eq!(implicit_mid.outcome, Outcome::Finished);
    assert!(implicit_mid.last().1[0].abs() <= 1.0);
    let explicit = solve_fixed(&sys, Method::Euler, 0.0, &[1.0], 0.1, 10.0, 1e12);
    assert!(matches!(explicit.outcome, Outcome::Diverged { .. }));
}

#[test]
fn stiff_van_der_pol_implicit_vs_explicit_work() {
    let p = problem("vanderpol");
    let want = [1.70617, -0.89281];
    let mut implicit_evals = Vec::new();
    // step-doubling control lets the implicit methods cross the two jumps with small steps
    // and stride along the slow manifold (fixed steps ≫ ε land on spurious roots there)
    for (m, tol, max_err) in [
        (Method::ImplicitEuler, 1e-5, 1e-2),
        (Method::ImplicitMidpoint, 1e-5, 1e-3),
    ] {
        let opts = Adaptive {
            rtol: tol,
            atol: tol,
            record: false,
            ..Adaptive::default()
        };
        let sol = solve_implicit_adaptive(&p, m, 0.0, &p.initial, 2.0, opts);
        assert_eq!(sol.outcome, Outcome::Finished, "{m}");
        let x = sol.last().1;
        eprintln!(
            "{m} tol = {tol:e}: y(2) = {x:?}, {} f-evals, {} steps, {} rejected",
            sol.f_evals, sol.steps, sol.rejected
        );
        assert!(max_error(x, &want) < max_err, "{m}: y(2) = {x:?}");
        implicit_evals.push(sol.f_evals);
    }
    let opts = Adaptive {
        rtol: 1e-6,
        atol: 1e-6,
        record: false,
        ..Adaptive::default()
    };
    let explicit = solve_adaptive(&p, 0.0, &p.initial, 2.0, opts);
    assert_eq!(explicit.outcome, Outcome::Finished);
    eprintln!(
        "dopri5: y(2) = {:?}, {} f-evals, {} rejected",
        explicit.last().1,
        explicit.f_evals,
        explicit.rejected
    );
    assert!(max_error(explicit.last().1, &want) < 1e-4);
    let ratios: Vec<f64> = implicit_evals
        .iter()
        .map(|&n| explicit.f_evals as f64 / n as f64)
        .collect();
    eprintln!(
        "explicit / implicit f-evaluations (implicit Euler, implicit midpoint): {ratios:.1?}"
    );
    assert!(
        ratios[0] > 20.0,
        "explicit needs only {}× implicit Euler's work",
        ratios[0]
    );
    assert!(
        ratios[1] > 100.0,
        "explicit needs only {}× implicit midpoint's work",
        ratios[1]
    );
    // fixed-step RK4 at the implicit step diverges outright
    let rk4 = solve_fixed_final(
        &p,
        Scheme::Method(Method::Rk4),
        0.0,
        &p.initial,
        1e-3,
        2.0,
        1e12,
    );
    assert!(
        matches!(rk4.outcome, Outcome::Diverged { .. }),
        "{:?}",
        rk4.outcome
    );
}

#[test]
fn verlet_is_second_order_and_reference_agrees() {
    let kep = problem("kepler");
    let exact = kep.initial.clone();
    let c = convergence(
        &kep,
        Scheme::Method(Method::Verlet),
        0.0,
        &kep.initial,
        2.0 * PI,
        &exact,
        &hs(4000, 4),
    );
    assert!((c.slope - 2.0).abs() < 0.1, "Verlet order {}", c.slope);
    // symplectic Euler: at whole periods its error cancels to second order (it is conjugate
    // to a second-order method), so measure at t = 1 against a reference
    let r1 = reference(&kep, 0.0, &kep.initial, 1.0);
    let hs1: Vec<f64> = (0..3).map(|i| 1.0 / (20_000 << i) as f64).collect();
    let c = convergence(
        &kep,
        Scheme::Method(Method::SymplecticEuler),
        0.0,
        &kep.initial,
        1.0,
        &r1,
        &hs1,
    );
    eprintln!(
        "symplectic Euler on Kepler to t = 1: {:?} slope {:.4}",
        c.points, c.slope
    );
    assert!(
        (c.slope - 1.0).abs() < 0.1,
        "symplectic Euler order {}",
        c.slope
    );
    let r = reference(&kep, 0.0, &kep.initial, 2.0 * PI);
    assert!(max_error(&r, &exact) < 1e-10, "{r:?}");
}
