//! Limit analysis of a square running-bond wall (0.4 x 0.175 m blocks, dry joints,
//! mu = psi = 0.65), timed by the analysis's own clock, with the peak memory of the process:
//!
//!     cargo run --release --example limit_collapse -- 100          # courses (100: 10,050 blocks)
//!     cargo run --release --example limit_collapse -- 100 verbose  # and every iteration
use masonry_dem::limit::{limit_analysis_with, LimitOptions};
use masonry_dem::model::Model;

#[path = "../benches/common/walls.rs"]
mod walls;

/// The process's peak resident memory [MB] (Linux), or NaN.
fn peak_rss_mb() -> f64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| s.lines().find(|l| l.starts_with("VmHWM:")).map(|l| l.to_string()))
        .and_then(|l| l.split_whitespace().nth(1).and_then(|v| v.parse::<f64>().ok()))
        .map_or(f64::NAN, |kb| kb / 1024.0)
}

fn main() {
    let courses: usize = std::env::args().nth(1).and_then(|s| s.parse().ok()).unwrap_or(32);
    let verbose = std::env::args().nth(2).as_deref() == Some("verbose");
    let model = Model::new(walls::associative(courses)).expect("model");
    let start = std::time::Instant::now();
    let r = limit_analysis_with(&model, &LimitOptions::default(), &mut |p| {
        if verbose {
            eprintln!(
                "iteration {:3}  lambda {:.9}  residual {:.2e}  {:8.3} s",
                p.iteration,
                p.multiplier,
                p.residual,
                start.elapsed().as_secs_f64()
            );
        }
        true
    })
    .expect("options");
    let c = r.certificate.expect("certificate");
    println!(
        "{} blocks: lambda {:.9}, {:?}, {} iterations, {:.3} s, residuals {:.1e} / {:.1e}, gap {:.1e}, peak RSS {:.1} MB",
        model.n_blocks(),
        r.collapse_multiplier,
        r.status,
        c.iterations,
        r.elapsed_s,
        c.primal_residual,
        c.dual_residual,
        c.duality_gap,
        peak_rss_mb()
    );
}
