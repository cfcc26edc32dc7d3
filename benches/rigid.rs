//! Rigid-body step cost in ns/body: free bodies with each integrator, and a floating body
//! (gravity, buoyancy against the Gerstner sum, drag) with RK4.
//!
//! `CARGO_TARGET_DIR=/work/target-release cargo bench --bench rigid`

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group};
use glam::{DQuat, DVec3};
use lectern::rigid::{
    BuoyancySamples, Integrator, NoForces, RigidBody, TriMesh, WaterForces, mass,
};
use lectern::waves::{GerstnerWave, WaveSum};
use std::time::{Duration, Instant};

const BODIES: usize = 1000;

fn free_bodies(method: Integrator) -> Vec<RigidBody> {
    (0..BODIES)
        .map(|i| {
            let w = DVec3::new(0.01 + i as f64 * 1e-4, 1.0, 0.2);
            RigidBody::free_spinning(DVec3::new(1.0, 2.0, 3.0), w, method)
        })
        .collect()
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

fn bench_rigid(c: &mut Criterion) {
    let mut g = c.benchmark_group("rigid");
    g.throughput(Throughput::Elements(BODIES as u64));
    g.measurement_time(Duration::from_secs(2));
    g.warm_up_time(Duration::from_millis(500));
    for method in Integrator::ALL {
        let mut bodies = free_bodies(method);
        g.bench_with_input(BenchmarkId::new("free", method.name()), &method, |b, _| {
            b.iter(|| {
                bodies
                    .iter_mut()
                    .for_each(|body| body.step(1.0 / 60.0, &NoForces))
            })
        });
    }
    g.finish();
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
    c.bench_function("rigid/floating_rk4_64_samples", |b| {
        b.iter(|| body.step(1.0 / 60.0, &forces))
    });
}

fn summary() {
    println!("\n## rigid summary (one core, medians of 21 runs over {BODIES} bodies)\n");
    println!("| integrator | free body ns/step |");
    println!("|---|---|");
    for method in Integrator::ALL {
        let mut bodies = free_bodies(method);
        let mut t: Vec<f64> = (0..21)
            .map(|_| {
                let s = Instant::now();
                bodies
                    .iter_mut()
                    .for_each(|b| b.step(1.0 / 60.0, &NoForces));
                s.elapsed().as_secs_f64()
            })
            .collect();
        t.sort_by(f64::total_cmp);
        println!("| {} | {:.1} |", method.name(), t[10] * 1e9 / BODIES as f64);
    }
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
