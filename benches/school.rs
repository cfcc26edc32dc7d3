//! Fish school step cost for N = 1k … 1M at constant density (so O(N) shows as flat ns/fish),
//! split into grid rebuild, neighbour steering and integration; and the integration pass
//! against a STREAM-like copy bandwidth measured in the same run.
//!
//! `CARGO_TARGET_DIR=/work/target-release cargo bench --bench school` runs criterion and then
//! prints a markdown summary (the figures in docs/benchmarks/sim.md).

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group};
use glam::Vec3;
use lectern::school::{Aabb, Environment, School, SchoolParams};
use std::hint::black_box;
use std::time::{Duration, Instant};

const SIZES: [usize; 4] = [1_000, 10_000, 100_000, 1_000_000];
/// fish per m³: with the default 1.2 m neighbour radius about 7 neighbours per fish
const DENSITY: f32 = 1.0;

fn tank(n: usize) -> Aabb {
    // a flat tank, 4 wide for each 1 high, holding n fish at DENSITY
    let side = (4.0 * n as f32 / DENSITY).cbrt();
    Aabb::new(
        Vec3::new(-side / 2.0, -side / 4.0, -side / 2.0),
        Vec3::new(side / 2.0, 0.0, side / 2.0),
    )
}

fn school(n: usize) -> (School, Aabb) {
    let bounds = tank(n);
    let env = Environment::new(bounds);
    let mut s = School::new(
        &SchoolParams {
            count: n,
            ..Default::default()
        },
        &env,
    );
    // let the school form before timing
    for _ in 0..5 {
        s.step(1.0 / 60.0, &env);
    }
    (s, bounds)
}

fn bench_school(c: &mut Criterion) {
    let mut g = c.benchmark_group("school");
    for n in SIZES {
        let (mut s, bounds) = school(n);
        let env = Environment::new(bounds);
        g.throughput(Throughput::Elements(n as u64));
        g.sample_size(if n >= 1_000_000 { 10 } else { 20 });
        g.measurement_time(Duration::from_secs(if n >= 100_000 { 4 } else { 2 }));
        g.warm_up_time(Duration::from_millis(500));
        g.bench_with_input(BenchmarkId::new("step", n), &n, |b, _| {
            b.iter(|| s.step(1.0 / 60.0, &env))
        });
        g.bench_with_input(BenchmarkId::new("grid", n), &n, |b, _| {
            b.iter(|| s.rebuild_grid(&env))
        });
        g.bench_with_input(BenchmarkId::new("steer", n), &n, |b, _| {
            b.iter(|| s.compute_steering(&env))
        });
        g.bench_with_input(BenchmarkId::new("integrate", n), &n, |b, _| {
            b.iter(|| s.integrate(1.0 / 60.0, &env))
        });
    }
    g.finish();
}

/// Median seconds of `f` over `reps` runs.
fn median_secs(reps: usize, mut f: impl FnMut()) -> f64 {
    let mut t: Vec<f64> = (0..reps)
        .map(|_| {
            let s = Instant::now();
            f();
            s.elapsed().as_secs_f64()
        })
        .collect();
    t.sort_by(f64::total_cmp);
    t[reps / 2]
}

/// STREAM-like copy: bytes read + written per second, on arrays far larger than cache.
fn copy_bandwidth() -> f64 {
    let n = 32 << 20; // 32 Mi f32 = 128 MiB per array
    let src = vec![1.0f32; n];
    let mut dst = vec![0.0f32; n];
    let secs = median_secs(9, || {
        dst.copy_from_slice(black_box(&src));
        black_box(&mut dst);
    });
    (2 * n * 4) as f64 / secs
}

fn summary() {
    let bw = copy_bandwidth();
    println!("\n## school summary (one core, medians)\n");
    println!("STREAM-like copy bandwidth: {:.2} GB/s\n", bw / 1e9);
    println!(
        "| N | step ns/fish | grid ns/fish | steer ns/fish | integrate ns/fish | step ms | integrate GB/s | integrate / copy |"
    );
    println!("|---|---|---|---|---|---|---|---|");
    for n in SIZES {
        let (mut s, bounds) = school(n);
        let env = Environment::new(bounds);
        let reps = if n >= 1_000_000 {
            7
        } else if n >= 100_000 {
            15
        } else {
            51
        };
        let step = median_secs(reps, || s.step(1.0 / 60.0, &env));
        let grid = median_secs(reps, || s.rebuild_grid(&env));
        let steer = median_secs(reps, || s.compute_steering(&env));
        let integ = median_secs(reps, || s.integrate(1.0 / 60.0, &env));
        let per = |t: f64| t * 1e9 / n as f64;
        let bytes = (School::INTEGRATE_BYTES_PER_FISH * n) as f64;
        println!(
            "| {n} | {:.1} | {:.1} | {:.1} | {:.1} | {:.2} | {:.2} | {:.0} % |",
            per(step),
            per(grid),
            per(steer),
            per(integ),
            step * 1e3,
            bytes / integ / 1e9,
            100.0 * bytes / integ / bw
        );
    }
}

criterion_group!(benches, bench_school);

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
