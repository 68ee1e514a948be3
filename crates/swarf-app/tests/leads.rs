//! Lead arcs and ramps on the wave raster (jobs/wave-raster.toml with
//! `lead_radius = 3`, `ramp_angle = 10`): every pass is entered and left along a
//! quarter arc tangent to it, rising at 10 degrees, and the program, simulated on a
//! dexel stock against the design, gouges nowhere.

use swarf_app::{Job, PlanInput, plan};
use swarf_sim::{Design, Quiet, StockSpec, VerifyOptions};

#[test]
fn arc_and_ramp_leads_are_tangent_and_gouge_free() {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../jobs/wave-raster.toml"
    ))
    .unwrap()
    .replace(
        "[feeds]",
        "[linking]\nlead_radius = 3\nramp_angle = 10\n\n[feeds]",
    )
    .replace("scallop = 0.15", "scallop = 1.0");
    let job = Job::parse(&text, "wave-raster.toml").unwrap();
    let part = swarf_io::builtin_part("wave").unwrap();
    let mesh = part.tessellate(0.001).unwrap();
    let plan = plan(&job, PlanInput::Mesh(&mesh)).unwrap();
    let plain = {
        let mut j = job.clone();
        j.linking.lead_radius = None;
        j.linking.ramp_angle = None;
        swarf_app::plan(&j, PlanInput::Mesh(&mesh)).unwrap()
    };
    let mut checked = 0;
    for (with, without) in plan.toolpath.passes.iter().zip(&plain.toolpath.passes) {
        let (a, b) = (&with.points, &without.points);
        let lead = a.len() - b.len();
        assert!(lead >= 4 && lead % 2 == 0, "{lead} lead points");
        let n = lead / 2;
        let p0 = a[n].pose.cl;
        assert_eq!(p0, b[0].pose.cl, "the pass starts where it did");
        // Tangent: the last lead chord and the pass's first direction differ by at
        // most half the arc step (5 degrees).
        let before = a[n - 1].pose.cl;
        let after = b
            .iter()
            .map(|p| p.pose.cl)
            .find(|q| (q.x - p0.x).hypot(q.y - p0.y) > 1e-6)
            .unwrap();
        let (u, v) = (
            [p0.x - before.x, p0.y - before.y],
            [after.x - p0.x, after.y - p0.y],
        );
        let cos = (u[0] * v[0] + u[1] * v[1]) / (u[0].hypot(u[1]) * v[0].hypot(v[1]));
        assert!(
            cos > 2.6f64.to_radians().cos(),
            "not tangent: {} degrees",
            cos.acos().to_degrees()
        );
        // The arc: radius 3 about a centre 3 mm to the left of the pass.
        let start = a[0].pose.cl;
        let chord = (start.x - p0.x).hypot(start.y - p0.y);
        assert!(
            (chord - 3.0 * 2f64.sqrt()).abs() < 1e-9,
            "quarter arc chord {chord}"
        );
        // Rising at 10 degrees (unless lifted over the part).
        assert!(
            start.z >= p0.z + 3.0 * std::f64::consts::FRAC_PI_2 * 10f64.to_radians().tan() - 1e-9
        );
        checked += 1;
    }
    assert!(checked > 10);

    let moves = plan.toolpath.moves();
    let gcode =
        swarf_nc::write_gcode(&moves, &job.feeds, &swarf_nc::GcodeOptions::default()).unwrap();
    let program = swarf_nc::read::parse_gcode(&gcode, "leads.ngc", &Default::default()).unwrap();
    let opts = VerifyOptions {
        tol: 0.01,
        cell: Some(0.25),
        stock: StockSpec::Offset { allowance: 1.0 },
        ..VerifyOptions::default()
    };
    let v = swarf_sim::verify(Design::Part(&part), &program, &job.tool, &opts, &Quiet).unwrap();
    let g = &v.deviation.summary.gouge;
    eprintln!(
        "{checked} passes with leads; gouge cells {} (worst {:.2e} mm)",
        g.cells, g.worst
    );
    assert_eq!(g.cells, 0);
}
