//! Iso-planar with a fixed cross feed (`stepover`, the "cross feed 3.5 mm" of
//! thesis 000 ch. 8): planes exactly the stepover apart, centred in the part, the
//! closed-form ball scallop predicted; and pass ends without stubs.

use swarf_geom::{Part, Patch};
use swarf_path::Cutting;
use swarf_path::strategy::iso::planar::{IsoPlanarParams, plan};

/// Iso-planar parameters read from their strategy table (TOML, without `kind`),
/// checked for `tool`.
fn params(table: &str, tool: &Cutting) -> Result<IsoPlanarParams, String> {
    let p: IsoPlanarParams = toml::from_str(table).map_err(|e| e.to_string())?;
    p.validate(&tool.tool).map_err(|e| e.to_string())?;
    Ok(p)
}

fn cutting(tool: &str) -> Cutting {
    Cutting::new(tool.parse().unwrap())
}

/// A fixed cross feed on a plane: drive planes exactly `s` apart and centred in the
/// part, in start-side order, and the closed-form ball scallop predicted.
#[test]
fn fixed_stepover_on_a_plane() {
    let p = |x: f64, y: f64| swarf_geom::Point3::new(x, y, 1.0);
    let plane = Patch::bezier(
        [1, 1],
        vec![p(0.0, 0.0), p(0.0, 10.0), p(20.0, 0.0), p(20.0, 10.0)],
    )
    .unwrap();
    let part = Part::new("plane", vec![plane]);
    let ball = cutting("ball:d=8");
    let with = |extra: &str| {
        params(
            &format!("stepover = 1.5\ntolerance = 0.01\nangle = 0\n{extra}\n"),
            &ball,
        )
        .unwrap()
    };
    for (extra, first) in [("", 0.5), ("start = \"max\"", 9.5)] {
        let plan = plan(&part, &ball, &with(extra)).unwrap();
        let ys: Vec<f64> = plan
            .toolpath
            .passes
            .iter()
            .map(|pass| {
                let y = pass.points[0].contact.unwrap().point.y;
                for q in &pass.points {
                    assert!((q.contact.unwrap().point.y - y).abs() < 1e-9);
                }
                y
            })
            .collect();
        assert_eq!(ys.len(), 7, "{ys:?}");
        let sign = if first < 5.0 { 1.0 } else { -1.0 };
        for (k, y) in ys.iter().enumerate() {
            assert!((y - (first + sign * 1.5 * k as f64)).abs() < 1e-9, "{ys:?}");
        }
        let h = 4.0 - (16.0f64 - 0.25 * 1.5 * 1.5).sqrt();
        let pred = plan.report.predicted_max_scallop.unwrap();
        assert!((pred - h).abs() < 1e-9, "{pred} vs {h}");
        let [a, b] = plan.report.side_step_range.unwrap();
        assert!((a - 1.5).abs() < 1e-9 && (b - 1.5).abs() < 1e-9);
    }
    let both = params("stepover = 1.5\nscallop = 0.1\n", &ball);
    assert!(both.unwrap_err().to_string().contains("stepover"));
}

/// Sections of the die end on its patch edges and corners, where the section
/// polyline can end in two samples 1e-13 mm apart: no pass keeps such a stub.
#[test]
fn pass_ends_have_no_stubs() {
    let part = swarf_io::builtin_part("die").unwrap();
    let bull = cutting("bull:d=38.1,r=6.35");
    let job = params("stepover = 10\nangle = 60\n", &bull).unwrap();
    let plan = plan(&part, &bull, &job).unwrap();
    assert!(plan.toolpath.passes.len() > 10);
    for pass in &plan.toolpath.passes {
        for w in pass.points.windows(2) {
            let (a, b) = (w[0].contact.unwrap(), w[1].contact.unwrap());
            assert!((b.point - a.point).norm() > 1e-6, "{a:?} {b:?}");
        }
    }
}

/// The thesis's drive planes on the die: 60 degrees off X, cross feed 3.5 mm. Every
/// pass lies on its plane, consecutive planes are exactly 3.5 mm apart, passes
/// alternate direction (zigzag), and every CC point is on the design with its normal
/// up.
#[test]
fn die_drive_planes_at_the_thesis_cross_feed() {
    let part = swarf_io::builtin_part("die").unwrap();
    let bull = cutting("bull:d=38.1,r=6.35");
    let job = params("stepover = 3.5\nangle = 60\n", &bull).unwrap();
    let plan = plan(&part, &bull, &job).unwrap();
    let passes = &plan.toolpath.passes;
    assert!(passes.len() > 30, "{}", passes.len());
    let a = 60f64.to_radians();
    let (n, f) = ([-a.sin(), a.cos()], [a.cos(), a.sin()]);
    let mut offsets = Vec::new();
    for (k, pass) in passes.iter().enumerate() {
        let cs: Vec<_> = pass.points.iter().map(|p| p.contact.unwrap()).collect();
        let m = n[0] * cs[0].point.x + n[1] * cs[0].point.y;
        for c in &cs {
            assert!((n[0] * c.point.x + n[1] * c.point.y - m).abs() < 1e-6);
            assert!(c.normal.z > 0.0 && (c.normal.norm() - 1.0).abs() < 1e-9);
            let on = part.patches[c.face].eval(c.uv[0], c.uv[1]);
            assert!((on - c.point).norm() < 1e-9);
        }
        let (first, last) = (cs[0].point, cs[cs.len() - 1].point);
        let along = f[0] * (last.x - first.x) + f[1] * (last.y - first.y);
        assert_eq!(along > 0.0, k % 2 == 0, "pass {k}");
        offsets.push(m);
    }
    for w in offsets.windows(2) {
        assert!((w[1] - w[0] - 3.5).abs() < 1e-6, "{offsets:?}");
    }
}
