//! A static load-control analysis to collapse of a square running-bond wall (0.4 x 0.175 m
//! blocks, dry joints, mu = psi = 0.65, default options), timed by the solver's own clock:
//!
//!     cargo run --release --example static_collapse -- 32        # courses (32: 1,040 blocks)
//!     cargo run --release --example static_collapse -- 32 steps  # and every converged step
use masonry_dem::geometry::{running_bond, FirstCourse, RunningBond};
use masonry_dem::joint::JointLaw;
use masonry_dem::model::{JointLaws, Model, ModelSpec};
use masonry_dem::static_solver::{solve_with, StaticOptions};

fn main() {
    let courses: usize = std::env::args().nth(1).and_then(|s| s.parse().ok()).unwrap_or(32);
    let verbose = std::env::args().nth(2).as_deref() == Some("steps");
    let blocks = running_bond(&RunningBond {
        block_length: 0.4,
        block_height: 0.175,
        courses,
        length: 0.4 * courses as f64,
        first_course: FirstCourse::Half,
        openings: vec![],
    })
    .expect("wall");
    let law = JointLaw { friction: 0.65, dilatancy: 0.65, ..JointLaw::default() };
    let spec = ModelSpec { blocks, gravity: 10.0, joints: JointLaws::uniform(law), ..ModelSpec::default() };
    let model = Model::new(spec).expect("model");
    let r = solve_with(&model, &StaticOptions::default(), &mut |p| {
        if verbose && !p.poll {
            eprintln!("step {:4}  lambda {:.6}  u {:.4e} m", p.step, p.multiplier, p.displacement);
        }
        true
    })
    .expect("options");
    println!(
        "{} blocks: lambda {:.5}, {:?}, {} steps, {} Newton iterations, {:.3} s",
        model.n_blocks(),
        r.collapse_multiplier,
        r.status,
        r.steps,
        r.iterations,
        r.elapsed_s
    );
}
