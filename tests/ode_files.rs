//! Problems and tableaux written in RON, the expression compiler, divergence as data, and the
//! `lectern solve` command.

use std::process::Command;

use lectern::ode::expr::{self, Program};
use lectern::ode::problem::Problem;
use lectern::ode::{
    Adaptive, FnSystem, Method, Outcome, Tableau, solve_adaptive, solve_fixed, solve_tableau,
};

/// xorshift64*: reproducible random inputs without a dependency.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        let bits = self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11;
        bits as f64 / (1u64 << 53) as f64
    }
    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next()
    }
}

type Native = fn(f64, &[f64]) -> f64;

#[test]
fn compiled_expressions_equal_native_closures() {
    let vars: Vec<String> = ["x", "y", "z"].iter().map(|s| s.to_string()).collect();
    let params = vec![("a".to_string(), 1.75), ("b".to_string(), -0.5)];
    let (a, b) = (1.75, -0.5);
    let _ = (a, b);
    let cases: Vec<(&str, Native)> = vec![
        ("x + y * z - a", |_, v| v[0] + v[1] * v[2] - 1.75),
        ("-x^2 + y^3 - z^0.5", |_, v| {
            -(v[0] * v[0]) + v[1].powi(3) - v[2].powf(0.5)
        }),
        ("sin(x) * cos(y) / (1 + z^2)", |_, v| {
            v[0].sin() * v[1].cos() / (1.0 + v[2] * v[2])
        }),
        ("exp(-t*b) * ln(z + 1)", |t, v| {
            (-t * -0.5f64).exp() * (v[2] + 1.0).ln()
        }),
        ("sqrt(abs(x*y)) + tan(z/4)", |_, v| {
            (v[0] * v[1]).abs().sqrt() + (v[2] / 4.0).tan()
        }),
        ("atan2(y, x) + min(x, y) * max(z, a)", |_, v| {
            v[1].atan2(v[0]) + v[0].min(v[1]) * v[2].max(1.75)
        }),
        ("pow(z, x) - 2^x", |_, v| v[2].powf(v[0]) - 2f64.powf(v[0])),
        ("-x/((x^2 + y^2)*sqrt(x^2 + y^2))", |_, v| {
            let r2 = v[0] * v[0] + v[1] * v[1];
            -v[0] / (r2 * r2.sqrt())
        }),
        ("((1 - x^2)*y - x)/a", |_, v| {
            ((1.0 - v[0] * v[0]) * v[1] - v[0]) / 1.75
        }),
        ("a*b*t - (x - (y - z))", |t, v| {
            1.75 * -0.5 * t - (v[0] - (v[1] - v[2]))
        }),
    ];
    let srcs: Vec<String> = cases.iter().map(|c| c.0.to_string()).collect();
    let prog: Program = expr::compile(&srcs, &vars, &params).unwrap();
    let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
    let mut out = vec![0.0; cases.len()];
    let mut worst = 0.0f64;
    for _ in 0..20_000 {
        let t = rng.range(-5.0, 5.0);
        let x = [
            rng.range(-3.0, 3.0),
            rng.range(-3.0, 3.0),
            rng.range(0.01, 4.0),
        ];
        prog.eval(t, &x, &mut out);
        for (i, (src, native)) in cases.iter().enumerate() {
            let want = native(t, &x);
            let got = out[i];
            if want.is_nan() {
                assert!(got.is_nan(), "{src}");
                continue;
            }
            let rel = (got - want).abs() / want.abs().max(1.0);
            worst = worst.max(rel);
            assert!(rel <= 1e-15, "{src} at t={t}, x={x:?}: {got} vs {want}");
        }
    }
    eprintln!("worst relative difference compiled vs native: {worst:e}");
}

#[test]
fn parse_errors_name_file_line_column_and_token() {
    let text = "(\n    name: \"bad\",\n    vars: [\"x\"],\n    rhs: [\"2 * (x +\"],\n    initial: [1.0],\n)";
    let d = Problem::parse(text, "slides/problems/bad.ron").unwrap_err();
    // `    rhs: ["2 * (x +"],` — the expression ends where an operand should be (column 20)
    assert_eq!((d.line, d.col), (4, 20), "{d}");
    let s = d.to_string();
    assert!(
        s.starts_with("slides/problems/bad.ron:4:20: in rhs[0]"),
        "{s}"
    );
    assert!(s.contains("end of expression"), "{s}");

    let text = text.replace("2 * (x +", "x * sinn(x)");
    let d = Problem::parse(&text, "p.ron").unwrap_err();
    assert_eq!((d.line, d.col), (4, 16), "{d}");
    assert!(d.message.contains("`sinn`"), "{d}");

    // a RON syntax error keeps ron's position
    let d = Problem::parse("(\n name: \"x\",\n vars: [\"x\"\n", "p.ron").unwrap_err();
    assert!(d.line >= 3, "{d}");
    let d = Problem::load("slides/problems/does-not-exist.ron").unwrap_err();
    assert!(d.to_string().contains("does-not-exist.ron"), "{d}");
}

#[test]
fn every_shipped_problem_loads_and_solves() {
    let cases = [
        ("harmonic", Method::Rk4, 0.01, 10.0),
        ("dahlquist", Method::Rk4, 0.001, 1.0),
        ("kepler", Method::Rk4, 0.001, 6.283185307179586),
        ("pendulum", Method::Verlet, 0.001, 10.0),
        ("vanderpol", Method::ImplicitEuler, 1e-3, 2.0),
        ("robertson", Method::ImplicitEuler, 1e-2, 40.0),
    ];
    for (name, method, h, t_end) in cases {
        let p = Problem::load(format!("slides/problems/{name}.ron")).unwrap();
        let sol = solve_fixed(&p, method, p.t0, &p.initial, h, t_end, 1e12);
        assert_eq!(sol.outcome, Outcome::Finished, "{name}");
        if let Some(exact) = p.exact(t_end) {
            let err = lectern::ode::study::max_error(sol.last().1, &exact);
            assert!(err < 1e-8, "{name}: error {err}");
        }
    }
    // Robertson conserves y1 + y2 + y3 = 1 (every method that is linear in f does)
    let p = Problem::load("slides/problems/robertson.ron").unwrap();
    let sol = solve_fixed(&p, Method::ImplicitEuler, 0.0, &p.initial, 1e-2, 40.0, 1e12);
    let y = sol.last().1;
    assert!((y.iter().sum::<f64>() - 1.0).abs() < 1e-12, "{y:?}");
    // known reference at t = 40: y1 = 0.7158, y3 = 0.2842 (Hairer & Wanner)
    assert!((y[0] - 0.7158).abs() < 2e-3, "{y:?}");
    let opts = Adaptive {
        rtol: 1e-6,
        atol: 1e-10,
        record: false,
        ..Adaptive::default()
    };
    assert!(solve_adaptive(&p, 0.0, &p.initial, 0.3, opts).finished());
}

#[test]
fn shipped_tableaux_validate_and_malformed_ones_are_rejected_with_positions() {
    for entry in std::fs::read_dir("slides/tableaux").unwrap() {
        let path = entry.unwrap().path();
        let t = Tableau::load(&path).unwrap_or_else(|d| panic!("{d}"));
        assert!(t.row_sums_consistent(), "{}", path.display());
    }
    let implicit = "(name: \"imp\", a: [[0.5]], b: [1.0], c: [0.5])";
    let d = Tableau::parse(implicit, "imp.ron").unwrap_err();
    assert!(d.message.contains("explicit"), "{d}");
    let d = Tableau::parse(
        "(name: \"x\",\n a: [[0.0]],\n b: [1.0, oops],\n c: [0.0])",
        "x.ron",
    )
    .unwrap_err();
    assert_eq!(d.line, 3, "{d}");
}

#[test]
fn divergence_is_data_for_huge_steps_and_nan_states() {
    let p = Problem::load("slides/problems/harmonic.ron").unwrap();
    for m in Method::ALL {
        // the stiff solvers take the fixed huge steps too (they have a fixed-step form)
        let sol = if m.is_adaptive() && !m.is_implicit() {
            solve_adaptive(&p, 0.0, &[f64::NAN, 0.0], 10.0, Adaptive::default())
        } else {
            // ten steps of h = 1e9
            solve_fixed(&p, m, 0.0, &p.initial, 1e9, 1e10, 1e12)
        };
        eprintln!("{m}: h = 1e9 → {}", sol.outcome);
        if m.is_implicit() {
            // A-stable: the huge step is fine
            assert_eq!(sol.outcome, Outcome::Finished, "{m}");
        } else {
            assert!(
                matches!(sol.outcome, Outcome::Diverged { .. }),
                "{m}: {:?}",
                sol.outcome
            );
            assert!(sol.outcome.to_string().starts_with("diverged at t = "));
        }
        // NaN initial values: diverged at t0, no step taken
        let sol = solve_fixed(&p, m, 0.0, &[f64::NAN, 1.0], 0.1, 1.0, 1e12);
        assert_eq!(sol.outcome, Outcome::Diverged { t: 0.0 }, "{m}");
    }
    let sol = solve_fixed(&p, Method::Euler, 0.0, &p.initial, 1e9, 1e10, 1e12);
    assert_eq!(sol.outcome, Outcome::Diverged { t: 2e9 });
    // a right-hand side that turns NaN half way (at x > 2, reached near t = 1.5)
    let sys = FnSystem::new(1, |_t, x: &[f64], d: &mut [f64]| {
        d[0] = if x[0] > 2.0 { f64::NAN } else { 1.0 }
    });
    let sol = solve_fixed(&sys, Method::Rk4, 0.0, &[0.5], 0.1, 10.0, 1e12);
    match sol.outcome {
        Outcome::Diverged { t } => assert!((t - 1.6).abs() < 0.11, "{t}"),
        other => panic!("{other:?}"),
    }
    // nonsense steps are refused, not panicked on
    for h in [0.0, -1.0, f64::NAN, f64::INFINITY, 1e-300] {
        let sol = solve_fixed(&p, Method::Rk4, 0.0, &p.initial, h, 1.0, 1e12);
        assert!(matches!(sol.outcome, Outcome::Failed { .. }), "h = {h}");
    }
    let typo = Tableau::rk4_typo();
    let sol = solve_tableau(&p, &typo, 0.0, &p.initial, 1e9, 1e10, 1e12);
    assert!(matches!(sol.outcome, Outcome::Diverged { .. }));
    // symplectic methods refuse a first-order system rather than computing nonsense
    let d = Problem::load("slides/problems/dahlquist.ron").unwrap();
    let sol = solve_fixed(&d, Method::Verlet, 0.0, &d.initial, 0.1, 1.0, 1e12);
    assert!(matches!(sol.outcome, Outcome::Failed { .. }));
}

fn lectern(args: &[&str]) -> (bool, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_lectern"))
        .args(args)
        .output()
        .unwrap();
    (
        out.status.success(),
        String::from_utf8(out.stdout).unwrap(),
        String::from_utf8(out.stderr).unwrap(),
    )
}

#[test]
fn solve_cli_prints_final_state_trajectory_and_work() {
    let tau = std::f64::consts::TAU.to_string();
    let (ok, out, err) = lectern(&[
        "solve",
        "slides/problems/harmonic.ron",
        "--method",
        "rk4",
        "--h",
        "0.001",
        "--t-end",
        &tau,
    ]);
    assert!(ok, "{err}");
    let nums: Vec<f64> = out.split_whitespace().map(|s| s.parse().unwrap()).collect();
    assert_eq!(nums.len(), 3, "{out}");
    assert!((nums[0] - std::f64::consts::TAU).abs() < 1e-15);
    assert!(
        (nums[1] - 1.0).abs() < 1e-12 && nums[2].abs() < 1e-12,
        "{out}"
    );
    assert!(err.contains("f-evaluations: 25136"), "{err}");

    let (ok, out, _) = lectern(&[
        "solve",
        "slides/problems/harmonic.ron",
        "--method",
        "euler",
        "--h",
        "0.1",
        "--t-end",
        "0.3",
        "--trajectory",
    ]);
    assert!(ok);
    let lines: Vec<&str> = out.lines().collect();
    assert_eq!(lines[0], "t,x,v");
    assert_eq!(lines.len(), 5, "{out}");
    assert_eq!(lines[1], "0,1,0");
    assert_eq!(lines[2], "0.1,1,-0.1");

    let (ok, out, err) = lectern(&[
        "solve",
        "slides/problems/kepler.ron",
        "--method",
        "dopri5",
        "--rtol",
        "1e-10",
        "--atol",
        "1e-10",
        "--t-end",
        &tau,
    ]);
    assert!(ok, "{err}");
    assert!(err.contains("rejected"), "{err}");
    let nums: Vec<f64> = out.split_whitespace().map(|s| s.parse().unwrap()).collect();
    assert!(
        (nums[1] - 0.4).abs() < 1e-7 && (nums[4] - 2.0).abs() < 1e-6,
        "{out}"
    );

    let (ok, _, err) = lectern(&[
        "solve",
        "slides/problems/harmonic.ron",
        "--tableau",
        "slides/tableaux/rk4-typo.ron",
        "--h",
        "0.01",
        "--t-end",
        "1",
    ]);
    assert!(ok, "{err}");
    assert!(err.contains("RK4 as printed"), "{err}");

    let (ok, _, err) = lectern(&[
        "solve",
        "slides/problems/harmonic.ron",
        "--method",
        "euler",
        "--h",
        "1e9",
        "--t-end",
        "1e10",
    ]);
    assert!(!ok);
    assert!(err.contains("diverged at t = "), "{err}");
    assert!(!err.contains("panicked"), "{err}");

    let (ok, _, err) = lectern(&[
        "solve",
        "slides/problems/harmonic.ron",
        "--method",
        "rk5",
        "--h",
        "0.1",
        "--t-end",
        "1",
    ]);
    assert!(!ok && err.contains("dopri5"), "{err}");

    let (ok, out, err) = lectern(&[
        "solve",
        "slides/problems/dahlquist.ron",
        "--method",
        "implicit-euler",
        "--h",
        "0.1",
        "--t-end",
        "1",
        "--param",
        "lambda=-1e6",
    ]);
    assert!(ok, "{err}");
    let y: f64 = out.split_whitespace().nth(1).unwrap().parse().unwrap();
    assert!(y > 0.0 && y < 1e-40, "{out}");
}
