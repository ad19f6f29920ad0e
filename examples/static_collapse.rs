//! A static load-control analysis to collapse of a square running-bond wall (0.4 x 0.175 m
//! blocks, dry joints, mu = psi = 0.65, default options), timed by the solver's own clock:
//!
//!     cargo run --release --example static_collapse -- 32        # courses (32: 1,040 blocks)
//!     cargo run --release --example static_collapse -- 32 steps  # and every converged step, with the time
use masonry_dem::model::Model;
use masonry_dem::static_solver::{solve_with, StaticOptions};

#[path = "../benches/common/walls.rs"]
mod walls;

fn main() {
    let courses: usize = std::env::args().nth(1).and_then(|s| s.parse().ok()).unwrap_or(32);
    let verbose = std::env::args().nth(2).as_deref() == Some("steps");
    let model = Model::new(walls::associative(courses)).expect("model");
    let start = std::time::Instant::now();
    let r = solve_with(&model, &StaticOptions::default(), &mut |p| {
        if verbose && !p.poll {
            eprintln!(
                "step {:4}  lambda {:.6}  u {:.4e} m  {:8.3} s",
                p.step,
                p.multiplier,
                p.displacement,
                start.elapsed().as_secs_f64()
            );
        }
        true
    })
    .expect("options");
    println!(
        "{} blocks: lambda {:.5} (last equilibrium {:.5}), {:?}, {} steps, {} Newton iterations, {:.3} s",
        model.n_blocks(),
        r.collapse_multiplier,
        r.last_equilibrium,
        r.status,
        r.steps,
        r.iterations,
        r.elapsed_s
    );
    if let Some(e) = &r.error {
        println!("  {e}");
    }
}
