//! Two side measurements: the cost of an expression-defined right-hand side against the same
//! one in native Rust, and a few criterion benchmarks of the headline RK4 comparison.

use std::f64::consts::TAU;
use std::fmt::Write as _;
use std::hint::black_box;
use std::time::Duration;

use criterion::Criterion;
use differential_equations::prelude::{ExplicitRungeKutta, IVP};
use lectern::ode::fixed::AsSystem;
use lectern::ode::native::Kepler;
use lectern::ode::problem::Problem;
use lectern::ode::{FixedSystem, Method, Scheme, System, solve_fixed_final, solve_fixed_n};
use ode_solvers::SVector;

use super::ROUNDS;
use super::runners::{KeepLast, Peer, Run, timed};

/// The Kepler problem file seen as a fixed-size system: the expression evaluator behind the
/// fast driver, to separate the cost of the evaluator from the cost of the driver.
struct ExprFixed<'a>(&'a Problem);

impl FixedSystem<4> for ExprFixed<'_> {
    #[inline]
    fn rhs(&self, t: f64, x: &[f64; 4]) -> [f64; 4] {
        let mut d = [0.0; 4];
        System::rhs(self.0, t, x, &mut d);
        d
    }
}

/// Expression RHS ÷ native RHS: (per evaluation, general RK4 driver, fixed-size driver).
pub fn expression_vs_native(out: &mut String) -> (f64, f64, f64) {
    let problem = Problem::load("slides/problems/kepler.ron").unwrap();
    let x0 = problem.initial.clone();
    let per_eval = |sys: &dyn System| {
        let mut d = [0.0; 4];
        let (_, s) = timed(|| {
            let mut x = x0.clone();
            for i in 0..100_000 {
                sys.rhs(0.0, &x, &mut d);
                x[0] += 1e-12 * d[2] + i as f64 * 1e-18;
            }
            (0.0, x, 100_000)
        });
        s / 100_000.0
    };
    let h = TAU / 20_000.0;
    let solve = |sys: &dyn System| {
        timed(|| {
            let sol = solve_fixed_final(
                sys,
                Scheme::Method(Method::Rk4),
                0.0,
                &x0,
                h,
                TAU,
                f64::INFINITY,
            );
            (0.0, sol.last().1.to_vec(), sol.f_evals)
        })
        .1
    };
    let x0n = [0.4, 0.0, 0.0, 2.0];
    let fast = |sys: &dyn Fn(f64, [f64; 4]) -> Run| timed(|| sys(h, black_box(x0n))).1;
    let fast_expr = |h: f64, x0: [f64; 4]| {
        let sol = solve_fixed_n(&ExprFixed(&problem), 0.0, x0, h, TAU, f64::INFINITY);
        (sol.t, sol.x.to_vec(), sol.f_evals)
    };
    let fast_native = |h: f64, x0: [f64; 4]| {
        let sol = solve_fixed_n(&Kepler, 0.0, x0, h, TAU, f64::INFINITY);
        (sol.t, sol.x.to_vec(), sol.f_evals)
    };
    // the expression evaluator is sensitive to what shares the core (branch prediction), so
    // interleave expression and native measurements over several rounds and keep the minima
    let [mut e, mut n, mut se, mut sn, mut fe, mut fnat] = [f64::INFINITY; 6];
    for _ in 0..ROUNDS {
        e = e.min(per_eval(&problem));
        n = n.min(per_eval(&AsSystem::<4, _>(Kepler)));
        se = se.min(solve(&problem));
        sn = sn.min(solve(&AsSystem::<4, _>(Kepler)));
        fe = fe.min(fast(&fast_expr));
        fnat = fnat.min(fast(&fast_native));
    }
    writeln!(
        out,
        "| Kepler right-hand side | RON expression | native Rust | expression ÷ native |"
    )
    .unwrap();
    writeln!(out, "|---|---:|---:|---:|").unwrap();
    writeln!(
        out,
        "| one f-evaluation through `&dyn System` (ns) | {:.1} | {:.1} | {:.2}× |",
        e * 1e9,
        n * 1e9,
        e / n
    )
    .unwrap();
    writeln!(
        out,
        "| RK4 (slices driver), 20000 steps (ms) | {:.3} | {:.3} | {:.2}× |",
        se * 1e3,
        sn * 1e3,
        se / sn
    )
    .unwrap();
    writeln!(
        out,
        "| RK4 (`[f64; 4]` driver), 20000 steps (ms) | {:.3} | {:.3} | {:.2}× |\n",
        fe * 1e3,
        fnat * 1e3,
        fe / fnat
    )
    .unwrap();
    writeln!(
        out,
        "Worst case for the expression path: RON expression on the slices driver ÷ native RHS on \
         the `[f64; 4]` fast path = **{:.2}×**.\n",
        se / fnat
    )
    .unwrap();
    (e / n, se / sn, fe / fnat)
}

pub fn criterion_part() {
    let mut c = Criterion::default()
        .sample_size(20)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2))
        .configure_from_args();
    let x0 = [0.4, 0.0, 0.0, 2.0];
    let h = TAU / 2000.0;
    let mut g = c.benchmark_group("kepler_rk4_2000_steps");
    g.bench_function("lectern", |b| {
        b.iter(|| {
            solve_fixed_final(
                &AsSystem::<4, _>(Kepler),
                Scheme::Method(Method::Rk4),
                0.0,
                black_box(&x0),
                h,
                TAU,
                f64::INFINITY,
            )
        })
    });
    g.bench_function("lectern_fixed_size", |b| {
        b.iter(|| solve_fixed_n(&Kepler, 0.0, black_box(x0), h, TAU, f64::INFINITY))
    });
    let problem = Problem::load("slides/problems/kepler.ron").unwrap();
    g.bench_function("lectern_ron_expression", |b| {
        b.iter(|| {
            solve_fixed_final(
                &problem,
                Scheme::Method(Method::Rk4),
                0.0,
                black_box(&x0),
                h,
                TAU,
                f64::INFINITY,
            )
        })
    });
    g.bench_function("ode_solvers", |b| {
        b.iter(|| {
            let mut st = ode_solvers::Rk4::new(
                Peer(Kepler),
                0.0,
                SVector::<f64, 4>::from(black_box(x0)),
                TAU,
                h,
            );
            st.integrate().unwrap();
            st.y_out().len()
        })
    });
    g.bench_function("differential_equations", |b| {
        b.iter(|| {
            IVP::ode(&Peer(Kepler), 0.0, TAU, black_box(x0))
                .method(ExplicitRungeKutta::rk4(h).max_steps(10_000_000))
                .solout(KeepLast)
                .solve()
                .unwrap()
        })
    });
    g.finish();
    c.final_summary();
}
