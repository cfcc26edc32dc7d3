//! The stiff solvers (`ode::stiff`: rodas5p, radau5) and what they stand on: one step on
//! y' = λy against the stability function, L- and A-stability, orders measured on
//! non-autonomous and nonlinear problems, the symbolic Jacobian against finite differences,
//! the hard cases (Robertson to 1e11, Van der Pol μ = 1000) against the Test Set's and
//! scipy's values (`tests/data/stiff_reference.json`, made by
//! `scripts/scipy_stiff_reference.py`), the stiffness test of the explicit pairs, and bad input.

use std::time::Instant;

use lectern::ode::native::{Robertson, VanDerPol};
use lectern::ode::problem::Problem;
use lectern::ode::study::loglog_slope;
use lectern::ode::{
    Adaptive, FnSystem, Method, Outcome, Scheme, System, solve_embedded, solve_fixed,
    solve_fixed_final,
};

const STIFF: [Method; 2] = [Method::Rodas5p, Method::Radau5];

fn reference() -> serde_json::Value {
    let text = std::fs::read_to_string("tests/data/stiff_reference.json").unwrap();
    serde_json::from_str(&text).unwrap()
}

fn floats(v: &serde_json::Value) -> Vec<f64> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

fn opts(rtol: f64, atol: f64) -> Adaptive {
    Adaptive {
        rtol,
        atol,
        record: false,
        ..Adaptive::default()
    }
}

fn problem(name: &str) -> Problem {
    Problem::load(format!("slides/problems/{name}.ron")).unwrap()
}

/// y' = λy for complex λ = a + ib as the real system (u, v)' = (au − bv, bu + av).
struct Complex1 {
    a: f64,
    b: f64,
}

impl System for Complex1 {
    fn dim(&self) -> usize {
        2
    }
    fn rhs(&self, _t: f64, x: &[f64], d: &mut [f64]) {
        d[0] = self.a * x[0] - self.b * x[1];
        d[1] = self.b * x[0] + self.a * x[1];
    }
    fn jacobian(&self, _t: f64, _x: &[f64], j: &mut [f64]) -> bool {
        j.copy_from_slice(&[self.a, -self.b, self.b, self.a]);
        true
    }
}

/// One step of h = 1 from 1 multiplies by R(z), to 1e-14 (relative to max(|R|, 1)) over a grid
/// of z with −20 ≤ Re z ≤ 0, |Im z| ≤ 15; Rodas5P to
/// 5e-14, as its transformed coefficients (up to 165 in size) amplify round-off in the stage
/// sums: the real-system step and the complex recurrence differ by ~1.3e-14 already at |z| ≈ 6.
#[test]
fn one_step_on_dahlquist_is_the_stability_function() {
    let methods = [
        Method::Rodas5p,
        Method::Radau5,
        Method::ImplicitEuler,
        Method::ImplicitMidpoint,
    ];
    for m in methods {
        let mut worst = 0.0f64;
        for i in 0..=20 {
            for j in -10..=10 {
                let z = (-20.0 + i as f64, 1.5 * j as f64);
                let sys = Complex1 { a: z.0, b: z.1 };
                let sol = solve_fixed(&sys, m, 0.0, &[1.0, 0.0], 1.0, 1.0, f64::INFINITY);
                assert!(sol.finished(), "{m} at {z:?}: {}", sol.outcome);
                let (_, y) = sol.last();
                let r = m.stability(z).unwrap();
                let size = r.0.hypot(r.1).max(1.0);
                let e = (y[0] - r.0).hypot(y[1] - r.1) / size;
                worst = worst.max(e);
                let limit = if m == Method::Rodas5p { 5e-14 } else { 1e-14 };
                assert!(e < limit, "{m} at z = {z:?}: step {y:?}, R = {r:?} ({e:e})");
            }
        }
        eprintln!("{m}: worst relative difference {worst:.1e}");
    }
}

/// L-stable: |R(−1e8)| < 1e-6 (and R → 0 along the axis); A-stable: |R| ≤ 1 on the imaginary
/// axis and in the left half-plane; accurate: R(z) − e^z = O(z⁶) (order 5).
#[test]
fn stiff_methods_are_l_stable_and_fifth_order_at_the_origin() {
    for m in STIFF {
        let r = m.stability((-1e8, 0.0)).unwrap();
        assert!(r.0.hypot(r.1) < 1e-6, "{m}: R(-1e8) = {r:?}");
        for k in 0..2000 {
            let y = (k as f64 - 1000.0) * 0.05;
            for x in [0.0, -0.01, -1.0, -30.0] {
                let r = m.stability((x, y)).unwrap();
                assert!(
                    r.0.hypot(r.1) <= 1.0 + 1e-13,
                    "{m}: |R({x} + {y}i)| = {}",
                    r.0.hypot(r.1)
                );
            }
        }
        let err = |s: f64| {
            let z = (-s, 0.5 * s);
            let r = m.stability(z).unwrap();
            let e = (z.0.exp() * z.1.cos(), z.0.exp() * z.1.sin());
            (r.0 - e.0).hypot(r.1 - e.1)
        };
        for s in [0.4, 0.2, 0.1, 0.05, 0.025] {
            eprintln!(
                "{m}: |R(z) - e^z| at |z| = {:.3}: {:.3e}",
                s * 1.25f64.sqrt(),
                err(s)
            );
        }
        // at least order 5 (slope 6); Rodas5P's R matches e^z one order further (slope ≈ 6.8)
        let slope = (err(0.2) / err(0.1)).log2();
        assert!(
            (5.8..7.3).contains(&slope),
            "{m}: local error slope {slope}"
        );
    }
    // implicit Euler damps everything stiff, implicit midpoint keeps |R| = 1 at ∞
    let r = Method::ImplicitMidpoint.stability((-1e8, 0.0)).unwrap();
    assert!((r.0.hypot(r.1) - 1.0).abs() < 1e-6);
}

/// Prothero–Robinson y' = λ(y − sin t) + cos t, y(0) = 0 (exact: sin t), non-autonomous: a
/// Rosenbrock method without its ∂f/∂t term loses its order here.
fn prothero_robinson(lambda: f64) -> Problem {
    let text = format!(
        r#"(vars: ["y"], rhs: ["lambda*(y - sin(t)) + cos(t)"], params: {{"lambda": {lambda:e}}},
            initial: [0.0], exact: Some(["sin(t)"]))"#
    );
    Problem::parse(&text, "pr.ron").unwrap()
}

fn fixed_errors(
    sys: &dyn System,
    m: Method,
    x0: &[f64],
    t_end: f64,
    exact: &[f64],
    ns: &[usize],
) -> Vec<(f64, f64)> {
    ns.iter()
        .map(|&n| {
            let h = t_end / n as f64;
            let sol = solve_fixed_final(sys, Scheme::Method(m), 0.0, x0, h, t_end, f64::INFINITY);
            assert!(sol.finished(), "{m} h = {h}: {}", sol.outcome);
            let e = sol
                .last()
                .1
                .iter()
                .zip(exact)
                .map(|(a, b)| (a - b).abs())
                .fold(0.0, f64::max);
            (h, e)
        })
        .collect()
}

#[test]
fn orders_on_prothero_robinson_and_van_der_pol() {
    let t_end = 2.0f64;
    for m in STIFF {
        // non-stiff λ = −1: the classical order 5
        let pr = prothero_robinson(-1.0);
        let exact = [t_end.sin()];
        let pts = fixed_errors(&pr, m, &[0.0], t_end, &exact, &[10, 20, 40, 80]);
        let p = loglog_slope(&pts);
        eprintln!("{m}: PR λ = -1 order {p:.2} {pts:?}");
        assert!((p - 5.0).abs() < 0.4, "{m}: order {p} on PR λ = -1");
        // stiff λ = −1e6: both keep a high order (Rodas5P was built for it; RADAU5's stage
        // order 3 gives at least 3), and small errors
        let pr = prothero_robinson(-1e6);
        let pts = fixed_errors(&pr, m, &[0.0], t_end, &exact, &[10, 20, 40, 80]);
        let p = loglog_slope(&pts);
        eprintln!("{m}: PR λ = -1e6 order {p:.2} {pts:?}");
        assert!(p > 2.8, "{m}: order {p} on PR λ = -1e6");
        assert!(pts[0].1 < 1e-7, "{m}: error {:e} at h = 0.2", pts[0].1);
    }
    // Van der Pol μ = 1 (nonlinear, non-symmetric Jacobian), against a tight DOP853 run
    let vdp = VanDerPol { mu: 1.0 };
    let x0 = [2.0, 0.0];
    let r = solve_embedded(&vdp, Method::Dop853, 0.0, &x0, t_end, opts(1e-14, 1e-14));
    let exact = r.last().1.to_vec();
    for m in STIFF {
        let pts = fixed_errors(&vdp, m, &x0, t_end, &exact, &[20, 40, 80, 160]);
        let p = loglog_slope(&pts);
        eprintln!("{m}: VdP μ = 1 order {p:.2} {pts:?}");
        assert!((p - 5.0).abs() < 0.5, "{m}: order {p} on Van der Pol");
    }
}

/// A Rosenbrock method is exact to its order only with the exact ∂f/∂t: the same problem as a
/// closure (forward differences for J and f_t) reaches the same accuracy, and the differences'
/// f-evaluations are counted: n + 1 more per step.
#[test]
fn difference_jacobians_are_counted_and_agree() {
    let p = prothero_robinson(-1e3);
    let closure = FnSystem::new(1, |t, x: &[f64], d: &mut [f64]| {
        d[0] = -1e3 * (x[0] - t.sin()) + t.cos()
    });
    let exact = solve_fixed(&p, Method::Rodas5p, 0.0, &[0.0], 0.1, 1.0, f64::INFINITY);
    let fd = solve_fixed(
        &closure,
        Method::Rodas5p,
        0.0,
        &[0.0],
        0.1,
        1.0,
        f64::INFINITY,
    );
    assert_eq!(exact.f_evals, 10 * 8);
    assert_eq!(fd.f_evals, 10 * (8 + 1 + 1));
    let (a, b) = (exact.last().1[0], fd.last().1[0]);
    assert!(
        (a - b).abs() < 1e-7 && (a - 1f64.sin()).abs() < 1e-8,
        "{a} {b}"
    );
    // adaptive: Jacobian evaluations reported, one per accepted step for Rodas5P
    let s = solve_embedded(&p, Method::Rodas5p, 0.0, &[0.0], 1.0, opts(1e-8, 1e-10));
    assert!(s.finished());
    assert!(
        s.work.jac_evals as usize >= s.steps && s.work.lu_decomps as usize == s.steps + s.rejected
    );
}

/// Random but deterministic numbers in [lo, hi).
struct Lcg(u64);

impl Lcg {
    fn next(&mut self, lo: f64, hi: f64) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        lo + (hi - lo) * ((self.0 >> 11) as f64 / (1u64 << 53) as f64)
    }
}

/// ∂f/∂x and ∂f/∂t by a 6th-order central difference (truncation ~ h⁶ f⁽⁷⁾, round-off ~ ε|f|/h,
/// both ≲ 1e-11 at h = 2e-3·(1 + |x|) on these problems).
fn fd_derivatives(p: &dyn System, t: f64, x: &[f64]) -> (Vec<f64>, Vec<f64>) {
    let n = x.len();
    let mut jac = vec![0.0; n * n];
    let mut dt = vec![0.0; n];
    let stencil = [
        (-3.0, -1.0 / 60.0),
        (-2.0, 3.0 / 20.0),
        (-1.0, -0.75),
        (1.0, 0.75),
        (2.0, -3.0 / 20.0),
        (3.0, 1.0 / 60.0),
    ];
    let mut f = vec![0.0; n];
    for j in 0..=n {
        let scale = if j == 0 {
            1.0 + t.abs()
        } else {
            1.0 + x[j - 1].abs()
        };
        let h = 2e-3 * scale;
        let mut acc = vec![0.0; n];
        for (k, w) in stencil {
            let mut xs = x.to_vec();
            let mut ts = t;
            if j == 0 {
                ts += k * h;
            } else {
                xs[j - 1] += k * h;
            }
            p.rhs(ts, &xs, &mut f);
            for i in 0..n {
                acc[i] += w * f[i] / h;
            }
        }
        for i in 0..n {
            if j == 0 {
                dt[i] = acc[i];
            } else {
                jac[i * n + j - 1] = acc[i];
            }
        }
    }
    (jac, dt)
}

fn assert_derivatives_match(p: &Problem, t: f64, x: &[f64], what: &str) {
    let n = x.len();
    let (fd_j, fd_t) = fd_derivatives(p, t, x);
    let mut jac = vec![0.0; n * n];
    let mut dt = vec![0.0; n];
    assert!(p.jacobian(t, x, &mut jac) && p.time_derivative(t, x, &mut dt));
    let size = fd_j.iter().chain(&fd_t).fold(1.0f64, |m, v| m.max(v.abs()));
    for (k, (a, b)) in jac
        .iter()
        .zip(&fd_j)
        .chain(dt.iter().zip(&fd_t))
        .enumerate()
    {
        assert!(
            (a - b).abs() <= 1e-8 * size,
            "{what}: entry {k}: symbolic {a:e}, differences {b:e} at t = {t}, x = {x:?}"
        );
    }
}

#[test]
fn symbolic_jacobians_equal_finite_differences_on_every_bundled_problem() {
    let mut rng = Lcg(7);
    let mut files: Vec<_> = std::fs::read_dir("slides/problems")
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "ron"))
        .collect();
    files.sort();
    assert!(files.len() >= 13);
    for path in &files {
        let p = Problem::load(path).unwrap();
        for _ in 0..20 {
            // around the initial state, away from singular points (Kepler's r = 0)
            let x: Vec<f64> = p
                .initial
                .iter()
                .map(|v| v + rng.next(-0.3, 0.3) * (1.0 + v.abs()))
                .collect();
            let t = rng.next(0.0, 3.0);
            assert_derivatives_match(&p, t, &x, &path.display().to_string());
        }
    }
}

/// Random expressions over x, y and t from every operation the compiler knows.
fn random_expr(rng: &mut Lcg, depth: u32) -> String {
    let leaf = |rng: &mut Lcg| match (rng.next(0.0, 5.0)) as u32 {
        0 => "x".to_string(),
        1 => "y".to_string(),
        2 => "t".to_string(),
        3 => format!("{:.3}", rng.next(0.5, 3.0)),
        _ => "x*y".to_string(),
    };
    if depth == 0 {
        return leaf(rng);
    }
    let a = random_expr(rng, depth - 1);
    let b = random_expr(rng, depth - 1);
    match (rng.next(0.0, 14.0)) as u32 {
        0 => format!("({a} + {b})"),
        1 => format!("({a} - {b})"),
        2 => format!("({a} * {b})"),
        3 => format!("({a} / (2 + sin({b})))"),
        4 => format!("sin({a})"),
        5 => format!("cos({a})*{b}"),
        6 => format!("exp(0.3*sin({a}))"),
        7 => format!("ln(2 + cos({a}))"),
        8 => format!("sqrt(1.5 + sin({a}))"),
        9 => format!("(1.5 + cos({a}))^(1.5 + 0.5*sin({b}))"),
        10 => format!("atan2({a}, 2 + cos({b}))"),
        11 => format!("({a})^3 - abs({b} + 0.37)"),
        12 => format!("tan(0.3*sin({a}))"),
        _ => format!("max({a}, 0.61) + min({b}, -0.43) + pow(1.2 + sin({a}), 2)"),
    }
}

#[test]
fn symbolic_jacobians_of_random_expressions_equal_finite_differences() {
    let mut rng = Lcg(2026);
    for k in 0..300 {
        let (e1, e2) = (random_expr(&mut rng, 3), random_expr(&mut rng, 2));
        let text = format!(r#"(vars: ["x", "y"], rhs: ["{e1}", "{e2}"], initial: [0.5, -0.5])"#);
        let p = Problem::parse(&text, "random.ron").unwrap();
        for _ in 0..5 {
            let x = [rng.next(-1.5, 1.5), rng.next(-1.5, 1.5)];
            // |·|, min and max are not differentiable at their kinks: keep clear of them
            let near_kink = [x[0], x[1], x[0] * x[1]].iter().any(|v| {
                (v + 0.37).abs() < 0.1 || (v - 0.61).abs() < 0.1 || (v + 0.43).abs() < 0.1
            });
            if !near_kink && !text.contains("max") && !text.contains("abs") {
                assert_derivatives_match(&p, rng.next(0.0, 2.0), &x, &format!("#{k}: {e1}; {e2}"));
            }
        }
    }
}

#[test]
fn robertson_to_1e11_matches_the_test_set_and_conserves_mass() {
    let reference = reference();
    let r = &reference["problems"]["robertson-1e11"];
    let y_ref = floats(&r["reference"]);
    let files = problem("robertson");
    let native = Robertson::default();
    let systems: [(&str, &dyn System); 2] = [("file", &files), ("native", &native)];
    for (what, sys) in systems {
        for m in STIFF {
            let rtol = 1e-6;
            let start = Instant::now();
            let s = solve_embedded(sys, m, 0.0, &[1.0, 0.0, 0.0], 1e11, opts(rtol, 1e-12));
            let secs = start.elapsed().as_secs_f64();
            assert!(s.finished(), "{m}: {}", s.outcome);
            let y = s.last().1;
            for i in 0..3 {
                let rel = (y[i] - y_ref[i]).abs() / y_ref[i];
                assert!(
                    rel < 10.0 * rtol,
                    "{m} ({what}): y{} = {:e}, reference {:e} ({rel:e})",
                    i + 1,
                    y[i],
                    y_ref[i]
                );
            }
            let mass = y.iter().sum::<f64>() - 1.0;
            assert!(mass.abs() < 1e-12, "{m}: y1 + y2 + y3 - 1 = {mass:e}");
            eprintln!(
                "{m} ({what}): {} f, {} J, {} LU, {} steps ({} rejected) in {secs:.4} s",
                s.f_evals, s.work.jac_evals, s.work.lu_decomps, s.steps, s.rejected
            );
        }
    }
}

/// Van der Pol μ = 1000 on [0, 3000] at rtol = atol = 1e-6: the final state to the reference's
/// tolerance-proportional accuracy in at most 3e4 f-evaluations (scipy's Radau: 7702 with
/// its analytic Jacobian; DOPRI5 needs about 1e7).
#[test]
fn van_der_pol_mu_1000_is_cheap_and_right() {
    let reference = reference();
    let r = &reference["problems"]["vanderpol-1000"];
    let y_ref = floats(&r["reference"]);
    let scipy_radau = r["runs"]
        .as_array()
        .unwrap()
        .iter()
        .find(|row| row["method"] == "Radau" && row["rtol"].as_f64() == Some(1e-6))
        .unwrap()["nfev"]
        .as_u64()
        .unwrap();
    let p = problem("vanderpol-1000");
    for m in STIFF {
        let s = solve_embedded(&p, m, 0.0, &p.initial, 3000.0, opts(1e-6, 1e-6));
        assert!(s.finished(), "{m}: {}", s.outcome);
        let y = s.last().1;
        let err = (y[0] - y_ref[0]).abs() / y_ref[0].abs();
        eprintln!(
            "{m}: {} f ({} J, {} LU), error {err:.1e}; scipy Radau {scipy_radau} f",
            s.f_evals, s.work.jac_evals, s.work.lu_decomps
        );
        assert!(s.f_evals <= 30_000, "{m}: {} f-evaluations", s.f_evals);
        assert!(
            err < 1e-3,
            "{m}: y1(3000) = {}, reference {}",
            y[0],
            y_ref[0]
        );
    }
}

fn stiff_opts() -> Adaptive {
    Adaptive {
        stop_if_stiff: true,
        ..opts(1e-6, 1e-9)
    }
}

/// Hairer's test fires on Robertson and on Van der Pol μ = 1000 within a second (about a
/// thousand steps), with the time it happened, and never on the non-stiff problems.
#[test]
fn explicit_pairs_report_stiffness_on_stiff_problems_only() {
    for m in [Method::Dopri5, Method::Dop853] {
        for (name, t_end) in [
            ("robertson", 1e5),
            ("vanderpol-1000", 3000.0),
            ("vanderpol", 2.0),
        ] {
            let p = problem(name);
            let start = Instant::now();
            let s = solve_embedded(&p, m, 0.0, &p.initial, t_end, stiff_opts());
            let secs = start.elapsed().as_secs_f64();
            let Outcome::Stiff { t } = s.outcome else {
                panic!("{m} on {name}: {}", s.outcome);
            };
            assert!(
                t > 0.0 && t < t_end && secs < 1.0,
                "{m} on {name}: t = {t}, {secs} s"
            );
            assert!(s.outcome.to_string().contains("looks stiff at t = "));
            assert!(
                s.outcome
                    .to_string()
                    .contains("try --method rodas5p or radau5")
            );
            eprintln!(
                "{m} on {name}: stiff at t = {t:.4} after {} steps, {secs:.4} s",
                s.steps
            );
        }
        // long non-stiff runs (well over the 1000 steps between tests) finish
        for (name, t_end, rtol) in [
            ("harmonic", 2000.0, 1e-8),
            ("kepler", 200.0, 1e-10),
            ("pendulum", 2000.0, 1e-8),
            ("limit-cycle", 500.0, 1e-8),
            ("logistic", 100.0, 1e-10),
        ] {
            let p = problem(name);
            let s = solve_embedded(
                &p,
                m,
                0.0,
                &p.initial,
                t_end,
                Adaptive {
                    rtol,
                    atol: rtol,
                    ..stiff_opts()
                },
            );
            assert!(
                s.finished(),
                "{m} on {name}: {} after {} steps",
                s.outcome,
                s.steps
            );
            assert!(
                s.steps > 1000 || name == "logistic",
                "{m} on {name}: only {} steps",
                s.steps
            );
        }
        // without the flag the pair grinds on (here for a bounded span)
        let p = problem("robertson");
        let s = solve_embedded(&p, m, 0.0, &p.initial, 1.0, opts(1e-6, 1e-9));
        assert!(s.finished(), "{}", s.outcome);
    }
}

/// Bad input ends in a clear `Failed` with t, never a hang or a panic.
#[test]
fn bad_input_fails_clearly() {
    struct BadJacobian(f64);
    impl System for BadJacobian {
        fn dim(&self) -> usize {
            2
        }
        fn rhs(&self, _t: f64, x: &[f64], d: &mut [f64]) {
            d[0] = -x[0] + x[1];
            d[1] = x[0] - x[1];
        }
        fn jacobian(&self, _t: f64, _x: &[f64], j: &mut [f64]) -> bool {
            j.fill(self.0);
            true
        }
    }
    for m in STIFF {
        // NaN in the Jacobian
        let s = solve_embedded(
            &BadJacobian(f64::NAN),
            m,
            0.0,
            &[1.0, 0.0],
            1.0,
            opts(1e-6, 1e-9),
        );
        match &s.outcome {
            Outcome::Failed { t, reason } => {
                assert_eq!(*t, 0.0);
                assert!(reason.contains("NaN"), "{m}: {reason}");
            }
            other => panic!("{m}: {other:?}"),
        }
        // a Newton matrix singular at every h the run can reach (round-off wipes the pivot)
        let s = solve_embedded(
            &BadJacobian(1e300),
            m,
            0.0,
            &[1.0, 0.0],
            1.0,
            opts(1e-6, 1e-9),
        );
        match &s.outcome {
            Outcome::Failed { t, reason } => {
                assert_eq!(*t, 0.0);
                assert!(reason.contains("singular"), "{m}: {reason}");
            }
            other => panic!("{m}: {other:?}"),
        }
        // f turns NaN at t > 0.5: steps shrink to underflow there (or Rodas5P's difference
        // quotient in t sees the NaN first)
        let nan_later = FnSystem::new(1, |t, x: &[f64], d: &mut [f64]| {
            d[0] = if t > 0.5 { f64::NAN } else { -x[0] }
        });
        let start = Instant::now();
        let s = solve_embedded(&nan_later, m, 0.0, &[1.0], 1.0, opts(1e-6, 1e-9));
        match &s.outcome {
            Outcome::Failed { t, reason } => {
                assert!((t - 0.5).abs() < 1e-6, "{m}: t = {t}");
                assert!(
                    reason.contains("underflow") || reason.contains("NaN"),
                    "{m}: {reason}"
                );
            }
            other => panic!("{m}: {other:?}"),
        }
        assert!(start.elapsed().as_secs_f64() < 5.0);
        // tolerances
        for (rtol, atol) in [(0.0, 1e-9), (1e-6, 0.0), (f64::NAN, 1e-9), (1e-6, f64::NAN)] {
            let s = solve_embedded(&nan_later, m, 0.0, &[1.0], 1.0, opts(rtol, atol));
            assert!(
                matches!(s.outcome, Outcome::Failed { t: 0.0, .. }),
                "{m}: {:?}",
                s.outcome
            );
        }
        // a state that leaves the bound is divergence, as for every method
        let blowup = FnSystem::new(1, |_t, x: &[f64], d: &mut [f64]| d[0] = x[0] * x[0]);
        let s = solve_embedded(&blowup, m, 0.0, &[1.0], 2.0, opts(1e-6, 1e-9));
        assert!(
            matches!(s.outcome, Outcome::Diverged { .. } | Outcome::Failed { .. }),
            "{m}: {:?}",
            s.outcome
        );
    }
}

/// The f-evaluation counts against scipy's Radau and BDF (given analytic Jacobians too) on the
/// hard cases at the same tolerances: never more than twice scipy's Radau. The figures are in
/// docs/benchmarks/stiff.md.
#[test]
fn work_is_comparable_to_scipy_radau() {
    let reference = reference();
    let cases = [
        ("vanderpol-1000", "vanderpol-1000", 3000.0),
        ("robertson-1e5", "robertson", 1e5),
        ("hires", "hires", 321.8122),
        ("orego", "orego", 360.0),
    ];
    for (key, file, t_end) in cases {
        let r = &reference["problems"][key];
        let scale = r["atol_over_rtol"].as_f64().unwrap();
        let p = problem(file);
        for row in r["runs"].as_array().unwrap() {
            if row["method"] != "Radau" {
                continue;
            }
            let rtol = row["rtol"].as_f64().unwrap();
            if rtol < 1e-8 {
                continue;
            }
            let scipy = row["nfev"].as_u64().unwrap();
            for m in STIFF {
                let s = solve_embedded(&p, m, 0.0, &p.initial, t_end, opts(rtol, rtol * scale));
                assert!(s.finished(), "{m} on {key} at {rtol:e}: {}", s.outcome);
                eprintln!(
                    "{key} {rtol:.0e}: {m} {} f, scipy Radau {scipy} f",
                    s.f_evals
                );
                assert!(
                    s.f_evals <= 2 * scipy,
                    "{m} on {key} at {rtol:e}: {} f vs scipy's {scipy}",
                    s.f_evals
                );
            }
        }
    }
}

/// The fixed-size fast path takes the stiff solvers too (through the general system view):
/// the same steps and state as the slice driver, the system's own Jacobian used, every
/// accepted step reported to the callback.
#[test]
fn the_fixed_size_driver_runs_rodas5p_and_radau5_with_the_systems_jacobian() {
    use lectern::ode::fixed::AsSystem;
    use lectern::ode::{FixedSystem, solve_embedded_n_with};
    #[derive(Clone, Copy)]
    struct FixedRobertson;
    impl FixedSystem<3> for FixedRobertson {
        fn rhs(&self, _t: f64, y: &[f64; 3]) -> [f64; 3] {
            [
                -0.04 * y[0] + 1e4 * y[1] * y[2],
                0.04 * y[0] - 1e4 * y[1] * y[2] - 3e7 * y[1] * y[1],
                3e7 * y[1] * y[1],
            ]
        }
        fn jacobian(&self, _t: f64, y: &[f64; 3], j: &mut [f64]) -> bool {
            j.copy_from_slice(&[
                -0.04,
                1e4 * y[2],
                1e4 * y[1],
                0.04,
                -1e4 * y[2] - 6e7 * y[1],
                -1e4 * y[1],
                0.0,
                6e7 * y[1],
                0.0,
            ]);
            true
        }
    }
    /// The same right-hand side without its Jacobian.
    struct NoJacobian;
    impl FixedSystem<3> for NoJacobian {
        fn rhs(&self, t: f64, y: &[f64; 3]) -> [f64; 3] {
            FixedRobertson.rhs(t, y)
        }
    }
    let opts = lectern::ode::Adaptive {
        rtol: 1e-6,
        atol: 1e-12,
        record: false,
        ..Default::default()
    };
    let y0 = [1.0, 0.0, 0.0];
    for m in [Method::Rodas5p, Method::Radau5] {
        let mut steps = 0;
        let fast = solve_embedded_n_with(&FixedRobertson, m, 0.0, y0, 1e5, opts, |_, _| steps += 1);
        assert!(fast.finished(), "{m}: {:?}", fast.outcome);
        let general = solve_embedded(&AsSystem::<3, _>(FixedRobertson), m, 0.0, &y0, 1e5, opts);
        assert_eq!(fast.x.as_slice(), general.last().1, "{m}");
        assert_eq!(
            (fast.f_evals, fast.steps),
            (general.f_evals, general.steps),
            "{m}"
        );
        assert_eq!(steps, fast.steps, "{m}");
        // the system's Jacobian, not differences (which cost n f-evaluations each)
        let differences = solve_embedded_n_with(&NoJacobian, m, 0.0, y0, 1e5, opts, |_, _| {});
        assert!(differences.finished());
        assert!(differences.f_evals > fast.f_evals, "{m}");
        // Robertson's mass is conserved to round-off
        assert!((fast.x.iter().sum::<f64>() - 1.0).abs() < 1e-12, "{m}");
    }
}
