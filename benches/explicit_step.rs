//! Throughput of the explicit solver: ONE velocity-Verlet time step (interface forces, gather
//! onto the blocks, accelerations, velocity and position updates) of running-bond walls of
//! about 10^2, 10^3, 10^4 and 10^5 blocks (0.4 x 0.175 m blocks, dry joints, square walls of
//! ~sqrt(n) courses), on 1 and 2 threads, under self-weight with local damping 0.8 (the
//! quasi-static setting) and the linearized kinematics. Criterion reports interface updates per
//! second (`Throughput::Elements(interfaces)`).
//!
//! Everything else is outside the timed region: the model, the integrator (thread pool, time
//! step, work arrays) and 20 warm-up steps.
//!
//! `cargo bench --features bench-internals --bench explicit_step`; one size or thread count:
//! `cargo bench --features bench-internals --bench explicit_step -- 100000_blocks/2_threads`
//! (criterion's filter, a regular expression).
//! `EXPLICIT_STEP_LARGE=1` benches the finite-rotation kinematics of time histories instead.

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use masonry_dem::explicit::{Damping, Stepper};
use masonry_dem::model::Model;
use std::time::Duration;

#[path = "common/walls.rs"]
mod walls;

fn wall(courses: usize, blocks_per_course: usize) -> Model {
    Model::new(walls::spec(courses, blocks_per_course)).unwrap()
}

fn bench(c: &mut Criterion) {
    let large = std::env::var("EXPLICIT_STEP_LARGE").is_ok_and(|v| v == "1");
    let mut g = c.benchmark_group(if large { "explicit_step_large_rotations" } else { "explicit_step" });
    g.sample_size(20).warm_up_time(Duration::from_secs(2)).measurement_time(Duration::from_secs(4));
    for n in [10, 32, 100, 316] {
        let model = wall(n, n);
        g.throughput(Throughput::Elements(model.interfaces().len() as u64));
        for threads in [1, 2] {
            let mut s = Stepper::new(&model, 0.0, Damping::Local(0.8), large, threads).unwrap();
            s.run(20);
            let name = format!("{}_blocks/{}_threads", model.n_wall(), threads);
            g.bench_function(name, |b| b.iter(|| s.run(1)));
        }
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
