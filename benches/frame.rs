//! Frame time of the default water scene at 1280×720 on the adapter at hand (lavapipe when
//! there is no GPU): CPU time (snapshot, uploads, command recording) and GPU time (submit to
//! idle), reported as two criterion benchmarks; plus one fixed simulation step (school and
//! floating bodies), which the window adds to each frame.
//!
//! `CARGO_TARGET_DIR=/work/target-release cargo bench --bench frame`

use std::path::Path;
use std::time::Duration;

use criterion::{Criterion, criterion_group, criterion_main};
use lectern::render::Headless;
use lectern::scene;

const SIZE: (u32, u32) = (1280, 720);

fn frame(c: &mut Criterion) {
    let s = scene::load_scene(Path::new(scene::DEFAULT_SCENE)).expect("default scene");
    let mut h = Headless::new(s, Path::new("shaders")).expect("renderer");
    let info = &h.gpu.adapter_info;
    eprintln!(
        "adapter: {} ({:?}, {:?})",
        info.name, info.backend, info.device_type
    );
    h.sim.set_time(2.5);
    h.timed_frame(SIZE).expect("warm-up frame");
    let mut group = c.benchmark_group("frame_1280x720");
    group
        .sample_size(10)
        .measurement_time(Duration::from_secs(8))
        .warm_up_time(Duration::from_secs(1));
    group.bench_function("cpu", |b| {
        b.iter_custom(|iters| {
            (0..iters)
                .map(|_| h.timed_frame(SIZE).expect("frame").0)
                .sum()
        })
    });
    group.bench_function("gpu", |b| {
        b.iter_custom(|iters| {
            (0..iters)
                .map(|_| h.timed_frame(SIZE).expect("frame").1)
                .sum()
        })
    });
    group.finish();

    // the simulation step each frame also pays in the window (fish + floating bodies)
    let mut group = c.benchmark_group("scene_sim");
    group
        .sample_size(10)
        .measurement_time(Duration::from_secs(5));
    let fish = h.sim.fish_count();
    group.bench_function(format!("fixed_step_{fish}_fish_3_bodies"), |b| {
        b.iter(|| h.sim.step_once())
    });
    group.finish();
}

criterion_group!(benches, frame);
criterion_main!(benches);
