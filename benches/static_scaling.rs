//! The stages of a static analysis on running-bond walls of about 10^2, 10^3, 10^4 and 10^5
//! blocks (dry joints, mu = 0.65, associative): the model (interface detection included), one
//! evaluation of every joint (return mapping), one assembly of the tangent, one factorization
//! (a symmetric tangent: sparse Cholesky), and one static increment (the dead-load state, from
//! rest: Newton with factorizations, line search and joint evaluations).
//!
//! `cargo bench --features bench-internals --bench static_scaling`; one size: `cargo bench --features
//! bench-internals --bench static_scaling -- 1e4`.
//! The whole analysis to collapse is timed by `benches/scaling.py` (one run per size).

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use masonry_dem::model::Model;
use masonry_dem::static_solver::stages::Stages;
use masonry_dem::static_solver::{solve, Control, StaticOptions};
use std::hint::black_box;

#[path = "common/walls.rs"]
mod walls;

const SIZES: [(&str, usize); 4] = [("1e2", 10), ("1e3", 32), ("1e4", 100), ("1e5", 316)];

fn bench(c: &mut Criterion) {
    let mut g = c.benchmark_group("static_scaling");
    g.sample_size(10);
    for (label, courses) in SIZES {
        let sp = walls::associative(courses);
        let model = Model::new(sp.clone()).unwrap();
        let (nb, m) = (model.n_blocks(), model.interfaces().len());
        eprintln!("{label}: {nb} blocks, {m} interfaces");
        g.throughput(Throughput::Elements(nb as u64));
        g.bench_with_input(BenchmarkId::new("model", label), &sp, |b, sp| {
            b.iter(|| Model::new(black_box(sp.clone())).unwrap())
        });
        let mut st = Stages::new(&model).unwrap();
        g.throughput(Throughput::Elements(m as u64));
        g.bench_function(BenchmarkId::new("evaluate", label), |b| b.iter(|| st.evaluate()));
        g.bench_function(BenchmarkId::new("assemble", label), |b| b.iter(|| st.assemble()));
        st.assemble();
        st.factorize().unwrap(); // the symbolic analysis, once
        g.throughput(Throughput::Elements(st.n_eq() as u64));
        g.bench_function(BenchmarkId::new("factorize", label), |b| b.iter(|| st.factorize().unwrap()));
        // the dead-load state and one displacement step of 1 um
        let opts = StaticOptions {
            control: Control::Displacement { max_displacement: 1e-6 },
            steps: 1,
            ..StaticOptions::default()
        };
        g.throughput(Throughput::Elements(nb as u64));
        g.bench_function(BenchmarkId::new("increment", label), |b| {
            b.iter(|| solve(black_box(&model), &opts).unwrap())
        });
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
