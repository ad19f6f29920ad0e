//! The static solver's targets on walls of the literature: Ferris & Tin-Loi's walls 1 to 6
//! (mu = 0.65, g = 10; walls 3 to 6 as in tests/python/test_limit_analysis.py) and the LACT3
//! tilting wall (examples/lact3-tilting-wall.toml), each with associative joints (dilatancy =
//! friction; against limit analysis, exact there) or with dilatancy 0 (`-- 0`). Times are the
//! solver's own clock, the median of `repeat` runs:
//!
//!     cargo run --release --example static_targets              # associative, 3 runs each
//!     cargo run --release --example static_targets -- 0 1       # dilatancy 0, 1 run each
//!     cargo run --release --example static_targets -- 0 1 dynamic  # and the explicit solver beside it
use masonry_dem::explicit::{self, ExplicitOptions};
use masonry_dem::geometry::{polygons, pattern, running_bond, FirstCourse, Rect, RunningBond};
use masonry_dem::joint::JointLaw;
use masonry_dem::limit::{limit_analysis, LimitOptions};
use masonry_dem::model::{JointLaws, Model, ModelSpec};
use masonry_dem::static_solver::{solve, StaticOptions};

fn model(blocks: Vec<Rect>, mu: f64, psi: f64, g: f64) -> Model {
    let law = JointLaw { friction: mu, dilatancy: psi, normal_stiffness: 1e10, shear_stiffness: 1e10, ..JointLaw::default() };
    Model::new(ModelSpec { blocks: polygons(blocks), gravity: g, joints: JointLaws::uniform(law), ..ModelSpec::default() }).expect("model")
}

fn ferris(courses: usize) -> Vec<Rect> {
    let p = RunningBond {
        block_length: 0.4,
        block_height: 0.175,
        courses,
        height: None,
        length: 2.0,
        first_course: FirstCourse::Half,
        openings: vec![],
    };
    running_bond(&p).expect("wall")
}

/// Ferris & Tin-Loi's walls 3 to 6, course by course (tests/python/test_limit_analysis.py).
fn ferris_pattern(number: usize) -> Vec<Rect> {
    let v = |s: &[f64]| s.to_vec();
    let (e, u, we, wu, order): (Vec<f64>, Vec<f64>, Vec<f64>, Vec<f64>, &str) = match number {
        3 => (v(&[1., 1., 1., 1.]), v(&[0.5, 1., 1., 1., 0.5]), v(&[1., 0.5, -1., 0.5, 1.]), v(&[0.5, 1., -1., 1., 0.5]), "e u e wu we wu we wu e u e"),
        4 => (v(&[0.5, 1., 1., 1., 1., 0.5]), v(&[1.; 5]), v(&[0.5, 0.5, -1., 0.5, 0.5, -1., 0.5, 0.5]), v(&[1., -1., 1., -1., 1.]), "e u e wu we wu we wu e u e"),
        5 => (v(&[0.5, 1., 1., 0.5]), v(&[1.; 3]), v(&[0.5, 0.5, -1., 0.5, 0.5]), v(&[1., -1., 1.]), "e u e wu we wu we wu e u e wu we wu we wu e u e"),
        _ => (
            v(&[0.5, 1., 1., 1., 1., 1., 1., 0.5]),
            v(&[1.; 7]),
            v(&[1., 0.5, -1., 0.5, 1., 0.5, -1., 0.5, 1.]),
            v(&[0.5, 1., -1., 1., 1., -1., 1., 0.5]),
            "e u e u wu we wu we wu u e u wu we wu we wu u e u e",
        ),
    };
    let rows: Vec<Vec<f64>> = order
        .split(' ')
        .map(|c| match c {
            "e" => e.clone(),
            "u" => u.clone(),
            "we" => we.clone(),
            _ => wu.clone(),
        })
        .collect();
    pattern(0.4, 0.175, &rows).expect("wall")
}

/// The blocks of examples/lact3-tilting-wall.toml (its lines `  [x0, y0, x1, y1],`).
fn lact3() -> Vec<Rect> {
    let text = include_str!("lact3-tilting-wall.toml");
    text.lines()
        .filter(|l| l.starts_with("  ["))
        .map(|l| {
            let v: Vec<f64> = l.trim().trim_matches(|c| c == '[' || c == ']' || c == ',').split(',').map(|s| s.trim().parse().unwrap()).collect();
            Rect::new(v[0], v[1], v[2], v[3])
        })
        .collect()
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let psi_zero = args.get(1).map(|s| s == "0").unwrap_or(false);
    let repeat: usize = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(3);
    let mu_l3 = 0.487733;
    let mut walls: Vec<(String, Vec<Rect>, f64, f64)> = (1..=6)
        .map(|n| {
            let b = match n {
                1 => ferris(6),
                2 => ferris(10),
                n => ferris_pattern(n),
            };
            (format!("F&TL wall {n}"), b, 0.65, 10.0)
        })
        .collect();
    walls.push(("LACT3".into(), lact3(), mu_l3, 9.81));
    for (name, blocks, mu, g) in walls {
        let m = model(blocks, mu, if psi_zero { 0.0 } else { mu }, g);
        let mut times = vec![];
        let mut last = None;
        for _ in 0..repeat {
            let r = solve(&m, &StaticOptions::default()).expect("options");
            times.push(r.elapsed_s);
            last = Some(r);
        }
        times.sort_by(f64::total_cmp);
        let r = last.unwrap();
        let mut lp_times = vec![];
        let mut lp = f64::NAN;
        for _ in 0..if psi_zero { 0 } else { repeat } {
            let l = limit_analysis(&m, &LimitOptions::default()).unwrap();
            lp_times.push(l.elapsed_s);
            lp = l.collapse_multiplier;
        }
        lp_times.sort_by(f64::total_cmp);
        let lp_time = lp_times.get(lp_times.len() / 2).copied().unwrap_or(f64::NAN);
        println!(
            "{name:12} {:4} blocks  {:?}  lambda {:.6} (last {:.6})  LP {:.6}  {:+.4}%  {} steps {} iterations  median {:.4} s (limit analysis {:.4} s)",
            m.n_blocks(),
            r.status,
            r.collapse_multiplier,
            r.last_equilibrium,
            lp,
            100.0 * (r.last_equilibrium - lp) / lp,
            r.steps,
            r.iterations,
            times[times.len() / 2],
            lp_time
        );
        if let Some(e) = &r.error {
            println!("    {e}");
        }
        if args.get(3).map(|s| s == "dynamic").unwrap_or(false) {
            let opts = ExplicitOptions { threads: 1, ..ExplicitOptions::default() };
            let x = explicit::solve(&m, &opts).expect("options");
            println!(
                "    explicit: {:?}  lambda {:.6} (last {:.6})  static - explicit {:+.3}%  {:.1} s",
                x.status,
                x.collapse_multiplier,
                x.last_equilibrium,
                100.0 * (r.last_equilibrium - x.last_equilibrium) / x.last_equilibrium,
                x.elapsed_s
            );
        }
    }
}
