//! Static pushover (load control to collapse) of Ferris & Tin-Loi wall 2 (55 blocks, dry
//! joints, mu = 0.65), associative and non-associative. `cargo bench`.

use criterion::{criterion_group, criterion_main, Criterion};
use masonry_dem::geometry::{polygons, running_bond, FirstCourse, RunningBond};
use masonry_dem::joint::JointLaw;
use masonry_dem::model::{JointLaws, Model, ModelSpec};
use masonry_dem::static_solver::{solve, StaticOptions};
use std::hint::black_box;

fn wall2(dilatancy: f64) -> Model {
    let blocks = running_bond(&RunningBond {
        block_length: 0.4,
        block_height: 0.175,
        courses: 10,
        height: None,
        length: 2.0,
        first_course: FirstCourse::Half,
        openings: vec![],
    })
    .unwrap();
    let law = JointLaw {
        friction: 0.65,
        dilatancy,
        ..JointLaw::default()
    };
    Model::new(ModelSpec {
        blocks: polygons(blocks),
        gravity: 10.0,
        joints: JointLaws::uniform(law),
        ..ModelSpec::default()
    })
    .unwrap()
}

fn bench(c: &mut Criterion) {
    let mut g = c.benchmark_group("static_pushover");
    g.sample_size(10);
    for (name, psi) in [("wall2_associative", 0.65), ("wall2_non_associative", 0.0)] {
        let model = wall2(psi);
        g.bench_function(name, |b| {
            b.iter(|| solve(black_box(&model), &StaticOptions::default()).unwrap())
        });
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
