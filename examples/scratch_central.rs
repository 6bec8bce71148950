use railcontact::contact_search::WheelOnRail;
use railcontact::contact_search::{
    ContactCandidates, Region, SidePose, StripPoints, DEFAULT_B_MIN, DEFAULT_SCAN_STEP,
};
use railcontact::profile::Profile;
use railcontact::strips::StripGeometry;
use railcontact::track::TrackSetup;

fn main() {
    let w = Profile::load(
        "../shared/profiles/MBench_S1002_v3.prw",
        railcontact::profile::ProfileKind::Wheel,
        0.0,
    )
    .unwrap();
    let r = Profile::load(
        "../shared/profiles/MBench_UIC60_v3.prr",
        railcontact::profile::ProfileKind::Rail,
        0.0,
    )
    .unwrap();
    let setup = TrackSetup {
        rail_inclination: 0.0,
        ..TrackSetup::default()
    };
    let mut g = WheelOnRail::new(w, &r, &setup, DEFAULT_SCAN_STEP, DEFAULT_B_MIN).unwrap();
    let dy: f64 = std::env::args()
        .nth(1)
        .map(|a| a.parse().unwrap())
        .unwrap_or(0.0);
    let extra: f64 = std::env::args()
        .nth(2)
        .map(|a| a.parse().unwrap())
        .unwrap_or(0.02);
    let mut c = ContactCandidates::default();
    g.search(
        &SidePose {
            lateral: dy * 1e-3,
            yaw: 2.4e-3 * dy,
            roll: 0.0,
        },
        &mut c,
    )
    .unwrap();
    for p in c.as_slice() {
        println!(
            "cand w={:.3}mm gap={:.4}mm yrail={:.3} gamma={:.4} B={:.3}",
            p.lateral * 1e3,
            p.gap * 1e3,
            p.y_rail * 1e3,
            p.contact_angle,
            p.curv_b
        );
    }
    let deepest = c
        .as_slice()
        .iter()
        .min_by(|a, b| a.gap.total_cmp(&b.gap))
        .unwrap();
    let plane = g.contact_plane(deepest.lateral, deepest.gap);
    println!("plane {:?}", plane);
    let dz = deepest.gap + extra * 1e-3;
    let mut regs = [Region::default(); 3];
    let n = g.regions(dz, &mut regs);
    println!("regions {:?}", &regs[..n]);
    for reg in &regs[..n] {
        let s_lo = g.plane_coordinate_at(&plane, reg.first as f64 - 1.0);
        let s_hi = g.plane_coordinate_at(&plane, reg.last as f64 + 1.0);
        println!("s range {:.3} {:.3} mm", s_lo * 1e3, s_hi * 1e3);
        let mut geom = StripGeometry::default();
        let mut pts = StripPoints::default();
        g.strip_geometry(
            &plane,
            s_lo.min(s_hi),
            s_hi.max(s_lo),
            20,
            &mut geom,
            &mut pts,
        );
        for i in 0..geom.n {
            println!(
                "{:8.3} f={:9.5}mm A={:.4} B={:8.3} yr={:8.3} gam={:.4} lat={:.3}",
                geom.s[i] * 1e3,
                geom.f[i] * 1e3,
                geom.curv_a[i],
                geom.curv_b[i],
                pts.y_rail[i] * 1e3,
                pts.contact_angle[i],
                pts.lateral[i] * 1e3
            );
        }
    }
}
