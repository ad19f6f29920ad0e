//! Throughput of the explicit solver: time steps on running-bond walls (dry joints), on 1 and 2
//! threads, reported by criterion as interface updates per second. `cargo bench --bench explicit_step`.

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use masonry_dem::explicit::{simulate, DynamicOptions};
use masonry_dem::geometry::{running_bond, FirstCourse, RunningBond};
use masonry_dem::model::{Model, ModelSpec};

fn wall(courses: usize, blocks_per_course: usize) -> Model {
    let blocks = running_bond(&RunningBond {
        block_length: 0.4,
        block_height: 0.175,
        courses,
        length: 0.4 * blocks_per_course as f64,
        first_course: FirstCourse::Half,
        openings: vec![],
    })
    .unwrap();
    Model::new(ModelSpec { blocks, gravity: 10.0, ..ModelSpec::default() }).unwrap()
}

const STEPS: usize = 100;

fn bench(c: &mut Criterion) {
    let mut g = c.benchmark_group("explicit_100_steps");
    g.sample_size(10);
    for (courses, per) in [(10, 10), (32, 32), (100, 100)] {
        let model = wall(courses, per);
        let dt = 0.8 * masonry_dem::explicit::critical_time_step(&model);
        g.throughput(Throughput::Elements((model.interfaces().len() * STEPS) as u64));
        for threads in [1, 2] {
            let opts = DynamicOptions {
                duration: (STEPS as f64 - 0.5) * dt,
                time_step: Some(dt),
                record_every: STEPS * 10,
                large_rotations: false,
                threads,
                ..DynamicOptions::default()
            };
            let name = format!("{}_blocks_{}_threads", model.n_wall(), threads);
            g.bench_function(name, |b| b.iter(|| simulate(&model, &opts).unwrap()));
        }
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
