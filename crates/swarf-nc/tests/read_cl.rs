//! The APT CL reader: records, units, feeds, rapids, cutters, and what it refuses.

use swarf_geom::{Point3, Vec3};
use swarf_nc::read::{MotionKind, Program, parse_cl};
use swarf_tool::Cutter;

fn read(text: &str) -> Program {
    parse_cl(text, "t.cl").unwrap()
}

#[test]
fn feeds_in_both_orders_and_units() {
    let text = "UNITS/INCHES\nGOTO/0,0,1\nFEDRAT/10,IPM\nGOTO/1,0,1\nFEDRAT/MMPM,300\nGOTO/2,0,1\n\
                FEDRAT/5\nGOTO/3,0,1\nUNITS/MM\nFEDRAT/200\nGOTO/100,0,25.4\nSPINDL/RPM,1000,CLW\n\
                FEDRAT/0.1,MMPR\nGOTO/110,0,25.4\nFINI\n";
    let p = read(text);
    assert!(p.stopped.is_none(), "{:?}", p.stopped);
    let feeds: Vec<f64> = p.motions.iter().map(|m| m.feed).collect();
    assert_eq!(feeds, vec![254.0, 300.0, 127.0, 200.0, 100.0]);
    assert_eq!(p.motions[0].start.cl, Point3::new(0.0, 0.0, 25.4));
    assert_eq!(p.motions[3].end.cl, Point3::new(100.0, 0.0, 25.4));
    assert_eq!(
        p.motions.iter().map(|m| m.line).collect::<Vec<_>>(),
        vec![4, 6, 8, 11, 14]
    );
}

#[test]
fn rapid_applies_to_the_next_goto_only() {
    let p = read(
        "FROM/0,0,50\nRAPID\nGOTO/0,0,5\nFEDRAT/100\nGOTO/0,0,0\nRAPID\nGOTO/0,0,5\nGOTO/5,0,5\n",
    );
    let kinds: Vec<MotionKind> = p.motions.iter().map(|m| m.kind).collect();
    assert_eq!(
        kinds,
        vec![
            MotionKind::Rapid,
            MotionKind::Linear,
            MotionKind::Rapid,
            MotionKind::Linear
        ]
    );
    assert_eq!(p.motions[0].start.cl, Point3::new(0.0, 0.0, 50.0));
    assert_eq!(p.motions[2].feed, 0.0);
    assert_eq!(p.motions[3].feed, 100.0);
}

#[test]
fn axes_are_normalised_and_kept() {
    let p = read(
        "GOTO/0,0,0,0,0,2\nFEDRAT/100\nGOTO/1,0,0,1,0,1\nGOTO/2,0,0\nTLAXIS/0,1,0\nGODLTA/0,0,1\nGODLTA/2\n",
    );
    let s = 0.5f64.sqrt();
    assert_eq!(p.motions[0].start.axis, Vec3::z());
    assert!((p.motions[0].end.axis - Vec3::new(s, 0.0, s)).norm() < 1e-15);
    assert_eq!(
        p.motions[1].end.axis, p.motions[0].end.axis,
        "three values keep the axis"
    );
    assert_eq!(p.motions[2].end.cl, Point3::new(2.0, 0.0, 1.0));
    assert!((p.motions[3].end.cl - Point3::new(2.0 + 2.0 * s, 0.0, 1.0 + 2.0 * s)).norm() < 1e-12);
    let mid = p.motions[0].point_at(0.5);
    assert!((mid.axis.norm() - 1.0).abs() < 1e-12);
}

#[test]
fn cutter_records() {
    // Untapered APT tools read as the named shapes their jobs wrote.
    let name = |text: &str| read(text).tool.map(|c| c.to_string());
    assert_eq!(name("CUTTER/8\n").as_deref(), Some("flat:d=8"));
    let inch = read("UNITS/INCHES\nCUTTER/0.5,0.25,0,0.25,0,0,1.5\n").tool;
    assert!(
        matches!(inch, Some(Cutter::Ball { radius, .. }) if radius == 6.35),
        "{inch:?}"
    );
    assert!(inch.is_some_and(|c| (c.length() - 38.1).abs() < 1e-12));
    assert_eq!(
        name("CUTTER/38.100000,6.350000,12.700000,6.350000,0.000000,0.000000,25.400000\n")
            .as_deref(),
        Some("bull:d=38.1,r=6.35,length=25.4")
    );
    // e and f are checked against d, r, alpha, beta to the printed precision
    let bad = read("CUTTER/10,2,3.5,2,0,0,30\nGOTO/0,0,0\n");
    assert!(bad.tool.is_none());
    assert!(
        bad.warnings
            .iter()
            .any(|w| w.line == 1 && w.message.contains("e = 3.5")),
        "{:?}",
        bad.warnings
    );
    let coarse = read("CUTTER/10.,2.,3.,2.,0.,0.,30.\n");
    assert!(coarse.tool.is_some(), "{:?}", coarse.warnings);
    let angles = read("CUTTER/10,0,5,2.886751,30,0,40\n");
    assert!(
        matches!(angles.tool, Some(Cutter::Apt(a)) if (a.alpha - 30f64.to_radians()).abs() < 1e-15)
    );
    let changed = read("CUTTER/8,4\nGOTO/0,0,0\nFEDRAT/100\nGOTO/1,0,0\nCUTTER/6,3\nGOTO/2,0,0\n");
    assert_eq!(changed.motions.len(), 1);
    let stop = changed.stopped.unwrap();
    assert_eq!((stop.line, stop.column), (5, 1));
    assert!(stop.message.contains("one tool per program"));
}

#[test]
fn comments_continuations_and_unknown_records() {
    let text = "$$ header comment\nPARTNO/WAVE\nMULTAX/ON\nGOTO/0,0,0 $$ start\nFEDRAT/$\n  300,MMPM\n\
                GOTO/ 1.0E+01 ,$\n 0 , 0\nLOADTL/1\nTOOLPATH/FINISH\nFINI\nGOTO/99,0,0\n";
    let p = read(text);
    assert!(p.stopped.is_none(), "{:?}", p.stopped);
    assert_eq!(p.motions.len(), 1);
    assert_eq!(p.motions[0].end.cl, Point3::new(10.0, 0.0, 0.0));
    assert_eq!((p.motions[0].line, p.motions[0].feed), (7, 300.0));
    let lines: Vec<(usize, usize)> = p.warnings.iter().map(|w| (w.line, w.column)).collect();
    assert_eq!(lines, vec![(10, 1), (12, 1)], "{:?}", p.warnings);
    assert!(p.warnings[0].message.contains("TOOLPATH"));
}

#[test]
fn errors_stop_with_line_and_column() {
    let cases: [(&str, usize, usize, &str); 9] = [
        ("GOTO/0,0,0\nGOTO/1,2\n", 2, 1, "expected 3 or 6"),
        ("GOTO/0,0,0\nGOTO/1,x2,3\n", 2, 8, "expected a number"),
        ("GOTO/0,0,0\nGOTO/1,2,3,0,0,0\n", 2, 12, "axis"),
        (
            "GOTO/0,0,0\nCIRCLE/0,0,0,0,0,1,5\nGOTO/5,5,0\n",
            2,
            1,
            "circular",
        ),
        ("GOTO/0,0,0\nGOFWD/PL1\n", 2, 1, "APT source"),
        ("UNITS/FEET\n", 1, 1, "MM or INCHES"),
        ("FEDRAT/-5\n", 1, 8, "> 0"),
        ("FEDRAT/0.1,IPR\n", 1, 8, "SPINDL"),
        (
            "GOTO/0,0,0\nFEDRAT/100\nGOTO/1,0,0\nFROM/5,5,5\n",
            4,
            1,
            "FROM after motions",
        ),
    ];
    for (text, line, column, needle) in cases {
        let p = read(text);
        let d = p.stopped.unwrap_or_else(|| panic!("no error for {text:?}"));
        assert_eq!(
            (d.line, d.column),
            (line, column),
            "{text:?}: {}",
            d.message
        );
        assert!(d.message.contains(needle), "{text:?}: {}", d.message);
    }
}

#[test]
fn feed_moves_without_fedrat_warn_once() {
    let p = read("GOTO/0,0,0\nGOTO/1,0,0\nGOTO/2,0,0\n");
    assert_eq!(p.motions.len(), 2);
    assert!(
        p.motions
            .iter()
            .all(|m| m.feed == 0.0 && m.kind == MotionKind::Linear)
    );
    assert_eq!(p.warnings.len(), 1);
    assert_eq!(p.warnings[0].line, 2);
}
