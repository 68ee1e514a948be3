//! The G-code reader's modal behaviour and its handling of bad input: every error
//! and warning carries the right line and column, nothing is silently dropped, and a
//! program that stops mid-way keeps the motions before the error.

use swarf_geom::{Point3, Vec3};
use swarf_nc::read::{Diagnostic, GcodeReadOptions, MotionKind, Program, parse_gcode};
use swarf_tool::Pose;

fn read(text: &str) -> Program {
    parse_gcode(text, "t.ngc", &GcodeReadOptions::default()).unwrap()
}

fn ends(p: &Program) -> Vec<[f64; 3]> {
    p.motions
        .iter()
        .map(|m| [m.end.cl.x, m.end.cl.y, m.end.cl.z])
        .collect()
}

/// The stop diagnostic: line, column, and the message (for a `contains` check).
fn stop(text: &str) -> (usize, usize, String) {
    let p = read(text);
    let d = p.stopped.unwrap_or_else(|| panic!("no error for {text:?}"));
    (d.line, d.column, d.message)
}

fn has_warning(p: &Program, line: usize, column: usize, needle: &str) -> bool {
    p.warnings
        .iter()
        .any(|w: &Diagnostic| w.line == line && w.column == column && w.message.contains(needle))
}

#[test]
fn incremental_inch_and_modal_feed() {
    let p =
        read("G20 G90 G94\nG0 X1 Y1 Z0.5\nG1 Z0 F10\nG91 X0.5\nY-0.25 F20\nG90 G21 G1 X0\nM30\n");
    assert!(
        p.stopped.is_none() && p.warnings.is_empty(),
        "{:?} {:?}",
        p.stopped,
        p.warnings
    );
    let e = ends(&p);
    let close = |a: [f64; 3], b: [f64; 3]| a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-12);
    assert!(close(e[0], [25.4, 25.4, 12.7]));
    assert!(close(e[2], [38.1, 25.4, 0.0]));
    assert!(close(e[3], [38.1, 19.05, 0.0]));
    assert!(close(e[4], [0.0, 19.05, 0.0]), "G21 switches to mm for X0");
    let feeds: Vec<f64> = p.motions.iter().map(|m| m.feed).collect();
    // feeds are modal and converted; after G21 the stored feed stays 20 in/min = 508 mm/min
    assert_eq!(feeds, vec![0.0, 254.0, 254.0, 508.0, 508.0]);
    assert_eq!(
        p.motions.iter().map(|m| m.line).collect::<Vec<_>>(),
        vec![2, 3, 4, 5, 6]
    );
    assert_eq!(p.motions[0].kind, MotionKind::Rapid);
    assert_eq!(p.motions[0].start.cl, Point3::origin());
}

#[test]
fn initial_pose_and_chained_starts() {
    let opts = GcodeReadOptions {
        initial: Pose::vertical(Point3::new(0.0, 0.0, 50.0)),
        ..GcodeReadOptions::default()
    };
    let p = parse_gcode("G21 G90\nG0 X5\nG1 Z1 F100\nM2\n", "t.ngc", &opts).unwrap();
    assert_eq!(p.motions[0].start.cl, Point3::new(0.0, 0.0, 50.0));
    assert_eq!(p.motions[1].start, p.motions[0].end);
    assert_eq!(p.motions[1].end.axis, Vec3::z());
}

#[test]
fn comments_line_numbers_and_delimiters() {
    let text = "%\nO0100 (FANUC NUMBER)\nN10 G21 G90 (mm) ; trailing\nN20 G0 X1.5 Y2.\n/N30 G0 Z9.\nM30\n%\nG0 X99\n";
    let p = read(text);
    assert!(p.stopped.is_none());
    assert_eq!(ends(&p), vec![[1.5, 2.0, 0.0], [1.5, 2.0, 9.0]]);
    assert!(has_warning(&p, 5, 1, "block delete"));
    assert!(
        has_warning(&p, 8, 1, "not read"),
        "G0 X99 after the closing % is not read"
    );
    let skipped = parse_gcode(
        text,
        "t.ngc",
        &GcodeReadOptions {
            block_delete: true,
            ..GcodeReadOptions::default()
        },
    )
    .unwrap();
    assert_eq!(skipped.motions.len(), 1);
    // Fanuc-style program number + integer coordinates: LinuxCNC reads units, warn
    let p = read("%\nO1000\nG21 G90\nG0 X10 Y2.5\nM30\n%\n");
    assert!(has_warning(&p, 4, 4, "decimal point"));
}

#[test]
fn text_after_the_end_is_reported() {
    let p = read("G21 G90\nG0 X1\nM2\n(comment)\n\nG0 X5\n");
    assert_eq!(p.motions.len(), 1);
    assert!(has_warning(&p, 6, 1, "not read"));
    let open = read("%\nG21 G0 X1\n");
    assert!(has_warning(&open, 2, 1, "no closing %"));
    let unterminated = read("G21 G0 X1\n");
    assert!(has_warning(&unterminated, 1, 1, "without M2/M30"));
}

#[test]
fn harmless_words_warn_with_their_column() {
    let p = read("G21 G90 G64 P0.01\nG0 X1 Q3\nM60\nM8 M7 G4 P1.5\nG20 F10 G1 X1\nM2\n");
    assert!(p.stopped.is_none(), "{:?}", p.stopped);
    assert!(has_warning(&p, 1, 9, "G64"));
    assert!(has_warning(&p, 2, 7, "Q word"));
    assert!(has_warning(&p, 3, 1, "M60"));
    assert!(has_warning(&p, 4, 7, "dwell"));
    assert!(has_warning(&p, 5, 5, "units in force before"));
    // F10 read in mm (the units before the block), X1 in inches
    assert_eq!(p.motions[1].feed, 10.0);
    assert_eq!(p.motions[1].end.cl.x, 25.4);
    let missing_units = read("G90 G0 X1\nM2\n");
    assert!(has_warning(&missing_units, 1, 5, "assuming millimetres"));
}

#[test]
fn each_bad_input_names_line_and_column() {
    let cases: [(&str, usize, usize, &str); 22] = [
        ("G21\nG1 X1 Y2 G12\n", 2, 10, "unknown G code G12"),
        (
            "G21 F100\nG1 X1\nG2 X10.5 Y0 I5 J0\n",
            3,
            1,
            "radius to end of arc differs",
        ),
        ("G21 F100\nG1 X10\nG2 X0 R4\n", 3, 1, "too small"),
        ("G21\nG1 X1\n", 2, 1, "zero feed rate"),
        ("G21 F0\nG0 X1\nX2 G1\n", 3, 4, "zero feed rate"),
        (
            "G21\nG0 X1 A10\n",
            2,
            7,
            "five-axis programs need the machine's kinematics: give a machine file (swarf verify --machine FILE)",
        ),
        ("G21\nG0 X1 Y2 C-5\n", 2, 10, "rotary axis word C"),
        ("G21 G0 X1.2.3\n", 1, 8, "bad number"),
        ("G21 G0 Xabc\n", 1, 9, "unknown function or word 'abc'"),
        ("G21 G0 X1 Y\n", 1, 11, "Y word without a number"),
        ("G21\nX5\n", 2, 1, "without a motion mode"),
        ("G21 G0 X1\nG80 X2\n", 2, 1, "G80"),
        ("G21 G0 G1 X1\n", 1, 8, "same modal group"),
        ("G21 G0 X1 X2\n", 1, 11, "multiple X words"),
        (
            "G21\nG41 D1 G0 X1\n",
            2,
            5,
            "tool number 1 not found in the tool table",
        ),
        ("G21\nG81 X1 Y1 Z-1 R2\n", 2, 1, "zero feed rate"),
        ("G21\nG92\n", 2, 1, "all axes missing with G52 or G92"),
        ("G21\nG0 X#6000\n", 2, 5, "out of range"),
        ("G21\nG0 X[1/0]\n", 2, 7, "divide by zero"),
        ("G21\no100 sub\n", 2, 1, "looking for the end of o100"),
        ("G21\nM98 P100\n", 2, 1, "Fanuc dialect"),
        (
            "G21 F100 G0 X10\nG1 X0 I5\n",
            2,
            7,
            "I word with no G2, G3 or G87",
        ),
    ];
    for (text, line, column, needle) in cases {
        let (l, c, message) = stop(text);
        assert_eq!((l, c), (line, column), "{text:?}: {message}");
        assert!(message.contains(needle), "{text:?}: {message}");
    }
}

#[test]
fn arc_word_errors() {
    let cases: [(&str, usize, usize, &str); 7] = [
        (
            "G21 F100 G0 X10\nG2 X0 I-5 K1\n",
            2,
            11,
            "K word given for an arc in the XY",
        ),
        (
            "G21 F100 G0 X10\nG18 G2 X0 J1 I-5\n",
            2,
            11,
            "J word given for an arc in the XZ",
        ),
        ("G21 F100 G0 X10\nG2 X0 R5 I-5\n", 2, 7, "mixed"),
        ("G21 F100 G0 X10\nG2 X0\n", 2, 1, "without R"),
        ("G21 F100 G0 X10\nG2 X0 I-5 P1.5\n", 2, 11, "P (turns)"),
        (
            "G21 F100 G0 X10\nG2 X0 I-5 P10001\n",
            2,
            11,
            "from 1 to 10000",
        ),
        ("G21 F100 G0 X10\nG2 I0 J0\n", 2, 1, "zero-radius"),
    ];
    for (text, line, column, needle) in cases {
        let (l, c, message) = stop(text);
        assert_eq!((l, c), (line, column), "{text:?}: {message}");
        assert!(message.contains(needle), "{text:?}: {message}");
    }
}

#[test]
fn a_program_that_stops_keeps_earlier_motions() {
    let text = "G21 G90 F200\nG0 Z5\nG1 Z0\nG1 X10\nG2 X20 I5 J0\nG1 X30 B45\nG1 X40\nM30\n";
    let p = read(text);
    assert_eq!(p.motions.len(), 4);
    assert_eq!(p.motions.last().map(|m| m.line), Some(5));
    let stop = p.stopped.as_ref().unwrap();
    assert_eq!((stop.line, stop.column), (6, 8));
    assert_eq!(
        p.located(stop),
        "t.ngc:6:8: rotary axis word B: five-axis programs need the machine's kinematics: give a \
         machine file (swarf verify --machine FILE)"
    );
}

#[test]
fn tool_changes() {
    let p = read("G21 G90 T1 M6\nG0 X1\nT1 M6\nG0 X2\nT2 M6\nG0 X3\nG1 X4 F100\nM2\n");
    assert!(p.stopped.is_none());
    assert_eq!(p.motions.len(), 4);
    let tools: Vec<(usize, u32, usize)> = p
        .tools
        .iter()
        .map(|t| (t.first_motion, t.number, t.line))
        .collect();
    assert_eq!(tools, vec![(0, 1, 2), (2, 2, 6)]);
    let parts = p.split_by_tool();
    assert_eq!(parts.len(), 2);
    assert_eq!(parts[0].source, "t.ngc T1");
    assert_eq!(parts[0].motions.len(), 2);
    assert_eq!(parts[1].motions.len(), 2);
    assert_eq!(parts[1].motions[0].line, 6);
    // changes before the first motion leave one tool
    let p = read("G21 T1 M6\nT2 M6\nG0 X1\nM2\n");
    assert!(p.stopped.is_none());
    assert_eq!(p.tools.len(), 1);
    assert_eq!(p.tools[0].number, 2);
}

#[test]
fn byte_order_mark_is_skipped() {
    let p = read("\u{feff}G21 G90\nG0 X1\nM2\n");
    assert!(
        p.stopped.is_none() && p.warnings.is_empty(),
        "{:?}",
        p.stopped
    );
    assert_eq!(p.motions.len(), 1);
}

#[test]
fn binary_data_is_refused() {
    let err = parse_gcode("G21\nG0 X1\0\n", "b.ngc", &GcodeReadOptions::default()).unwrap_err();
    assert_eq!(
        err.to_string(),
        "b.ngc:2:6: control character U+0000: this is not a text program"
    );
}

#[test]
fn repeated_warnings_are_capped() {
    let mut text = String::from("G21 G90\n");
    for i in 0..100 {
        text.push_str(&format!("G0 X{i} Q1\n"));
    }
    let p = read(&text);
    // The first, to the assumed start, places the tool: a motion of its own.
    assert_eq!(p.motions.len(), 100);
    assert!(p.warnings.len() < 30, "{}", p.warnings.len());
    assert!(
        p.warnings
            .iter()
            .any(|w| w.message.starts_with("80 more warnings"))
    );
}
