//! Heidenhain conversational (Klartext) programs, as swarf's Heidenhain post writes
//! them: each statement is turned into the G-code block that means the same, on the
//! same line, and the G-code reader ([`crate::read::gcode`]) runs the result, so that
//! the modal machinery, units, feeds and five-axis kinematics are those of every
//! other program and every diagnostic keeps its line.
//!
//! | Heidenhain | G-code |
//! |---|---|
//! | `n` (block number), `; text`, `* text` | (nothing) |
//! | `BEGIN PGM name MM` / `INCH` | `G17 G21` / `G20` `G40 G49 G80 G90 G90.1 G94` |
//! | `TOOL CALL t Z S s` (the length from the tool table) | `T t M6 G43 H t S s` |
//! | `L X+1 Y-2 Z+3 [A B C] R0 FMAX M..` | `G0 X1 Y-2 Z3 ... M..` |
//! | `L X.. F f M..` (or no F: the last one) | `G1 X.. F f M..` |
//! | `CC X+a Y+b` (circle centre, both words) | (nothing; kept for `C`) |
//! | `C X.. Y.. [Z..] DR- [R0] [F f] [M..]` (`DR+`) | `G2 X.. Y.. Z.. I a J b F f M..` (`G3`) |
//! | `M3`, `M5` ... (a block of M words) | the same |
//! | `END PGM name MM` | `M30` |
//!
//! `FMAX` holds for its block only; `F` is modal; `CC` holds until the next one.
//! `C` turns about `CC` in the XY plane (`DR+` counter-clockwise); a `C` block with
//! a `Z` word is read as a helix, as the G-code it becomes. Anything else (`CR`, `CT`,
//! `CP`, polar `PA`, a `C` without `DR` or before any `CC`,
//! `CYCL DEF`, `LBL`, incremental `IX`, radius compensation `RL`/`RR`, a tool axis
//! other than Z ...) stops the reading at its line and column, as an error inside
//! any program does ([`crate::read::Program::stopped`]); so does a program without
//! `BEGIN PGM` first or `END PGM` matching it.

use crate::error::NcError;
use crate::post::Language;
use crate::read::gcode::{GcodeReadOptions, check_text, parse_gcode};
use swarf_toolpath::program::{Diagnostic, Program};

/// Reads Heidenhain conversational text (module doc); `source` names it.
///
/// # Units
/// `MM` or `INCH` from `BEGIN PGM`: motions in mm, feeds in mm/min.
///
/// # Errors
/// As [`parse_gcode`]: [`NcError::Unreadable`] for binary data; errors inside the
/// program stop the reading and are reported in [`Program::stopped`].
///
/// # Example
/// ```
/// use swarf_nc::read::{GcodeReadOptions, heidenhain::parse_heidenhain};
/// let text = "0 BEGIN PGM 1 MM\n1 TOOL CALL 1 Z S5000\n2 L X+10 Y-5 Z+2 FMAX\n\
///             3 L Z-1 F300\n4 END PGM 1 MM\n";
/// let p = parse_heidenhain(text, "a.h", &GcodeReadOptions::default()).unwrap();
/// assert!(p.stopped.is_none());
/// assert_eq!(p.motions.len(), 2);
/// assert_eq!(p.motions[1].end.cl.z, -1.0);
/// ```
pub fn parse_heidenhain(
    text: &str,
    source: &str,
    opts: &GcodeReadOptions,
) -> Result<Program, NcError> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    check_text(text, source)?;
    let mut state = State::default();
    let mut gcode = String::with_capacity(text.len() + 64);
    let mut error = None;
    for (i, raw) in text.lines().enumerate() {
        match statement(raw, i + 1, &mut state) {
            Ok(block) => gcode.push_str(&block),
            Err(d) => {
                // Ends the translated program here, so that the G-code reader runs
                // what came before and the error is this line's.
                gcode.push_str("M2");
                error = Some(d);
                break;
            }
        }
        gcode.push('\n');
    }
    if error.is_none() && state.end.is_none() {
        let last = text.lines().count().max(1);
        error = Some(Diagnostic::new(last, 1, "the program has no END PGM"));
    }
    let g = GcodeReadOptions {
        language: Language::Linuxcnc,
        ..*opts
    };
    let mut program = parse_gcode(&gcode, source, &g)?;
    if program.stopped.is_none() {
        program.stopped = error;
    }
    Ok(program)
}

/// What the statements so far declared.
#[derive(Debug, Default)]
struct State {
    /// `BEGIN PGM`'s name and units.
    begin: Option<(String, String)>,
    /// The line of `END PGM`.
    end: Option<usize>,
    /// The circle centre of the last `CC` (X and Y as G-code writes them).
    cc: Option<(String, String)>,
}

/// The words of a line with their 1-based columns, the block number, comments and
/// everything after `;` left out.
fn words(raw: &str) -> Vec<(usize, &str)> {
    let code = raw.split(';').next().unwrap_or("");
    if code.trim_start().starts_with('*') {
        return Vec::new();
    }
    let mut out = Vec::new();
    let mut start = None;
    for (k, (i, c)) in code.char_indices().enumerate() {
        match (c.is_whitespace(), start) {
            (false, None) => start = Some((k, i)),
            (true, Some((col, s))) => {
                out.push((col + 1, &code[s..i]));
                start = None;
            }
            _ => {}
        }
    }
    if let Some((col, s)) = start {
        out.push((col + 1, &code[s..]));
    }
    if out
        .first()
        .is_some_and(|(_, w)| w.bytes().all(|b| b.is_ascii_digit()))
    {
        out.remove(0);
    }
    out
}

/// The G-code block of the statement on line `line`.
fn statement(raw: &str, line: usize, state: &mut State) -> Result<String, Diagnostic> {
    let w = words(raw);
    let Some(&(col, first)) = w.first() else {
        return Ok(String::new());
    };
    let at = |col: usize, m: String| Diagnostic::new(line, col, m);
    if state.end.is_some() {
        return Err(at(col, "a statement after END PGM".into()));
    }
    let keyword = first.to_ascii_uppercase();
    if state.begin.is_none() && keyword != "BEGIN" {
        return Err(at(col, format!("{first}: expected BEGIN PGM first")));
    }
    match keyword.as_str() {
        "BEGIN" | "END" => program(&w, line, state),
        "TOOL" => tool_call(&w, line),
        "L" => straight(&w[1..], line),
        "CC" => {
            state.cc = Some(circle_center(&w, line)?);
            Ok(String::new())
        }
        "C" => circle(&w, line, state.cc.as_ref()),
        _ if keyword.starts_with('M') => {
            let mut block = String::new();
            for &(col, word) in &w {
                push(&mut block, &m_word(word).map_err(|m| at(col, m))?);
            }
            Ok(block)
        }
        _ => Err(at(
            col,
            format!(
                "{first} is not read by swarf's Heidenhain reader (it reads BEGIN PGM, \
                 TOOL CALL, L, CC, C, M blocks, ; comments and END PGM)"
            ),
        )),
    }
}

/// `BEGIN PGM name MM|INCH` and `END PGM name MM|INCH`.
fn program(w: &[(usize, &str)], line: usize, state: &mut State) -> Result<String, Diagnostic> {
    let (col, first) = w[0];
    let upper: Vec<String> = w.iter().map(|(_, s)| s.to_ascii_uppercase()).collect();
    let [_, pgm, name, units] = upper.as_slice() else {
        return Err(Diagnostic::new(
            line,
            col,
            format!("expected {first} PGM name MM|INCH"),
        ));
    };
    if pgm != "PGM" || !matches!(units.as_str(), "MM" | "INCH") {
        return Err(Diagnostic::new(
            line,
            col,
            format!("expected {first} PGM name MM|INCH"),
        ));
    }
    let declared = (name.clone(), units.clone());
    if upper[0] == "BEGIN" {
        if state.begin.is_some() {
            return Err(Diagnostic::new(line, col, "a second BEGIN PGM"));
        }
        state.begin = Some(declared);
        let g = if units == "MM" { "G21" } else { "G20" };
        return Ok(format!("G17 {g} G40 G49 G80 G90 G90.1 G94"));
    }
    if state.begin.as_ref() != Some(&declared) {
        let (n, u) = state.begin.clone().unwrap_or_default();
        return Err(Diagnostic::new(
            line,
            col,
            format!("END PGM {name} {units} does not match BEGIN PGM {n} {u}"),
        ));
    }
    state.end = Some(line);
    Ok("M30".into())
}

/// `TOOL CALL t [Z] [S s]`.
fn tool_call(w: &[(usize, &str)], line: usize) -> Result<String, Diagnostic> {
    let at = |col: usize, m: String| Diagnostic::new(line, col, m);
    let (col, _) = w[0];
    if w.get(1)
        .is_none_or(|(_, s)| !s.eq_ignore_ascii_case("CALL"))
    {
        return Err(at(col, "expected TOOL CALL".into()));
    }
    let Some(&(tcol, tool)) = w.get(2) else {
        return Err(at(col, "TOOL CALL: expected a tool number".into()));
    };
    let tool: u32 = tool
        .parse()
        .map_err(|_| at(tcol, format!("TOOL CALL: {tool} is not a tool number")))?;
    let mut block = format!("T{tool} M6 G43 H{tool}");
    let mut rest = w[3..].iter().peekable();
    while let Some(&(col, word)) = rest.next() {
        let upper = word.to_ascii_uppercase();
        if upper == "Z" {
            continue;
        }
        if let Some(v) = upper.strip_prefix('S') {
            let v = if v.is_empty() {
                rest.next().map_or("", |(_, s)| *s)
            } else {
                v
            };
            push(
                &mut block,
                &format!("S{}", number(v).map_err(|m| at(col, m))?),
            );
            continue;
        }
        let what = if matches!(upper.as_str(), "X" | "Y") {
            format!("TOOL CALL: tool axis {word}: swarf reads tool axis Z only")
        } else {
            format!("TOOL CALL: {word} is not read (swarf reads the tool number, Z and S)")
        };
        return Err(at(col, what));
    }
    Ok(block)
}

/// `CC X+a Y+b`: the centre's X and Y.
fn circle_center(w: &[(usize, &str)], line: usize) -> Result<(String, String), Diagnostic> {
    let at = |col: usize, m: String| Diagnostic::new(line, col, m);
    let (mut x, mut y) = (None, None);
    for &(col, word) in &w[1..] {
        let upper = word.to_ascii_uppercase();
        let (letter, value) = upper.split_at(1.min(upper.len()));
        let slot = match letter {
            "X" => &mut x,
            "Y" => &mut y,
            _ => {
                return Err(at(
                    col,
                    format!("CC: {word} is not read (swarf reads CC X.. Y..)"),
                ));
            }
        };
        *slot = Some(number(value).map_err(|e| at(col, e))?);
    }
    match (x, y) {
        (Some(x), Some(y)) => Ok((x, y)),
        _ => Err(at(w[0].0, "CC: expected both X and Y".into())),
    }
}

/// `C X.. Y.. [Z..] DR-|DR+ ...` about the centre `cc`.
fn circle(
    w: &[(usize, &str)],
    line: usize,
    cc: Option<&(String, String)>,
) -> Result<String, Diagnostic> {
    let at = |col: usize, m: String| Diagnostic::new(line, col, m);
    let Some((cx, cy)) = cc else {
        return Err(at(w[0].0, "C: no circle centre (CC) before it".into()));
    };
    let mut direction = None;
    let mut rest = Vec::with_capacity(w.len());
    for &(col, word) in &w[1..] {
        match word.to_ascii_uppercase().as_str() {
            "DR-" => direction = Some("G2"),
            "DR+" => direction = Some("G3"),
            "FMAX" => return Err(at(col, "C: FMAX is not read on arcs".into())),
            _ => rest.push((col, word)),
        }
    }
    let Some(g) = direction else {
        return Err(at(w[0].0, "C: expected DR- or DR+".into()));
    };
    let (axes, feed, m, _) = motion_words(&rest, line, "C")?;
    if axes.is_empty() {
        return Err(at(w[0].0, "C: expected an end point".into()));
    }
    let mut block = format!("{g} {axes} I{cx} J{cy}");
    push(&mut block, &feed);
    push(&mut block, &m);
    Ok(block)
}

/// The words after `L`.
fn straight(w: &[(usize, &str)], line: usize) -> Result<String, Diagnostic> {
    let (axes, feed, m, rapid) = motion_words(w, line, "L")?;
    let mut block = String::new();
    if !axes.is_empty() {
        block.push_str(if rapid { "G0 " } else { "G1 " });
        block.push_str(&axes);
    }
    if !rapid {
        push(&mut block, &feed);
    }
    push(&mut block, &m);
    Ok(block)
}

/// The axis, feed and M words of a motion statement `what` (`L`, `C`), and
/// whether it is a rapid (`FMAX`).
fn motion_words(
    w: &[(usize, &str)],
    line: usize,
    what: &str,
) -> Result<(String, String, String, bool), Diagnostic> {
    let at = |col: usize, m: String| Diagnostic::new(line, col, m);
    let (mut axes, mut feed, mut m) = (String::new(), String::new(), String::new());
    let mut rapid = false;
    for &(col, word) in w {
        let upper = word.to_ascii_uppercase();
        let (letter, value) = upper.split_at(1.min(upper.len()));
        match letter {
            "X" | "Y" | "Z" | "A" | "B" | "C" => {
                push(
                    &mut axes,
                    &format!("{letter}{}", number(value).map_err(|e| at(col, e))?),
                );
            }
            "F" if value == "MAX" => rapid = true,
            "F" => push(
                &mut feed,
                &format!("F{}", number(value).map_err(|e| at(col, e))?),
            ),
            "M" => push(&mut m, &m_word(word).map_err(|e| at(col, e))?),
            "R" if value == "0" => {}
            "R" => {
                return Err(at(
                    col,
                    format!("{what}: radius compensation {word} is not read (R0 only)"),
                ));
            }
            "I" => return Err(at(col, format!("{what}: incremental {word} is not read"))),
            _ => return Err(at(col, format!("{what}: {word} is not read"))),
        }
    }
    Ok((axes, feed, m, rapid))
}

/// An `M` word, checked.
fn m_word(word: &str) -> Result<String, String> {
    let digits = &word[1.min(word.len())..];
    match digits.parse::<u32>() {
        Ok(n) if word[..1].eq_ignore_ascii_case("M") => Ok(format!("M{n}")),
        _ => Err(format!("{word} is not an M function")),
    }
}

/// A signed decimal (`+10.5`, `-3`, `10`) as G-code writes it.
fn number(text: &str) -> Result<String, String> {
    let t = text.strip_prefix('+').unwrap_or(text);
    if t.is_empty() || t.parse::<f64>().map_or(true, |v| !v.is_finite()) || t.contains(['e', 'E']) {
        return Err(format!("{text:?} is not a number"));
    }
    Ok(t.to_string())
}

/// Appends `word` to `block`, after a space unless either is empty.
fn push(block: &mut String, word: &str) {
    if word.is_empty() {
        return;
    }
    if !block.is_empty() {
        block.push(' ');
    }
    block.push_str(word);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::read::MotionKind;

    fn read(text: &str) -> Program {
        parse_heidenhain(text, "t.h", &GcodeReadOptions::default()).unwrap()
    }

    #[test]
    fn statements_become_motions() {
        let p = read(
            "0 BEGIN PGM 5 INCH\n1 ; part\n2 TOOL CALL 2 Z S8000\n3 M3\n\
             4 L X+1 Y+0 Z+0.5 R0 FMAX\n5 L Z-0.1 F10\n6 L X+2\n7 M5\n8 END PGM 5 INCH\n",
        );
        assert!(p.stopped.is_none(), "{:?}", p.stopped);
        assert_eq!(p.motions.len(), 3);
        let end = p.motions[2].end.cl;
        assert!((end.x - 50.8).abs() < 1e-9 && (end.z + 2.54).abs() < 1e-9);
        assert!((p.motions[2].feed - 254.0).abs() < 1e-9);
        assert_eq!(p.motions[2].line, 7);
    }

    #[test]
    fn circles_about_cc_are_arcs() {
        let p = read(
            "0 BEGIN PGM 5 MM\n1 TOOL CALL 2 Z S8000\n2 L X+10 Y+0 Z-1 FMAX\n\
             3 CC X+0 Y+0\n4 C X+0 Y+10 DR+ F300\n5 C X-10 Y+0 Z-2 DR- R0\n\
             6 L X+20 F200\n7 END PGM 5 MM\n",
        );
        assert!(p.stopped.is_none(), "{:?}", p.stopped);
        assert_eq!(p.motions.len(), 4);
        let (ccw, cw) = (&p.motions[1], &p.motions[2]);
        assert!(matches!(
            ccw.kind,
            MotionKind::Arc {
                clockwise: false,
                ..
            }
        ));
        assert!(matches!(
            cw.kind,
            MotionKind::Arc {
                clockwise: true,
                ..
            }
        ));
        // A quarter turn counter-clockwise passes (7.07, 7.07); the clockwise way
        // on to (-10, 0) goes through the fourth quadrant (three quarters), falling 1 mm.
        let mid = ccw.point_at(0.5).cl;
        assert!((mid.x - 50f64.sqrt()).abs() < 1e-9 && (mid.y - 50f64.sqrt()).abs() < 1e-9);
        assert!((cw.sweep().unwrap() - 1.5 * std::f64::consts::PI).abs() < 1e-9);
        let mid = cw.point_at(0.5).cl;
        assert!((mid.x - 50f64.sqrt()).abs() < 1e-9 && (mid.y + 50f64.sqrt()).abs() < 1e-9);
        assert!((mid.z + 1.5).abs() < 1e-9);
        assert!((cw.end.cl.z + 2.0).abs() < 1e-12 && (cw.feed - 300.0).abs() < 1e-12);
        assert!(matches!(p.motions[3].kind, MotionKind::Linear));
        assert_eq!(p.motions[3].line, 7);
    }

    #[test]
    fn what_is_not_read_stops_at_its_line_and_column() {
        let cases = [
            (
                "0 BEGIN PGM 1 MM\n1 CR X+0 Y+0 R+5 DR-\n",
                2,
                3,
                "CR is not read",
            ),
            (
                "0 BEGIN PGM 1 MM\n1 CC X+0\n",
                2,
                3,
                "CC: expected both X and Y",
            ),
            (
                "0 BEGIN PGM 1 MM\n1 CC IX+0 Y+0\n",
                2,
                6,
                "CC: IX+0 is not read",
            ),
            (
                "0 BEGIN PGM 1 MM\n1 C X+1 Y+0 DR-\n",
                2,
                3,
                "no circle centre",
            ),
            (
                "0 BEGIN PGM 1 MM\n1 CC X+0 Y+0\n2 C X+1 Y+0 F100\n",
                3,
                3,
                "expected DR- or DR+",
            ),
            (
                "0 BEGIN PGM 1 MM\n1 CC X+0 Y+0\n2 C X+1 Y+0 RL DR+ F100\n",
                3,
                13,
                "C: radius compensation RL",
            ),
            (
                "0 BEGIN PGM 1 MM\n1 L X+1 RL F100\n",
                2,
                9,
                "radius compensation RL",
            ),
            (
                "0 BEGIN PGM 1 MM\n1 L IX+1 F100\n",
                2,
                5,
                "incremental IX+1",
            ),
            ("0 BEGIN PGM 1 MM\n1 L X+1a F100\n", 2, 5, "is not a number"),
            ("0 BEGIN PGM 1 MM\n1 TOOL CALL 1 X\n", 2, 15, "tool axis X"),
            ("1 L X+1 FMAX\n", 1, 3, "expected BEGIN PGM first"),
            ("0 BEGIN PGM 1 MM\n1 END PGM 2 MM\n", 2, 3, "does not match"),
            ("0 BEGIN PGM 1 MM\n1 L X+1 FMAX\n", 2, 1, "no END PGM"),
        ];
        for (text, line, column, what) in cases {
            let d = read(text).stopped.unwrap();
            assert_eq!((d.line, d.column), (line, column), "{text}: {d:?}");
            assert!(d.message.contains(what), "{text}: {}", d.message);
        }
        // A feed move before any feed: the G-code reader's error, at its line.
        let d = read("0 BEGIN PGM 1 MM\n1 L X+1\n2 END PGM 1 MM\n")
            .stopped
            .unwrap();
        assert_eq!(d.line, 2);
    }
}
