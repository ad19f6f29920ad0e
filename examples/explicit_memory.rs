//! Memory of the explicit solver per interface: the growth of the process's peak resident set
//! (VmHWM, Linux's /proc/self/status) from the start of the process over building the model of
//! the bench's largest wall (316 courses of 316 blocks: 100,014 blocks, 299,095 interfaces), its
//! integrator and 5 time steps, divided by the number of interfaces. Issue 5's target: at most
//! 500 bytes per interface.
//!
//! `cargo run --release --example explicit_memory -- [threads] [courses]` (2 and 316 by default).

use masonry_dem::explicit::{Damping, Stepper};
use masonry_dem::model::Model;

#[path = "../benches/common/walls.rs"]
mod walls;

/// The peak resident set of this process so far, in bytes.
fn peak_rss() -> u64 {
    let status = std::fs::read_to_string("/proc/self/status").expect("/proc/self/status (Linux only)");
    let line = status.lines().find(|l| l.starts_with("VmHWM:")).expect("a VmHWM line");
    let kb: u64 = line.split_whitespace().nth(1).and_then(|v| v.parse().ok()).expect("VmHWM in kB");
    kb * 1024
}

fn main() {
    let arg = |i: usize, default: usize| std::env::args().nth(i).and_then(|s| s.parse().ok()).unwrap_or(default);
    let (threads, courses) = (arg(1, 2), arg(2, 316));
    let before = peak_rss();
    let model = Model::new(walls::spec(courses, courses)).expect("model");
    let mut stepper = Stepper::new(&model, 0.0, Damping::Local(0.8), false, threads).expect("integrator");
    stepper.run(5);
    let grown = peak_rss() - before;
    let m = model.interfaces().len();
    println!(
        "{} wall blocks, {m} interfaces, {threads} thread(s): peak RSS grew by {:.1} MB, {:.1} bytes per interface",
        model.n_wall(),
        grown as f64 / 1e6,
        grown as f64 / m as f64
    );
}
