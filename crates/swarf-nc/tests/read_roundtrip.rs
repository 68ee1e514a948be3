//! Round trips: a tool path written by swarf-nc's writers (G-code for LinuxCNC and
//! Fanuc, APT CL, pose CSV, in mm and inches) and read back gives the same poses,
//! kinds and feeds to the printed precision.

use proptest::prelude::*;
use swarf_geom::{Point3, Vec3};
use swarf_nc::read::{
    GcodeReadOptions, MotionKind, Program, parse_cl, parse_gcode, parse_pose_csv, read_program,
};
use swarf_nc::{GcodeOptions, NcError, Post, Units, write_cl, write_gcode, write_pose_csv};
use swarf_tool::{Cutter, Pose};
use swarf_toolpath::{Feeds, Linking, Move, MoveKind, Pass, PathPoint, Toolpath};

/// Three zigzag passes over a wavy surface; `tilt` leans the axis (five-axis CL).
fn toolpath(tilt: f64) -> Toolpath {
    let passes = (0..3)
        .map(|k| Pass {
            points: (0..8)
                .map(|i| {
                    let x = f64::from(i) * 1.37 - 2.0;
                    let y = f64::from(k) * 0.913;
                    let z = 0.3 * (x * 0.7).sin() - 0.05 * y;
                    let axis = Vec3::new(tilt * x.sin(), tilt * 0.5, 1.0).normalize();
                    PathPoint::new(Pose {
                        cl: Point3::new(x, y, z),
                        axis,
                    })
                })
                .collect(),
            ..Pass::default()
        })
        .collect();
    let feeds = Feeds {
        feed: 437.5,
        plunge: 120.0,
        rapid: 5000.0,
        spindle: 1500.0,
    };
    Toolpath {
        passes,
        feeds,
        linking: Linking::default(),
    }
}

/// The moves a G-code post actually writes: those that change a printed coordinate.
fn written(moves: &[Move], decimals: usize, scale: f64) -> Vec<Move> {
    let mut out: Vec<Move> = Vec::new();
    let round = |v: f64| swarf_nc::number::format_decimal(v / scale, decimals);
    let mut last: Option<[String; 3]> = None;
    for m in moves {
        let now = [m.to.cl.x, m.to.cl.y, m.to.cl.z].map(round);
        if last.as_ref() != Some(&now) {
            out.push(*m);
            last = Some(now);
        }
    }
    out
}

fn check(program: &Program, moves: &[Move], tol: f64, feed_tol: f64, axes: bool) {
    assert!(program.stopped.is_none(), "{:?}", program.stopped);
    assert_eq!(program.motions.len(), moves.len());
    for (k, (m, w)) in program.motions.iter().zip(moves).enumerate() {
        let off = (m.end.cl - w.to.cl).amax();
        assert!(off <= tol, "motion {k}: {:?} vs {:?}", m.end.cl, w.to.cl);
        if axes {
            assert!((m.end.axis - w.to.axis).amax() < 1e-8, "motion {k} axis");
        }
        match w.kind {
            MoveKind::Rapid => assert_eq!((m.kind, m.feed), (MotionKind::Rapid, 0.0)),
            MoveKind::Feed => {
                assert_eq!(m.kind, MotionKind::Linear);
                assert!(
                    (m.feed - w.feed).abs() <= feed_tol,
                    "motion {k}: feed {} vs {}",
                    m.feed,
                    w.feed
                );
            }
        }
        if k > 0 {
            assert_eq!(m.start, program.motions[k - 1].end);
        }
    }
}

#[test]
fn gcode_round_trip_in_both_dialects_and_units() {
    let tp = toolpath(0.0);
    let moves = tp.moves();
    for dialect in ["linuxcnc", "fanuc"] {
        for units in [Units::Mm, Units::Inch] {
            let opts = GcodeOptions {
                post: Post::builtin(dialect).unwrap(),
                units,
                comments: vec!["part wave".into()],
                ..GcodeOptions::default()
            };
            let text = write_gcode(&moves, &tp.feeds, &opts).unwrap();
            let p = parse_gcode(&text, "rt.ngc", &GcodeReadOptions::default()).unwrap();
            let scale = if units == Units::Inch { 25.4 } else { 1.0 };
            let decimals = units.decimals();
            let tol = 0.5 * 10f64.powi(-(decimals as i32)) * scale + 1e-12;
            let feed_tol = 0.5e-3 * scale + 1e-9;
            check(&p, &written(&moves, decimals, scale), tol, feed_tol, false);
            assert!(
                p.warnings.is_empty(),
                "{dialect:?} {units:?}: {:?}",
                p.warnings
            );
            assert!(p.tool.is_none());
        }
    }
}

#[test]
fn cl_round_trip_with_tilted_axes_and_cutter() {
    let cutter: Cutter = "bull:d=10,r=2".parse().unwrap();
    for tilt in [0.0, 0.3] {
        let tp = toolpath(tilt);
        let moves = tp.moves();
        for units in [Units::Mm, Units::Inch] {
            let text = write_cl(&moves, &tp.feeds, &cutter, "wave", units).unwrap();
            let p = parse_cl(&text, "rt.cl").unwrap();
            let scale = if units == Units::Inch { 25.4 } else { 1.0 };
            // the first GOTO is the start: no motion into it; repeated poses move nothing
            let mut distinct = moves.clone();
            distinct.dedup_by(|b, a| a.to == b.to);
            check(
                &p,
                &distinct[1..],
                0.5e-6 * scale + 1e-12,
                0.5e-4 * scale + 1e-9,
                true,
            );
            assert!((p.motions[0].start.cl - moves[0].to.cl).amax() <= 0.5e-6 * scale + 1e-12);
            assert!(p.warnings.is_empty(), "{:?}", p.warnings);
            let Some(apt) = p.tool.map(|c| c.to_apt()) else {
                panic!("no cutter: {:?}", p.tool);
            };
            assert!(matches!(p.tool, Some(Cutter::Bull { .. })), "{:?}", p.tool);
            let want = cutter.to_apt();
            let pairs = [
                (apt.d, want.d),
                (apt.r, want.r),
                (apt.e, want.e),
                (apt.f, want.f),
                (apt.h, want.h),
            ];
            for (got, want) in pairs {
                assert!((got - want).abs() < 1e-5 * scale, "{apt:?} vs {want:?}");
            }
            assert_eq!((apt.alpha, apt.beta), (want.alpha, want.beta));
        }
    }
}

#[test]
fn pose_csv_round_trip() {
    let tp = toolpath(0.2);
    let text = write_pose_csv(&tp, Units::Mm).unwrap();
    let p = parse_pose_csv(&text, "rt.csv").unwrap();
    // Passes are separated by `# pass` comments: no motion joins them.
    let mut want = Vec::new();
    for pass in &tp.passes {
        for w in pass.points.windows(2) {
            want.push((w[0].pose, w[1].pose));
        }
    }
    assert_eq!(p.motions.len(), want.len());
    for (m, (from, to)) in p.motions.iter().zip(&want) {
        assert!((m.start.cl - from.cl).amax() <= 0.5e-6 + 1e-12);
        assert!((m.end.cl - to.cl).amax() <= 0.5e-6 + 1e-12);
        assert!((m.end.axis - to.axis).amax() < 1e-8);
        assert_eq!((m.kind, m.feed), (MotionKind::Linear, tp.feeds.feed));
    }
}

#[test]
fn read_program_dispatches_on_extension() {
    let dir = std::env::temp_dir().join(format!("swarf-read-rt-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let tp = toolpath(0.0);
    let moves = tp.moves();
    let cutter: Cutter = "ball:d=8".parse().unwrap();
    let files = [
        (
            "a.NGC",
            write_gcode(&moves, &tp.feeds, &GcodeOptions::default()).unwrap(),
        ),
        (
            "a.tap",
            write_gcode(&moves, &tp.feeds, &GcodeOptions::default()).unwrap(),
        ),
        (
            "a.cls",
            write_cl(&moves, &tp.feeds, &cutter, "a", Units::Mm).unwrap(),
        ),
        ("a.csv", write_pose_csv(&tp, Units::Mm).unwrap()),
    ];
    for (name, text) in &files {
        let path = dir.join(name);
        std::fs::write(&path, text).unwrap();
        let p = read_program(&path).unwrap();
        assert!(p.stopped.is_none() && !p.motions.is_empty(), "{name}");
        assert_eq!(p.source, path.display().to_string());
        assert_eq!(p.tool.is_some(), name.ends_with(".cls"), "{name}");
    }
    let missing = read_program(&dir.join("nope.ngc")).unwrap_err();
    assert!(matches!(missing, NcError::Input(_)), "{missing}");
    assert!(
        missing.to_string().contains("nope.ngc: cannot read"),
        "{missing}"
    );
    let unknown = read_program(&dir.join("a.txt")).unwrap_err();
    assert!(
        matches!(unknown, NcError::UnknownFormat { .. }),
        "{unknown}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// Any straight 3-axis program the post writes reads back to the printed precision.
    #[test]
    fn random_programs_round_trip(
        points in prop::collection::vec((-500.0..500.0f64, -500.0..500.0f64, -50.0..50.0f64, any::<bool>()), 1..40),
        feed in 1.0..5000.0f64,
        inch in any::<bool>(),
    ) {
        let moves: Vec<Move> = points.iter().map(|&(x, y, z, rapid)| Move {
            kind: if rapid { MoveKind::Rapid } else { MoveKind::Feed },
            to: Pose::vertical(Point3::new(x, y, z)),
            feed: if rapid { 0.0 } else { feed },
            pass: None,
        }).collect();
        let units = if inch { Units::Inch } else { Units::Mm };
        let opts = GcodeOptions { units, ..GcodeOptions::default() };
        let text = write_gcode(&moves, &Feeds::default(), &opts).unwrap();
        let p = parse_gcode(&text, "p.ngc", &GcodeReadOptions::default()).unwrap();
        let scale = if inch { 25.4 } else { 1.0 };
        let kept = written(&moves, units.decimals(), scale);
        prop_assert!(p.stopped.is_none());
        prop_assert_eq!(p.motions.len(), kept.len());
        let tol = 0.5 * 10f64.powi(-(units.decimals() as i32)) * scale + 1e-9;
        for (m, w) in p.motions.iter().zip(&kept) {
            prop_assert!((m.end.cl - w.to.cl).amax() <= tol);
        }
    }
}
