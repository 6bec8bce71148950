//! A loop of `Wheelset::solve` for instruction counts (docs/performance.md): the benchmark's
//! central case (built-in S1002/UIC60, 78.5 kN per wheel, kinematic creepages at 30 m/s with
//! 0.1 % longitudinal creepage) at the default settings, steady or moving (y = 3 mm sin 2πt at
//! 1 ms steps). Wall-clock time on a shared machine varies by tens of per cent from run to run;
//! the instruction count of a fixed loop does not:
//!
//! ```sh
//! cargo build --release --example solve_loop
//! valgrind --tool=callgrind --callgrind-out-file=/dev/null target/release/examples/solve_loop analyn 300
//! ```
//!
//! Instructions per solve = (count at 300 solves − count at 100) / 200. Arguments: the normal
//! model (`hertz`, `linder`, `kik-piotrowski`, `stripes-b`, `stripes-ab`, `analyn`), the number
//! of solves, and `moving` for the moving pose.

use railcontact::normal::NormalModel;
use railcontact::wheelset::WheelsetResult;

#[path = "../tests/common/mod.rs"]
mod common;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let usage = "usage: solve_loop MODEL SOLVES [moving]";
    let model = args
        .get(1)
        .and_then(|name| NormalModel::from_name(name))
        .expect(usage);
    let solves: usize = args.get(2).and_then(|n| n.parse().ok()).expect(usage);
    let moving = args.get(3).is_some_and(|a| a == "moving");
    let mut wheelset = common::builtin_wheelset_with(|settings| settings.normal_model = model);
    let input = |k: usize| {
        let y = if moving {
            common::moving_y(k as u64)
        } else {
            0.0
        };
        common::central_input(y, 0.0)
    };
    let mut out = WheelsetResult::default();
    let start = std::time::Instant::now();
    for k in 0..solves {
        wheelset
            .solve(std::hint::black_box(&input(k)), &mut out)
            .expect("solve");
    }
    println!(
        "{}: {solves} solves, {:.2} µs each (wall clock, indicative only)",
        model.name(),
        start.elapsed().as_secs_f64() / solves as f64 * 1e6
    );
}
