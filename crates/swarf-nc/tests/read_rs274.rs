//! The G-code reader against LinuxCNC's own interpreter, `rs274 -g`, an independent
//! reference: its canonical calls (`STRAIGHT_TRAVERSE`, `STRAIGHT_FEED`, `ARC_FEED` with
//! end point, centre and rotation) are recorded next to the programs in `tests/data/`
//! (`*.rs274`), so these tests run without LinuxCNC; when `rs274` is installed they
//! also check that the recordings are still what it prints, and compare the arc
//! radius tolerance and the writers' output with it live. With
//! `SWARF_REQUIRE_REFERENCES=1`, a missing `rs274` fails instead of skipping.

use std::f64::consts::TAU;
use std::path::{Path, PathBuf};
use swarf_geom::{Point3, Vec3};
use swarf_nc::read::{GcodeReadOptions, Motion, MotionKind, parse_gcode};
use swarf_testkit::rs274::run_rs274;

/// One canonical move, in mm.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Canon {
    Traverse(Point3),
    Feed(Point3),
    /// End, centre (normal coordinate = start's), plane indices [a, b, n], rotation.
    Arc {
        end: Point3,
        center: [f64; 2],
        plane: [usize; 3],
        rotation: i32,
    },
}

impl Canon {
    fn end(&self) -> Point3 {
        match *self {
            Canon::Traverse(p) | Canon::Feed(p) => p,
            Canon::Arc { end, .. } => end,
        }
    }
}

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(name)
}

fn args(call: &str) -> Vec<f64> {
    let inner = &call[call.find('(').unwrap() + 1..call.rfind(')').unwrap()];
    inner
        .split(',')
        .map(|a| a.trim().parse().unwrap())
        .collect()
}

/// The moves of `rs274 -g` output, converted to mm, zero-length moves dropped.
fn parse_canon(text: &str) -> Vec<Canon> {
    let mut plane = [0, 1, 2];
    let mut scale = 1.0;
    let mut at = Point3::origin();
    let mut out = Vec::new();
    for line in text.lines() {
        let Some(call) = line.split("N..... ").nth(1) else {
            continue;
        };
        let canon = if call.starts_with("SELECT_PLANE") {
            plane = match call {
                c if c.contains("PLANE_XZ") => [2, 0, 1],
                c if c.contains("PLANE_YZ") => [1, 2, 0],
                _ => [0, 1, 2],
            };
            continue;
        } else if call.starts_with("USE_LENGTH_UNITS") {
            scale = if call.contains("INCHES") { 25.4 } else { 1.0 };
            continue;
        } else if call.starts_with("STRAIGHT_TRAVERSE") || call.starts_with("STRAIGHT_FEED") {
            let a = args(call);
            let p = Point3::new(a[0], a[1], a[2]) * scale;
            if call.starts_with("STRAIGHT_TRAVERSE") {
                Canon::Traverse(p)
            } else {
                Canon::Feed(p)
            }
        } else if call.starts_with("ARC_FEED") {
            let a = args(call);
            let mut end = Point3::origin();
            end[plane[0]] = a[0] * scale;
            end[plane[1]] = a[1] * scale;
            end[plane[2]] = a[5] * scale;
            Canon::Arc {
                end,
                center: [a[2] * scale, a[3] * scale],
                plane,
                rotation: a[4] as i32,
            }
        } else {
            continue;
        };
        let zero_straight = !matches!(canon, Canon::Arc { .. }) && canon.end() == at;
        at = canon.end();
        if !zero_straight {
            out.push(canon);
        }
    }
    out
}

fn read(name: &str) -> Vec<Motion> {
    let text = std::fs::read_to_string(data(name)).unwrap();
    let p = parse_gcode(&text, name, &GcodeReadOptions::default()).unwrap();
    assert!(p.stopped.is_none(), "{:?}", p.stopped);
    p.motions
}

/// Printed to 4 decimals in program units.
fn tol(scale: f64) -> f64 {
    0.6e-4 * scale
}

fn compare(motions: &[Motion], canon: &[Canon], scale: f64) {
    assert_eq!(motions.len(), canon.len(), "{motions:#?}\n{canon:#?}");
    for (m, c) in motions.iter().zip(canon) {
        let off = (m.end.cl - c.end()).amax();
        assert!(off < tol(scale), "line {}: {:?} vs {c:?}", m.line, m.end.cl);
        match (m.kind, *c) {
            (MotionKind::Rapid, Canon::Traverse(_)) | (MotionKind::Linear, Canon::Feed(_)) => {}
            (
                MotionKind::Arc {
                    center,
                    normal,
                    clockwise,
                    turns,
                },
                Canon::Arc {
                    center: rc,
                    plane,
                    rotation,
                    ..
                },
            ) => {
                let [a, b, n] = plane;
                assert!(
                    (center[a] - rc[0]).abs() < tol(scale)
                        && (center[b] - rc[1]).abs() < tol(scale),
                    "line {}",
                    m.line
                );
                assert_eq!(normal, Vec3::ith(n, 1.0), "line {}", m.line);
                assert_eq!(clockwise, rotation < 0, "line {}", m.line);
                assert_eq!(turns, rotation.unsigned_abs(), "line {}", m.line);
                check_samples(m, c, scale);
            }
            (kind, c) => panic!("line {}: {kind:?} vs {c:?}", m.line),
        }
    }
}

/// `point_at` against the closed form built from rs274's centre and rotation: radius,
/// angle advanced in the rotation direction, and height along the normal.
fn check_samples(m: &Motion, c: &Canon, scale: f64) {
    let Canon::Arc {
        center,
        plane: [a, b, n],
        rotation,
        end,
    } = *c
    else {
        return;
    };
    let start = m.start.cl;
    let angle = |p: &Point3| (p[b] - center[1]).atan2(p[a] - center[0]);
    let sense = f64::from(rotation.signum());
    let same = (start[a] - end[a]).abs() < 1e-9 && (start[b] - end[b]).abs() < 1e-9;
    let mut partial = (sense * (angle(&end) - angle(&start))).rem_euclid(TAU);
    if same || partial < 1e-12 {
        partial = TAU;
    }
    let total = partial + TAU * f64::from(rotation.unsigned_abs() - 1);
    let radius = (start[a] - center[0]).hypot(start[b] - center[1]);
    for t in [0.1, 0.25, 0.5, 0.75, 0.9] {
        let p = m.point_at(t).cl;
        let r = (p[a] - center[0]).hypot(p[b] - center[1]);
        assert!(
            (r - radius).abs() < tol(scale),
            "line {} t {t}: r {r} vs {radius}",
            m.line
        );
        let advanced = (sense * (angle(&p) - angle(&start))).rem_euclid(TAU);
        let expected = (t * total).rem_euclid(TAU);
        let diff = (advanced - expected).abs();
        assert!(
            diff.min(TAU - diff) < 1e-4,
            "line {} t {t}: {advanced} vs {expected}",
            m.line
        );
        let h = start[n] + t * (end[n] - start[n]);
        assert!((p[n] - h).abs() < 1e-9, "line {} t {t}", m.line);
    }
    let length = (radius * total).hypot(end[n] - start[n]);
    assert!(
        (m.length() - length).abs() < 1e-3 * scale,
        "line {}",
        m.line
    );
}

#[test]
fn arcs_in_all_planes_match_recorded_rs274() {
    let canon = parse_canon(&std::fs::read_to_string(data("arcs_mm.rs274")).unwrap());
    assert!(
        canon
            .iter()
            .filter(|c| matches!(c, Canon::Arc { .. }))
            .count()
            >= 18
    );
    compare(&read("arcs_mm.ngc"), &canon, 1.0);
}

#[test]
fn inch_program_matches_recorded_rs274() {
    let canon = parse_canon(&std::fs::read_to_string(data("arcs_inch.rs274")).unwrap());
    compare(&read("arcs_inch.ngc"), &canon, 25.4);
}

/// `rs274 -g` on `text`, stdout and stderr together; `None` when it is not installed.
fn rs274(text: &str) -> Option<String> {
    run_rs274(text, "read").map(|out| out.text(""))
}

#[test]
fn recordings_are_what_rs274_prints() {
    for name in ["arcs_mm", "arcs_inch"] {
        let program = std::fs::read_to_string(data(&format!("{name}.ngc"))).unwrap();
        let Some(live) = rs274(&program) else {
            return;
        };
        let recorded = std::fs::read_to_string(data(&format!("{name}.rs274"))).unwrap();
        assert_eq!(parse_canon(&live), parse_canon(&recorded), "{name}");
    }
}

/// Arcs around LinuxCNC's radius-mismatch limits: (program, accepted by rs274 2.9).
const LIMIT_CASES: [(&str, bool); 10] = [
    ("G21 G0 X0 Y0\nG2 X10.0282 Y0 I5 J0 F100\nM2\n", true),
    ("G21 G0 X0 Y0\nG2 X10.0284 Y0 I5 J0 F100\nM2\n", false),
    ("G21 G0 X0 Y0\nG2 X1000.4 Y0 I500 J0 F100\nM2\n", true),
    ("G21 G0 X0 Y0\nG2 X1000.6 Y0 I500 J0 F100\nM2\n", false),
    ("G21 G0 X0 Y0\nG2 X10002.8 Y0 I5000 J0 F100\nM2\n", true),
    ("G21 G0 X0 Y0\nG2 X10002.9 Y0 I5000 J0 F100\nM2\n", false),
    ("G20 G0 X0 Y0\nG2 X0.3965 Y0 I0.19685 J0 F10\nM2\n", true),
    ("G20 G0 X0 Y0\nG2 X0.3966 Y0 I0.19685 J0 F10\nM2\n", false),
    ("G21 G0 X10 Y0\nG2 X0 Y0 R4.999 F100\nM2\n", true),
    ("G21 G0 X10 Y0\nG2 X0 Y0 R4.9985 F100\nM2\n", false),
];

#[test]
fn radius_mismatch_limits_as_linuxcnc() {
    for (program, accepted) in LIMIT_CASES {
        let p = parse_gcode(program, "limit.ngc", &GcodeReadOptions::default()).unwrap();
        assert_eq!(p.stopped.is_none(), accepted, "{program}: {:?}", p.stopped);
        if let Some(stop) = &p.stopped {
            assert_eq!((stop.line, stop.column), (2, 1), "{program}");
        } else {
            let end = p.motions.last().unwrap();
            let x: f64 = program
                .split("G2 X")
                .nth(1)
                .unwrap()
                .split(' ')
                .next()
                .unwrap()
                .parse()
                .unwrap();
            let scale = if program.starts_with("G20") {
                25.4
            } else {
                1.0
            };
            assert!(
                (end.point_at(1.0 - 1e-12).cl.x - x * scale).abs() < 1e-9,
                "the spiral ends on the end point"
            );
        }
    }
    for (program, accepted) in LIMIT_CASES {
        let Some(out) = rs274(program) else {
            return;
        };
        assert_eq!(
            out.contains("ARC_FEED"),
            accepted,
            "rs274 on {program}: {out}"
        );
    }
}

#[test]
fn writer_output_matches_rs274_live() {
    use swarf_nc::{GcodeOptions, Post, Units, write_gcode};
    use swarf_tool::Pose;
    use swarf_toolpath::{Feeds, Linking, Pass, PathPoint, Toolpath};
    let passes = (0..3)
        .map(|k| Pass {
            points: (0..5)
                .map(|i| {
                    PathPoint::new(Pose::vertical(Point3::new(
                        f64::from(i) * 1.25,
                        f64::from(k) * 0.8,
                        -0.1 * f64::from(i * k),
                    )))
                })
                .collect(),
            ..Pass::default()
        })
        .collect();
    let toolpath = Toolpath {
        passes,
        feeds: Feeds::default(),
        linking: Linking::default(),
    };
    for units in [Units::Mm, Units::Inch] {
        let opts = GcodeOptions {
            post: Post::linuxcnc(),
            units,
            ..GcodeOptions::default()
        };
        let text = write_gcode(&toolpath.moves(), &toolpath.feeds, &opts).unwrap();
        let Some(live) = rs274(&text) else {
            return;
        };
        let p = parse_gcode(&text, "w.ngc", &GcodeReadOptions::default()).unwrap();
        let scale = if units == Units::Inch { 25.4 } else { 1.0 };
        compare(&p.motions, &parse_canon(&live), scale);
    }
}
