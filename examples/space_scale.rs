//! Limit analysis in 3D at scale: a U-shaped building wall (a facade with two return walls,
//! courses interlocked at the corners, a row of window openings per storey) pushed out of the
//! facade's plane, timed by the analysis's own clock, with the process's peak memory:
//!
//!     cargo run --release --example space_scale -- 3 2.5 1.5            # the 3 x 2.5 m U-wall, returns 1.5 m
//!     cargo run --release --example space_scale -- 40 10 8 openings     # a facade of about 10^4 blocks
//!
//! `THREADS=n` runs it on n threads (default: all cores); `VERBOSE=1` prints each iteration.
use masonry_dem::joint::JointLaw;
use masonry_dem::limit::{limit_analysis_3d_with, LimitOptions};
use masonry_dem::model::JointLaws;
use masonry_dem::space::{cut_openings, u_wall, LiveLoad3, Model3, ModelSpec3};

/// The process's peak resident memory [MB] (Linux), or NaN.
fn peak_rss_mb() -> f64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| s.lines().find(|l| l.starts_with("VmHWM:")).map(|l| l.to_string()))
        .and_then(|l| l.split_whitespace().nth(1).and_then(|v| v.parse::<f64>().ok()))
        .map_or(f64::NAN, |kb| kb / 1024.0)
}

fn main() {
    let arg = |i: usize, d: f64| std::env::args().nth(i).and_then(|s| s.parse().ok()).unwrap_or(d);
    let (facade, height, returns) = (arg(1, 3.0), arg(2, 2.5), arg(3, 1.5));
    let openings = std::env::args().nth(4).as_deref() == Some("openings");
    let (t, bl, bh) = (0.25, 0.5, 0.25);
    let mut blocks = u_wall(facade, height, returns, t, bl, bh).expect("u_wall");
    if openings {
        // windows 1 m wide and 1.25 m high, one per 2.5 m bay and per 2.5 m storey
        let mut holes = vec![];
        let (mut x, mut z) = (1.0, 0.75);
        while z + 1.25 < height - 0.5 {
            while x + 1.0 < facade - 1.0 {
                holes.push([x, z, x + 1.0, z + 1.25]);
                x += 2.5;
            }
            x = 1.0;
            z += 2.5;
        }
        blocks = cut_openings(blocks, &holes).expect("openings");
    }
    let law = JointLaw { friction: 0.7, dilatancy: 0.7, ..JointLaw::default() };
    let spec = ModelSpec3 {
        blocks,
        joints: JointLaws::uniform(law),
        live: LiveLoad3::HorizontalWeight { direction: 90.0 },
        ..ModelSpec3::default()
    };
    let start = std::time::Instant::now();
    let model = Model3::new(&spec).expect("model");
    let built = start.elapsed().as_secs_f64();
    let threads = std::env::var("THREADS").ok().and_then(|v| v.parse().ok()).unwrap_or(0);
    let opts = LimitOptions { threads, ..LimitOptions::default() };
    let r = limit_analysis_3d_with(&model, &opts, &mut |p| {
        if std::env::var_os("VERBOSE").is_some() {
            let t = start.elapsed().as_secs_f64() - built;
            eprintln!("iteration {:3}  lambda {:.9}  residual {:.2e}  {t:7.3} s", p.iteration, p.multiplier, p.residual);
        }
        true
    })
    .expect("limit analysis");
    let c = r.certificate.expect("certificate");
    println!(
        "{} blocks, {} contacts: lambda {:.9}, {:?}, {} iterations, model {:.3} s, analysis {:.3} s, residuals {:.1e} / {:.1e}, gap {:.1e}, peak RSS {:.1} MB",
        model.n_wall(),
        model.contacts().len(),
        r.collapse_multiplier,
        r.status,
        c.iterations,
        built,
        r.elapsed_s,
        c.primal_residual,
        c.dual_residual,
        c.duality_gap,
        peak_rss_mb()
    );
}
