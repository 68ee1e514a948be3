//! Rest in V-grooves against the closed forms of thesis 002 §1.1.

use swarf_geom::TriMesh;
use swarf_path::Cutting;
use swarf_rest::{CleanupParams, Pattern, RegionParams, Source, detect, plan_cleanup};
use swarf_tool::Cutter;
use swarf_tool::drop::{DropScratch, MeshDropper};

/// (bottom line x, included angle in degrees) of the three grooves.
const GROOVES: [(f64, f64); 3] = [(20.0, 60.0), (55.0, 90.0), (105.0, 120.0)];

fn grooves() -> TriMesh {
    swarf_io::builtin_mesh("v-grooves").unwrap()
}

/// Height of a ball's tip of radius `r` resting in the V of included angle `deg`
/// (bottom at z = 0): the rest left at the bottom, `r / sin(a/2) - r`.
fn v_rest(r: f64, deg: f64) -> f64 {
    r / (deg.to_radians() / 2.0).sin() - r
}

#[test]
fn reference_detection_finds_each_groove_at_its_closed_form_depth() {
    let mesh = grooves();
    let ball: Cutter = "ball:d=12".parse().unwrap();
    let det = detect(
        &mesh,
        &ball,
        Source::Reference,
        0.01,
        &RegionParams::default(),
    )
    .unwrap();
    assert_eq!(
        det.regions.len(),
        3,
        "{:?}",
        det.regions.iter().map(|r| r.deepest).collect::<Vec<_>>()
    );
    let mut by_x: Vec<_> = det.regions.iter().collect();
    by_x.sort_by(|a, b| a.deepest.x.total_cmp(&b.deepest.x));
    for (r, (x, deg)) in by_x.iter().zip(GROOVES) {
        let exact = v_rest(6.0, deg);
        assert!(
            (r.depth - exact).abs() < 1e-6,
            "{deg}: {} vs {exact}",
            r.depth
        );
        assert!(
            (r.deepest.x - x).abs() < 1e-6 && r.deepest.z.abs() < 1e-6,
            "{:?}",
            r.deepest
        );
        // The region spans the groove's length.
        use geo::BoundingRect;
        let b = r.boundary.bounding_rect().unwrap();
        assert!(b.min().y < 1.0 && b.max().y > 59.0, "{b:?}");
    }
}

#[test]
fn pencil_points_lie_on_the_bisector_at_the_closed_form_height() {
    let mesh = grooves();
    let reference: Cutter = "ball:d=12".parse().unwrap();
    let det = detect(
        &mesh,
        &reference,
        Source::Reference,
        0.01,
        &RegionParams::default(),
    )
    .unwrap();
    let tool: Cutter = "ball:d=4".parse().unwrap();
    let cut = Cutting::new(tool);
    let params = CleanupParams {
        pattern: Pattern::FlowCut,
        passes: 0,
        ..CleanupParams::new(0.01)
    };
    let tp = plan_cleanup(&mesh, &det.regions, &reference, &cut, &params).unwrap();
    assert!(tp.passes.len() >= 3, "{}", tp.passes.len());
    let dropper = MeshDropper::new(&mesh, &tool);
    let mut scratch = DropScratch::default();
    let mut contacts = Vec::new();
    let mut seen = [0usize; 3];
    for p in tp.passes.iter().flat_map(|p| &p.points) {
        let cl = p.pose.cl;
        let (k, &(x, deg)) = GROOVES
            .iter()
            .enumerate()
            .min_by(|a, b| (a.1.0 - cl.x).abs().total_cmp(&(b.1.0 - cl.x).abs()))
            .unwrap();
        seen[k] += 1;
        assert!((cl.x - x).abs() < 1e-6, "{cl:?} off the bisector x = {x}");
        // Past the groove's ends (y outside [0, 60]) the ball hangs over the edge of
        // the part and rests lower, on the flanks' end edges.
        if cl.y >= 2.0 && cl.y <= 58.0 {
            assert!((cl.z - v_rest(2.0, deg)).abs() < 1e-6, "{cl:?}");
        }
        let hit = dropper
            .drop_with_contacts(cl.x, cl.y, 1e-6, &mut scratch, &mut contacts)
            .unwrap();
        assert!((hit.z - cl.z).abs() < 1e-6);
        let far = contacts
            .iter()
            .any(|a| contacts.iter().any(|b| (a.cc - b.cc).norm() > 1.0));
        assert!(far, "{cl:?}: one contact only");
    }
    assert!(seen.iter().all(|&n| n >= 2), "{seen:?}");
}
