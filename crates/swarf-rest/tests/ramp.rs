//! Ramp rest (thesis 002 §3.1.3): a raster finish with a ramp angle limit across the
//! V-grooves, its ramp points, the ramp regions and their closed form.

use swarf_path::Cutting;
use swarf_path::strategy::raster::RasterParams;
use swarf_rest::{RegionParams, RestKind, Source, detect};
use swarf_tool::Cutter;
use swarf_tool::drop::{DropScratch, MeshDropper};

#[test]
fn a_ramp_limited_raster_leaves_ramp_rest_where_the_flanks_are_steeper() {
    let mesh = swarf_io::builtin_mesh("v-grooves").unwrap();
    let ball: Cutter = "ball:d=12".parse().unwrap();
    let mut params = RasterParams::new(2.0);
    params.max_ramp = Some(30f64.to_radians());
    let plan = swarf_path::strategy::raster::plan(&mesh, &Cutting::new(ball), &params).unwrap();
    let k = 30f64.to_radians().tan();
    let dropper = MeshDropper::new(&mesh, &ball);
    let mut s = DropScratch::default();
    let mut at_axis = Vec::new();
    for p in &plan.toolpath.passes {
        for w in p.points.windows(2) {
            let (a, b) = (w[0].pose.cl, w[1].pose.cl);
            let run = (b.x - a.x).hypot(b.y - a.y);
            assert!(
                (b.z - a.z).abs() <= k * run + 1e-9,
                "{a:?} -> {b:?} steeper than 30 degrees"
            );
        }
        for q in &p.points {
            let c = q.pose.cl;
            let drop = dropper
                .drop(c.x, c.y, &mut s)
                .map_or(f64::NEG_INFINITY, |d| d.z);
            assert!(c.z >= drop - 1e-9, "{c:?} below the drop height {drop}");
            if (c.x - 55.0).abs() < 1e-6 {
                at_axis.push(c.z);
            }
        }
    }
    // Over the 90 degree groove the ball leaves the convex top edge where its CL
    // curve falls at 30 degrees (3 mm in from the edge, height 4 + sqrt 27) and
    // descends at 30 degrees to the axis 7 mm on: 4 + 2 / sqrt 3 above the bottom.
    let exact = 4.0 + 2.0 / 3f64.sqrt();
    assert!(!at_axis.is_empty());
    for z in &at_axis {
        assert!((z - exact).abs() < 0.01, "{z} vs {exact}");
    }
    let ramps: Vec<_> = plan.double_contacts.iter().filter(|d| d.ramp).collect();
    assert!(!ramps.is_empty());
    // Ramp points on the 60 and 90 degree grooves (flanks steeper than 30 degrees),
    // none on the 120 degree one (flanks at exactly 30 degrees).
    for d in &ramps {
        let x = d.cl.x;
        assert!((x - 20.0).abs() < 10.0 || (x - 55.0).abs() < 12.0, "{x}");
    }
    let det = detect(
        &mesh,
        &ball,
        Source::Contacts(&plan.double_contacts),
        0.01,
        &RegionParams::default(),
    )
    .unwrap();
    let with_ramp = det
        .regions
        .iter()
        .filter(|r| r.kinds.contains(&RestKind::Ramp))
        .count();
    assert_eq!(with_ramp, 2);
    let lift_90 = det
        .regions
        .iter()
        .find(|r| (r.deepest.x - 55.0).abs() < 1.0)
        .unwrap();
    // The lifted ball leaves at least the lift above the axis (its bottom is there).
    assert!(
        lift_90.depth >= exact - (2f64.sqrt() * 6.0 - 6.0) - 0.01,
        "{}",
        lift_90.depth
    );
}

/// The ramp step under a 20-degree limit (parts/README.md): a ball of radius 5
/// leaves the plateau at CL x = 41.710 (tip z = 19.698), goes down at tan 20 and
/// lands on the floor at x = 95.831, lifted most (12.288 mm) at x = 62.071; the ramp
/// rest spans x in [40, 95.831].
#[test]
fn the_ramp_step_is_cut_at_the_limit_and_its_rest_found() {
    let mesh = swarf_io::builtin_mesh("ramp-step").unwrap();
    let ball: Cutter = "ball:d=10".parse().unwrap();
    let mut params = RasterParams::new(2.0);
    params.max_ramp = Some(20f64.to_radians());
    let plan = swarf_path::strategy::raster::plan(&mesh, &Cutting::new(ball), &params).unwrap();
    let k = 20f64.to_radians().tan();
    // Exact: the ball rolls off the edge (x = 40, z = 20) where its CL arc falls at
    // 20 degrees, 5 sin 20 past it.
    let (x0, z0) = (
        40.0 + 5.0 * 20f64.to_radians().sin(),
        15.0 + 5.0 * 20f64.to_radians().cos(),
    );
    let limited = |x: f64| (z0 - k * (x - x0)).clamp(0.0, 20.0);
    let dropper = MeshDropper::new(&mesh, &ball);
    let mut s = DropScratch::default();
    let mut lift = (0.0f64, 0.0);
    for q in plan.toolpath.passes.iter().flat_map(|p| &p.points) {
        let c = q.pose.cl;
        if (41.8..95.7).contains(&c.x) {
            // The limit holds between CL points, which the planner spaces to its
            // tolerance: the descent starts up to that late.
            assert!(
                (c.z - limited(c.x)).abs() < 0.01,
                "{c:?} vs {}",
                limited(c.x)
            );
        }
        let drop = dropper.drop(c.x, c.y, &mut s).unwrap().z;
        if c.z - drop > lift.0 {
            lift = (c.z - drop, c.x);
        }
    }
    assert!(
        (lift.0 - 12.288).abs() < 0.01 && (lift.1 - 62.071).abs() < 0.1,
        "{lift:?}"
    );
    let det = detect(
        &mesh,
        &ball,
        Source::Contacts(&plan.double_contacts),
        0.01,
        &RegionParams {
            overlap: 0.01,
            ..RegionParams::default()
        },
    )
    .unwrap();
    let ramp: Vec<_> = det
        .regions
        .iter()
        .filter(|r| r.kinds.contains(&RestKind::Ramp))
        .collect();
    assert_eq!(ramp.len(), 1);
    let xs = ramp[0].boundary.exterior().coords().map(|c| c.x);
    let (lo, hi) = xs.fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), x| {
        (l.min(x), h.max(x))
    });
    eprintln!("ramp rest x in [{lo}, {hi}], depth {}", ramp[0].depth);
    assert!(
        (lo - 40.0).abs() < 1.0 && (hi - 95.831).abs() < 1.0,
        "[{lo}, {hi}]"
    );
}
