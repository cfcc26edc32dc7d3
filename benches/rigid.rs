//! Rigid-body step cost in ns/body: free bodies (I = diag(1, 2, 3), h = 1/60) with each
//! integrator through `RigidBody::step` (one body at a time) and through `BodyBatch` (1000 and
//! 100 000 bodies, SIMD lanes; also its portable build), and a floating body (gravity,
//! buoyancy against the Gerstner sum, drag) with RK4.
//!
//! `SUMMARY_ONLY=1 CARGO_TARGET_DIR=/work/target-release-rigid cargo bench --bench rigid`

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group};
use glam::{DQuat, DVec3};
use lectern::rigid::{
    BodyBatch, BuoyancySamples, FreeBodies, Integrator, NoForces, RigidBody, TriMesh, WaterForces,
    mass,
};
use lectern::waves::{GerstnerWave, WaveSum};
use std::hint::black_box;
use std::time::{Duration, Instant};

const BODIES: usize = 1000;
const MANY: usize = 100_000;
const H: f64 = 1.0 / 60.0;

fn free_bodies(method: Integrator, n: usize) -> Vec<RigidBody> {
    (0..n)
        .map(|i| {
            let w = DVec3::new(0.01 + (i % 1000) as f64 * 1e-4, 1.0, 0.2);
            RigidBody::free_spinning(DVec3::new(1.0, 2.0, 3.0), w, method)
        })
        .collect()
}

fn batch(method: Integrator, n: usize) -> BodyBatch {
    let mut b = BodyBatch::new(method);
    for body in free_bodies(method, n) {
        b.push(&body.constants, body.state);
    }
    b
}

fn sea() -> WaveSum {
    WaveSum::new(
        vec![
            GerstnerWave {
                direction: [1.0, 0.2],
                wavelength: 9.0,
                amplitude: 0.3,
                steepness: 0.7,
                speed: 3.7,
            },
            GerstnerWave {
                direction: [0.5, 0.9],
                wavelength: 4.0,
                amplitude: 0.1,
                steepness: 0.6,
                speed: 2.5,
            },
        ],
        0.0,
    )
}

/// Runs `f` with a floating box (RK4, 64 buoyancy samples) ready to step.
fn with_floating_box(f: impl FnOnce(&mut dyn FnMut())) {
    let mesh = TriMesh::centred_box(DVec3::new(1.0, 0.6, 0.8));
    let unit = mass::mirtich(&mesh);
    let samples = BuoyancySamples::from_mesh(&mesh, &unit, unit.volume(), 4);
    let waves = sea();
    let props = unit.with_density(400.0);
    let forces = WaterForces {
        gravity: DVec3::new(0.0, -9.81, 0.0),
        water_density: 1000.0,
        waves: &waves,
        samples: &samples,
        linear_drag: props.mass,
        angular_drag: props.inertia.col(0).x,
        wave_time_offset: 0.0,
    };
    let mut body = RigidBody::from_mass_properties(&props, DVec3::ZERO, DQuat::IDENTITY);
    f(&mut || body.step(H, &forces));
}

fn bench_rigid(c: &mut Criterion) {
    let mut g = c.benchmark_group("rigid");
    g.measurement_time(Duration::from_secs(2));
    g.warm_up_time(Duration::from_millis(500));
    for method in Integrator::ALL {
        g.throughput(Throughput::Elements(BODIES as u64));
        let mut bodies = free_bodies(method, BODIES);
        g.bench_function(BenchmarkId::new("body_step_1000", method.name()), |b| {
            b.iter(|| bodies.iter_mut().for_each(|body| body.step(H, &NoForces)))
        });
        for n in [BODIES, MANY] {
            g.throughput(Throughput::Elements(n as u64));
            let mut bb = batch(method, n);
            g.bench_function(BenchmarkId::new(format!("batch_{n}"), method.name()), |b| {
                b.iter(|| bb.step(H, &FreeBodies))
            });
        }
    }
    g.finish();
    with_floating_box(|step| {
        c.bench_function("rigid/floating_rk4_64_samples", |b| b.iter(&mut *step));
    });
}

/// Median and minimum over `runs` timed runs of `run`, in ns per body. The machine is shared:
/// the minimum is the least-disturbed run, the median what a typical step costs under load.
fn timed(n: usize, runs: usize, mut run: impl FnMut()) -> (f64, f64) {
    run(); // warm the caches and the branch predictors
    let mut t: Vec<f64> = (0..runs)
        .map(|_| {
            let s = Instant::now();
            run();
            s.elapsed().as_secs_f64() * 1e9 / n as f64
        })
        .collect();
    t.sort_by(f64::total_cmp);
    (t[runs / 2], t[0])
}

fn cell((median, min): (f64, f64)) -> String {
    format!("{median:.1} ({min:.1})")
}

fn summary() {
    println!(
        "\n## rigid summary (one core, h = 1/60, free bodies I = diag(1, 2, 3); median (minimum) of 101 runs, 21 for 100 000 bodies)\n"
    );
    println!(
        "| integrator | RigidBody::step ns/body | BodyBatch 1000 ns/body | BodyBatch 100 000 ns/body | BodyBatch 1000, portable build, ns/body |"
    );
    println!("|---|---|---|---|---|");
    for method in Integrator::ALL {
        let mut bodies = free_bodies(method, BODIES);
        let single = timed(BODIES, 101, || {
            bodies.iter_mut().for_each(|b| b.step(H, &NoForces));
            black_box(&bodies);
        });
        let mut small = batch(method, BODIES);
        let b1k = timed(BODIES, 101, || small.step(H, &FreeBodies));
        let mut big = batch(method, MANY);
        let b100k = timed(MANY, 21, || big.step(H, &FreeBodies));
        let mut portable = batch(method, BODIES);
        let bport = timed(BODIES, 101, || portable.step_portable(H, &FreeBodies));
        black_box((&small, &big, &portable));
        println!(
            "| {} | {} | {} | {} | {} |",
            method.name(),
            cell(single),
            cell(b1k),
            cell(b100k),
            cell(bport)
        );
    }
    with_floating_box(|step| {
        let (median, min) = timed(100, 21, || {
            for _ in 0..100 {
                step();
            }
        });
        println!(
            "\nFloating box (RK4, gravity + 64 buoyancy samples on a 2-wave Gerstner sum + drag), `RigidBody::step`: {:.1} µs/step median ({:.1} min)",
            median / 1e3,
            min / 1e3
        );
    });
}

criterion_group!(benches, bench_rigid);

fn main() {
    // SUMMARY_ONLY=1 skips criterion and prints just the table (a quicker run)
    if std::env::var_os("SUMMARY_ONLY").is_none() {
        benches();
        criterion::Criterion::default()
            .configure_from_args()
            .final_summary();
    }
    summary();
}
