//! The Fanuc macro B dialect (`--dialect fanuc`) on programs whose motions follow by
//! hand from Fanuc's Custom Macro B rules: variables and vacancy, `IF`/`GOTO`/`THEN`,
//! `WHILE`/`DO`/`END`, `M98`/`M99` subprograms with repeats, `G65` macro calls with
//! argument specification I, `#3000` alarms; and the bounds on loops.

use swarf_geom::Point3;
use swarf_nc::Language;
use swarf_nc::read::{FlowLimits, GcodeReadOptions, Program, parse_gcode};

fn fanuc(text: &str) -> Program {
    let opts = GcodeReadOptions {
        language: Language::Fanuc,
        ..GcodeReadOptions::default()
    };
    parse_gcode(text, "f.nc", &opts).unwrap()
}

fn ends(p: &Program) -> Vec<[f64; 3]> {
    p.motions
        .iter()
        .map(|m| {
            let c = m.end.cl;
            [c.x, c.y, c.z].map(|v| (v * 1e9).round() / 1e9)
        })
        .collect()
}

#[test]
fn variables_expressions_and_vacancy() {
    let p = fanuc(
        "%\nO0001\nG21 G90 G0 X0 Y0 Z0\n#1 = 10\n#2 = #1 * 2 + 5\n#3 = SQRT[16] + ABS[-1]\n\
         G0 X#2 Y#3\n(#5 is vacant: Y is left out)\nG0 X#1 Y#5\n#6 = #5 + 2\nG0 Y#6\n\
         #7 = 5 OR 2\nG0 X#7\n#8 = ATAN[1, 1] + POW[2, 3]\nG0 Z#8\nM30\n%\n",
    );
    assert!(p.stopped.is_none(), "{:?}", p.stopped);
    let e = ends(&p);
    assert_eq!(e[1], [25.0, 5.0, 0.0]);
    assert_eq!(e[2], [10.0, 5.0, 0.0], "a vacant Y leaves Y where it was");
    assert_eq!(e[3], [10.0, 2.0, 0.0], "vacant + 2 is 2");
    assert_eq!(e[4], [7.0, 2.0, 0.0], "OR is bitwise in macro B");
    assert_eq!(e[5], [7.0, 2.0, 53.0]);
}

#[test]
fn goto_if_then_and_while_loops() {
    let p = fanuc(
        "G21 G90\n#1 = 0\nN10 #1 = #1 + 1\nG0 X#1 Y0\nIF [#1 LT 3] GOTO 10\n\
         IF [#1 EQ 3] THEN #2 = 7\nG0 Y#2\n#3 = 0\nWHILE [#3 LT 2] DO1\n#4 = 0\n\
         WHILE [#4 LT 2] DO2\nG0 X[#3 * 10] Y[#4 * 10] Z1\n#4 = #4 + 1\nEND2\n#3 = #3 + 1\nEND1\n\
         GOTO 99\nG0 X999\nN99 G0 Z5\nM30\n",
    );
    assert!(p.stopped.is_none(), "{:?}", p.stopped);
    let e = ends(&p);
    assert_eq!(
        &e[..3],
        &[[1.0, 0.0, 0.0], [2.0, 0.0, 0.0], [3.0, 0.0, 0.0]]
    );
    assert_eq!(e[3], [3.0, 7.0, 0.0]);
    let grid: Vec<[f64; 3]> = e[4..8].to_vec();
    assert_eq!(
        grid,
        vec![
            [0.0, 0.0, 1.0],
            [0.0, 10.0, 1.0],
            [10.0, 0.0, 1.0],
            [10.0, 10.0, 1.0]
        ]
    );
    assert_eq!(e.last(), Some(&[10.0, 10.0, 5.0]), "GOTO 99 skips X999");
}

#[test]
fn subprograms_repeat_and_macros_take_arguments() {
    let p = fanuc(
        "O0001\nG21 G91 G0 X0\nM98 P1000 L3\nG90\nG65 P2000 A5 B2\nG0 Y#1\nM30\n\
         O1000\nG0 X10\nM99\n\
         O2000\nIF [#3 EQ #0] THEN #3 = 7\nG0 X[#1 * #2] Z#3\nM99\n",
    );
    assert!(p.stopped.is_none(), "{:?}", p.stopped);
    let e = ends(&p);
    assert_eq!(
        &e[1..4],
        &[[10.0, 0.0, 0.0], [20.0, 0.0, 0.0], [30.0, 0.0, 0.0]],
        "M98 L3 runs O1000 three times, incrementally"
    );
    assert_eq!(
        e[4],
        [10.0, 0.0, 7.0],
        "A5 B2 are #1 #2; C not given: #3 vacant"
    );
    assert_eq!(
        e.len(),
        5,
        "#1 is vacant again after G65 returns: Y#1 moves nothing"
    );
}

#[test]
fn alarms_missing_targets_and_unbounded_loops_stop_with_their_line() {
    let stop = |text: &str| fanuc(text).stopped.expect("stops");
    let d = stop("G21\n#3000 = 12 (TOOL BROKEN)\nM30\n");
    assert_eq!(d.line, 2);
    assert!(d.message.contains("alarm #3000 = 12"), "{}", d.message);
    let d = stop("G21\nGOTO 50\nM30\n");
    assert!(d.message.contains("no block N50"), "{}", d.message);
    let d = stop("G21\nM98 P7777\nM30\n");
    assert!(
        d.message.contains("program O7777 not found"),
        "{}",
        d.message
    );
    let d = stop("G21\nEND1\nM30\n");
    assert!(d.message.contains("END1 without DO1"), "{}", d.message);
    let d = stop("G21\n#1 = #4999\nM30\n");
    assert!(
        d.message.contains("#4999 is not supported"),
        "{}",
        d.message
    );
    let opts = GcodeReadOptions {
        language: Language::Fanuc,
        limits: FlowLimits {
            loop_iterations: 1000,
            ..FlowLimits::default()
        },
        ..GcodeReadOptions::default()
    };
    let p = parse_gcode("G21\nWHILE [1 EQ 1] DO1\nG0 X1\nEND1\nM30\n", "f.nc", &opts).unwrap();
    let d = p.stopped.unwrap();
    assert_eq!(d.line, 2);
    assert!(d.message.contains("more than 1000 times"), "{}", d.message);
}

#[test]
fn m99_in_the_main_program_ends_it() {
    let p = fanuc("G21 G0 X1\nM99\nG0 X2\n");
    assert!(p.stopped.is_none());
    assert_eq!(p.motions.last().unwrap().end.cl, Point3::new(1.0, 0.0, 0.0));
    assert!(
        p.warnings
            .iter()
            .any(|w| w.message.contains("M99 in the main program"))
    );
}
