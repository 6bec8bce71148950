//! A loop of `Wheelset::solve` for instruction counts (docs/performance.md): the benchmark's
//! central case (built-in S1002/UIC60, 78.5 kN per wheel, kinematic creepages at 30 m/s with
//! 0.1 % longitudinal creepage) at the default settings, steady, moving (y = 3 mm sin 2πt at
//! 1 ms steps) or hunting (y = 3 mm and yaw = 1 mrad, both sin 2π·5 Hz·t, with the consistent
//! lateral velocity and yaw rate). Wall-clock time on a shared machine varies by tens of per
//! cent from run to run; the instruction count of a fixed loop does not:
//!
//! ```sh
//! cargo build --release --example solve_loop
//! valgrind --tool=callgrind --callgrind-out-file=/dev/null target/release/examples/solve_loop analyn 300
//! ```
//!
//! Instructions per solve = (count at 300 solves − count at 100) / 200. Arguments: the normal
//! model (`hertz`, `linder`, `kik-piotrowski`, `stripes-b`, `stripes-ab`, `analyn`,
//! `coupled-strips`), the number
//! of solves, then optionally the motion (`steady`, `moving` or `hunting`), the tangential model
//! on strip patches (`model-default`, `equivalent-ellipse`, `fastrip`, `local-ellipses`, `fastrip-coupled`) and
//! `planar` for planar strip patches, then optionally the `wearModel` code (0–2; damage outputs
//! on with 1 or 2).

use railcontact::damage::WearModel;
use railcontact::normal::NormalModel;
use railcontact::tangential::patch::TangentialModel;
use railcontact::wheelset::WheelsetResult;

#[path = "../tests/common/mod.rs"]
mod common;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let usage =
        "usage: solve_loop MODEL SOLVES [steady|moving|hunting] [TANGENTIAL] [planar|non-planar] \
         [WEAR]";
    let model = args
        .get(1)
        .and_then(|name| NormalModel::from_name(name))
        .expect(usage);
    let solves: usize = args.get(2).and_then(|n| n.parse().ok()).expect(usage);
    let motion = args.get(3).map_or("steady", String::as_str);
    let tangential = args
        .get(4)
        .map_or(Some(TangentialModel::ModelDefault), |name| {
            TangentialModel::ALL.into_iter().find(|t| t.name() == name)
        });
    let tangential = tangential.expect(usage);
    let planar = args.get(5).is_some_and(|a| a == "planar");
    let wear = args
        .get(6)
        .map_or(Some(WearModel::Off), |code| {
            code.parse().ok().and_then(WearModel::from_code)
        })
        .expect(usage);
    let mut wheelset = common::builtin_wheelset_with(|settings| {
        settings.normal_model = model;
        settings.tangential = tangential;
        settings.planar_patch = planar;
        settings.damage.wear_model = wear;
    });
    let input = |k: usize| match motion {
        "steady" => common::central_input(0.0, 0.0),
        "moving" => common::central_input(common::moving_y(k as u64), 0.0),
        "hunting" => common::hunting_input(k as u64),
        _ => panic!("{usage}"),
    };
    let mut out = WheelsetResult::default();
    let start = std::time::Instant::now();
    for k in 0..solves {
        wheelset
            .solve(std::hint::black_box(&input(k)), &mut out)
            .expect("solve");
    }
    println!(
        "{} {motion} {}{}: {solves} solves, {:.2} µs each (wall clock, indicative only)",
        model.name(),
        tangential.name(),
        if planar { " planar" } else { "" },
        start.elapsed().as_secs_f64() / solves as f64 * 1e6
    );
}
