//! Drop-and-spin passes along the shared edges (issue 13): every pose touches both
//! faces and cuts with the side asked for in both bands (dropped on either face), and the sectioning gouge check (whole
//! tool at every pose, against the part's upper envelope) finds no gouge between
//! the poses.

use swarf_fiveaxis::CurveOptions;
use swarf_fiveaxis::design::DesignSurface;
use swarf_fiveaxis::dsm::{Dsm, PassParams, Side};
use swarf_fiveaxis::gouge::{GougeOptions, check_pass};
use swarf_fiveaxis::sections::Sections;
use swarf_geom::Vec3;
use swarf_tool::profile::table::ProfileTable;
use swarf_tool::{Cutter, Pose};

const TOOL: &str = "bull:d=12,r=2,length=30";

fn params(side: Side) -> PassParams {
    PassParams {
        stations: (0..=16).map(|i| 10.0 + 5.0 * f64::from(i)).collect(),
        fractions: vec![0.5, 1.0],
        sides: vec![side],
        bands: vec![0, 1],
        max_turn: 10f64.to_radians(),
    }
}

#[test]
fn passes_touch_both_faces_and_gouge_neither() {
    let tool: Cutter = TOOL.parse().unwrap();
    for name in ["edge-concave", "edge-convex"] {
        let part = swarf_io::builtin_part(name).unwrap();
        let dsm = Dsm::new(&part, [0, 1], &tool, Vec3::x()).unwrap();
        let design = DesignSurface::new(&part).unwrap();
        let profile = tool.profile();
        let table = ProfileTable::new(&profile);
        for side in [Side::Leading, Side::Trailing] {
            let out = dsm.passes(&params(side), &|_| Ok(())).unwrap();
            eprintln!(
                "{name} {side:?}: {} passes, issues {:?}",
                out.passes.len(),
                out.issues
            );
            assert_eq!(out.passes.len(), 4, "{:?}", out.issues);
            assert!(out.issues.is_empty(), "{:?}", out.issues);
            for run in &out.poses {
                assert_eq!(run.len(), 17);
                for e in run {
                    assert_eq!(e.side, side);
                    let s = &e.spin;
                    assert!(s.clearance.abs() < 1e-6 && s.own_clearance > -1e-6, "{e:?}");
                    let ahead = (s.q - s.pose.cl).x;
                    match side {
                        Side::Leading => assert!(ahead > 0.0, "{e:?}"),
                        Side::Trailing => assert!(ahead < 0.0, "{e:?}"),
                    }
                }
            }
            let opts = GougeOptions {
                sections: Sections {
                    normal: Vec3::x(),
                    spacing: 0.25,
                    offset: 0.0,
                },
                tolerance: 0.01,
                curve: CurveOptions::default(),
                cap_meridians: 96,
                whole_tool: true,
            };
            let mut deepest = f64::NEG_INFINITY;
            for pass in &out.passes {
                let poses: Vec<Pose> = pass.points.iter().map(|p| p.pose).collect();
                for g in check_pass(&design, &table, &poses, &opts) {
                    deepest = deepest.max(g.depth);
                }
            }
            eprintln!("{name} {side:?}: deepest sectioning point {deepest:.5} mm");
            assert!(deepest <= 0.01, "gouge {deepest}");
        }
    }
}
