//! The explicit solver's step in 3D at scale: contact-point updates per second of a U-shaped
//! building wall with openings (the `space_scale` example's wall), on 1 and on 2 threads side by
//! side, the median of 7 runs of 200 time steps each (small rotations, local damping: a
//! quasi-static run's step; and finite rotations, a time history's):
//!
//!     cargo run --release --features bench-internals --example space_explicit_step -- 60 12.5 20
use masonry_dem::explicit::{Damping, Stepper3};
use masonry_dem::joint::JointLaw;
use masonry_dem::model::JointLaws;
use masonry_dem::space::{cut_openings, u_wall, LiveLoad3, Model3, ModelSpec3};

fn main() {
    let arg = |i: usize, d: f64| std::env::args().nth(i).and_then(|s| s.parse().ok()).unwrap_or(d);
    let (facade, height, returns) = (arg(1, 60.0), arg(2, 12.5), arg(3, 20.0));
    let blocks = u_wall(facade, height, returns, 0.25, 0.5, 0.25).expect("u_wall");
    // windows 1 m wide and 1.25 m high, one per 2.5 m bay and per 2.5 m storey
    let mut holes = vec![];
    let mut z = 0.75;
    while z + 1.25 < height - 0.5 {
        let mut x = 1.0;
        while x + 1.0 < facade - 1.0 {
            holes.push([x, z, x + 1.0, z + 1.25]);
            x += 2.5;
        }
        z += 2.5;
    }
    let blocks = cut_openings(blocks, &holes).expect("openings");
    let law = JointLaw { friction: 0.7, dilatancy: 0.7, ..JointLaw::default() };
    let spec = ModelSpec3 { blocks, joints: JointLaws::uniform(law), live: LiveLoad3::HorizontalWeight { direction: 90.0 }, ..ModelSpec3::default() };
    let model = Model3::new(&spec).expect("model");
    let (steps, runs) = (200, 7);
    for large in [false, true] {
        let mut line = vec![];
        for threads in [1, 2] {
            let mut s = Stepper3::new(&model, 0.1, Damping::Local(0.8), large, threads).expect("stepper");
            s.run(20);
            let mut t: Vec<f64> = (0..runs)
                .map(|_| {
                    let start = std::time::Instant::now();
                    s.run(steps);
                    start.elapsed().as_secs_f64()
                })
                .collect();
            t.sort_by(f64::total_cmp);
            let median = t[runs / 2];
            let rate = s.n_points() as f64 * steps as f64 / median;
            line.push(format!("{threads} thread(s): {:.3} ms a step, {:.2} M point updates/s", 1e3 * median / steps as f64, rate * 1e-6));
        }
        println!(
            "{} blocks, {} contact points, {}: {}",
            model.n_wall(),
            model.contacts().iter().map(|c| c.corners.len()).sum::<usize>(),
            if large { "finite rotations" } else { "small rotations" },
            line.join("; ")
        );
    }
}
