//! Programs that ask for unbounded or impossible work stop with an error naming the
//! file, line and column, as LinuxCNC stops them, and keep what came before: a loop
//! that never ends (at the stated turn limit), recursion past LinuxCNC's depth, a
//! missing subroutine file, domain errors in expressions.

use swarf_nc::read::{FlowLimits, GcodeReadOptions, Program, parse_gcode};

fn read_with(text: &str, limits: FlowLimits) -> Program {
    let opts = GcodeReadOptions {
        limits,
        ..GcodeReadOptions::default()
    };
    parse_gcode(text, "loop.ngc", &opts).unwrap()
}

fn stop(text: &str) -> (usize, usize, String) {
    let d = read_with(text, FlowLimits::default())
        .stopped
        .expect("the program stops");
    (d.line, d.column, d.message)
}

#[test]
fn a_loop_that_never_ends_stops_at_the_limit() {
    let limits = FlowLimits {
        loop_iterations: 5000,
        ..FlowLimits::default()
    };
    let p = read_with(
        "G21 G90 F100\no1 while [1]\nG1 X[#1 mod 10]\n#1 = [#1 + 1]\no1 endwhile\nM2\n",
        limits,
    );
    let d = p.stopped.expect("stops");
    assert_eq!(d.line, 5, "{d:?}");
    assert!(d.message.contains("more than 5000 times"), "{}", d.message);
    assert!(
        p.motions.len() > 4000,
        "the motions before the stop are kept"
    );
    let blocks = FlowLimits {
        blocks: 10_000,
        ..FlowLimits::default()
    };
    let p = read_with("G21\no1 do\no1 while [1]\nM2\n", blocks);
    let m = p.stopped.unwrap().message;
    assert!(m.contains("more than 10000 lines beyond its own 4"), "{m}");
}

#[test]
fn recursion_past_linuxcnc_depth_is_refused() {
    let (line, _, m) = stop("G21\no<r> sub\no<r> call\no<r> endsub\no<r> call\nM2\n");
    assert_eq!(line, 3);
    assert!(m.contains("too many nested levels"), "{m}");
}

#[test]
fn a_missing_subroutine_names_the_search() {
    let (line, _, m) = stop("G21\no<nowhere> call [1]\nM2\n");
    assert_eq!(line, 2);
    assert!(m.contains("subroutine o<nowhere> not found"), "{m}");
    assert!(m.contains("nowhere.ngc"), "{m}");
}

#[test]
fn domain_errors_name_their_column() {
    for (text, column, needle) in [
        ("G21\n#1 = [1 / 0]\nM2\n", 9, "divide by zero"),
        ("G21\n#1 = sqrt[-1]\nM2\n", 6, "negative argument to sqrt"),
        ("G21\n#1 = ln[0]\nM2\n", 6, "argument to ln"),
        ("G21\n#1 = acos[2]\nM2\n", 6, "acos out of range"),
        ("G21\n#1 = [[-8] ** 0.5]\nM2\n", 12, "non-integer power"),
        ("G21\nG0 X#<nothing>\nM2\n", 5, "#<nothing> not defined"),
        ("G21\n#5420 = 1\nM2\n", 1, "read-only"),
    ] {
        let (line, c, m) = stop(text);
        assert_eq!((line, c), (2, column), "{text:?}: {m}");
        assert!(m.contains(needle), "{text:?}: {m}");
    }
}
