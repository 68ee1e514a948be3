//! The G-code reader against LinuxCNC's `rs274` on the reference corpus
//! (`tests/corpus/`, its README): for every program rs274 accepts, swarf's motions
//! equal rs274's canonical moves point for point (ends, arc centres, directions and
//! turns) to 1e-6 mm, and its `(DEBUG, ...)` messages equal rs274's; every program
//! rs274 refuses, swarf refuses.
//!
//! The oracle carries rs274's moves into the part frame with the canonical calls it
//! prints, independently of swarf's reader: `machine = rot(p + g92) + g5x + tool`
//! (`SET_G92_OFFSET`, `SET_XY_ROTATION`, `SET_G5X_OFFSET`, `USE_TOOL_LENGTH_OFFSET`, in
//! the units of `USE_LENGTH_UNITS` when printed), less the offset of the tool that
//! `CHANGE_TOOL` loaded, read from the corpus tool table (inches: rs274 is an inch
//! machine). With `rs274` installed, `record --check` proves the recordings current.

use std::path::{Path, PathBuf};
use swarf_geom::Point3;
use swarf_nc::read::{
    GcodeReadOptions, Motion, MotionKind, ToolTable, parse_gcode, parse_var_file,
};
use swarf_testkit::references::skip_reference;

/// Programs whose comparison is left out, and why.
const LEFT_OUT: [(&str, &str); 1] = [(
    "40-",
    "cutter compensation in G18 is lathe compensation: swarf refuses it by name",
)];

/// LinuxCNC examples where standalone rs274 departs from the machine, and why.
const EXAMPLES_LEFT_OUT: [(&str, &str); 1] = [(
    "skeleton.ngc",
    "M6 and G43 in one block: standalone rs274 then re-reads the position from its own \
     canonical layer, which ignores the new tool length offset; LinuxCNC's task (and swarf) \
     keep the tip where the machine left it",
)];

fn corpus() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/corpus")
}

/// One canonical move, in the part frame (mm).
#[derive(Debug, Clone, Copy)]
struct Canon {
    rapid: bool,
    end: Point3,
    /// Arc: centre and plane normal index and signed turns.
    arc: Option<(Point3, usize, i32)>,
}

/// What rs274 printed: the moves, the messages, and whether it accepted the program.
struct Recording {
    moves: Vec<Canon>,
    messages: Vec<String>,
    accepted: bool,
    error: String,
}

fn args(call: &str) -> Vec<f64> {
    let inner = &call[call.find('(').unwrap() + 1..call.rfind(')').unwrap()];
    inner
        .split([',', ' '])
        .filter(|a| !a.trim().is_empty())
        .map(|a| a.trim().parse().unwrap_or(f64::NAN))
        .collect()
}

fn rotate(x: f64, y: f64, deg: f64) -> (f64, f64) {
    let (s, c) = deg.to_radians().sin_cos();
    (x * c - y * s, x * s + y * c)
}

/// The frame the oracle carries program points through (all mm).
struct Frame {
    scale: f64,
    g5x: [f64; 3],
    g92: [f64; 3],
    rotation: f64,
    tool: [f64; 3],
    loaded: [f64; 3],
}

impl Frame {
    /// Takes in a canonical call that changes the frame; false for other calls.
    fn apply(&mut self, name: &str, call: &str, tools: &ToolTable) -> bool {
        let a = || args(call);
        match name {
            "USE_LENGTH_UNITS" => self.scale = if call.contains("INCHES") { 25.4 } else { 1.0 },
            "SET_G5X_OFFSET" => self.g5x = [1, 2, 3].map(|k| a()[k] * self.scale),
            "SET_G92_OFFSET" => self.g92 = [0, 1, 2].map(|k| a()[k] * self.scale),
            "SET_XY_ROTATION" => self.rotation = a()[0],
            "USE_TOOL_LENGTH_OFFSET" => self.tool = [0, 1, 2].map(|k| a()[k] * self.scale),
            "CHANGE_TOOL" => {
                let t = tools.get(a()[0] as u32).copied().unwrap_or_default();
                self.loaded = [0, 1, 2].map(|k| t.offset[k] * 25.4);
            }
            _ => return false,
        }
        true
    }

    fn part(&self, p: [f64; 3]) -> Point3 {
        let q = [0, 1, 2].map(|k| p[k] * self.scale + self.g92[k]);
        let (x, y) = rotate(q[0], q[1], self.rotation);
        let r = [x, y, q[2]];
        Point3::from([0, 1, 2].map(|k| r[k] + self.g5x[k] + self.tool[k] - self.loaded[k]))
    }
}

fn parse_recording(text: &str, tools: &ToolTable) -> Recording {
    let (out, rest) = text.split_once("--- stderr").unwrap_or((text, ""));
    let accepted = rest.contains("--- exit 0");
    let error = rest
        .lines()
        .filter(|l| !l.trim().is_empty() && !l.starts_with("---") && *l != "executing")
        .collect::<Vec<_>>()
        .join(" / ");
    let mut f = Frame {
        scale: 1.0,
        g5x: [0.0; 3],
        g92: [0.0; 3],
        rotation: 0.0,
        tool: [0.0; 3],
        loaded: [0.0; 3],
    };
    let mut plane = [0usize, 1, 2];
    let mut moves = Vec::new();
    let mut messages = Vec::new();
    for line in out.lines() {
        let mut fields = line.trim_start().splitn(3, ' ');
        let (Some(_), Some(n), Some(call)) = (fields.next(), fields.next(), fields.next()) else {
            continue;
        };
        if !n.starts_with('N') {
            continue;
        }
        let call = call.trim_start();
        let a = || args(call);
        let name = call.split('(').next().unwrap_or("");
        if f.apply(name, call, tools) {
            continue;
        }
        match name {
            "SELECT_PLANE" => {
                plane = match call {
                    c if c.contains("PLANE_XZ") => [2, 0, 1],
                    c if c.contains("PLANE_YZ") => [1, 2, 0],
                    _ => [0, 1, 2],
                };
            }
            "MESSAGE" => {
                let inner = &call[call.find('"').unwrap() + 1..call.rfind('"').unwrap()];
                messages.push(inner.to_string());
            }
            "STRAIGHT_TRAVERSE" | "STRAIGHT_FEED" => {
                let v = a();
                moves.push(Canon {
                    rapid: name == "STRAIGHT_TRAVERSE",
                    end: f.part([v[0], v[1], v[2]]),
                    arc: None,
                });
            }
            "ARC_FEED" => {
                let v = a();
                let mut end = [0.0; 3];
                end[plane[0]] = v[0];
                end[plane[1]] = v[1];
                end[plane[2]] = v[5];
                let mut center = end;
                center[plane[0]] = v[2];
                center[plane[1]] = v[3];
                moves.push(Canon {
                    rapid: false,
                    end: f.part(end),
                    arc: Some((f.part(center), plane[2], v[4] as i32)),
                });
            }
            _ => {}
        }
    }
    Recording {
        moves,
        messages,
        accepted,
        error,
    }
}

/// Drops moves of (nearly) zero length after the first, as swarf's reader does.
fn drop_still<T>(items: Vec<T>, end: impl Fn(&T) -> Point3, is_arc: impl Fn(&T) -> bool) -> Vec<T> {
    let mut out: Vec<T> = Vec::new();
    for m in items {
        let still = out
            .last()
            .is_some_and(|p| (end(p) - end(&m)).norm() < 1e-9 && !is_arc(&m));
        if !still {
            out.push(m);
        }
    }
    out
}

fn read_swarf(
    name: &str,
    tools: &ToolTable,
    vars: &[(usize, f64)],
    subs: &[PathBuf],
) -> swarf_nc::read::Program {
    let path = corpus().join(name);
    let text = std::fs::read_to_string(&path).unwrap();
    let opts = GcodeReadOptions {
        tool_table: Some(tools),
        machine_inch: true,
        parameters: vars,
        sub_path: subs,
        ..GcodeReadOptions::default()
    };
    parse_gcode(&text, name, &opts).unwrap()
}

/// Motions of G88's simulated manual retract (not a canonical move of rs274).
fn manual_retracts(p: &swarf_nc::read::Program) -> Vec<usize> {
    p.warnings
        .iter()
        .filter(|w| w.message.starts_with("G88"))
        .map(|w| w.line)
        .collect()
}

/// Compares swarf's motions with rs274's; `retracts`: the lines of G88 cycles, whose
/// manual retract swarf simulates as a rapid straight up and rs274 leaves to the
/// operator (the oracle inserts it, and drops the move it makes redundant).
fn compare(
    name: &str,
    motions: &[Motion],
    rec: &Recording,
    retracts: &[usize],
) -> Result<(), String> {
    let ours = drop_still(
        motions.to_vec(),
        |m| m.end.cl,
        |m| !matches!(m.kind, MotionKind::Rapid | MotionKind::Linear),
    );
    let mut theirs = drop_still(rec.moves.clone(), |c| c.end, |c| c.arc.is_some());
    for (k, m) in ours.iter().enumerate() {
        let manual = m.kind == MotionKind::Rapid
            && retracts.contains(&m.line)
            && m.start.cl.x == m.end.cl.x
            && m.start.cl.y == m.end.cl.y
            && m.end.cl.z > m.start.cl.z;
        if manual && k <= theirs.len() {
            theirs.insert(
                k,
                Canon {
                    rapid: true,
                    end: m.end.cl,
                    arc: None,
                },
            );
            if theirs
                .get(k + 1)
                .is_some_and(|c| c.arc.is_none() && (c.end - m.end.cl).norm() < 1e-9)
            {
                theirs.remove(k + 1);
            }
        }
    }
    if ours.len() != theirs.len() {
        return Err(format!(
            "{name}: {} motions against rs274's {}",
            ours.len(),
            theirs.len()
        ));
    }
    for (k, (m, c)) in ours.iter().zip(&theirs).enumerate() {
        let off = (m.end.cl - c.end).norm();
        if off > 1e-6 {
            return Err(format!(
                "{name}: motion {k} (line {}) ends at {:?}, rs274 at {:?} ({off:e} mm)",
                m.line, m.end.cl, c.end
            ));
        }
        match (m.kind, c.arc) {
            (MotionKind::Rapid, None) if c.rapid => {}
            (MotionKind::Linear, None) if !c.rapid => {}
            (
                MotionKind::Arc {
                    center,
                    normal,
                    clockwise,
                    turns,
                },
                Some((rc, n, rotation)),
            ) => {
                let axis = normal.iamax();
                let d = center - rc;
                let in_plane = (d - normal * d.dot(&normal)).norm();
                if axis != n
                    || in_plane > 1e-6
                    || clockwise != (rotation < 0)
                    || turns != rotation.unsigned_abs()
                {
                    return Err(format!(
                        "{name}: arc {k} (line {}): centre {center:?} normal {normal:?} cw {clockwise} turns {turns}; rs274 {rc:?} axis {n} rotation {rotation}",
                        m.line
                    ));
                }
            }
            (kind, arc) => {
                return Err(format!(
                    "{name}: motion {k} (line {}): {kind:?} against rapid {} arc {arc:?}",
                    m.line, c.rapid
                ));
            }
        }
    }
    Ok(())
}

#[test]
fn corpus_matches_rs274_point_for_point() {
    let dir = corpus();
    let tools = ToolTable::parse(
        &std::fs::read_to_string(dir.join("tool.tbl")).unwrap(),
        "tool.tbl",
    )
    .unwrap();
    let vars = parse_var_file(
        &std::fs::read_to_string(dir.join("rs274ngc.var")).unwrap(),
        "rs274ngc.var",
    )
    .unwrap();
    let subs = vec![dir.join("subs")];
    let mut names: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .filter_map(|e| e.ok()?.file_name().into_string().ok())
        .filter(|n| n.ends_with(".ngc"))
        .collect();
    names.sort();
    assert!(names.len() >= 90, "{}", names.len());
    let mut failures = Vec::new();
    let (mut compared, mut refused, mut motions) = (0, 0, 0);
    for name in &names {
        if LEFT_OUT.iter().any(|(p, _)| name.starts_with(p)) {
            continue;
        }
        let rec_text = std::fs::read_to_string(dir.join(name.replace(".ngc", ".rs274"))).unwrap();
        let rec = parse_recording(&rec_text, &tools);
        let p = read_swarf(name, &tools, &vars, &subs);
        if !rec.accepted {
            refused += 1;
            if p.stopped.is_none() {
                failures.push(format!(
                    "{name}: rs274 refuses ({}) but swarf reads it",
                    rec.error
                ));
            }
            continue;
        }
        if let Some(stop) = &p.stopped {
            failures.push(format!("{name}: swarf stopped: {}", p.located(stop)));
            continue;
        }
        let retracts = manual_retracts(&p);
        let kept = p.motions.clone();
        if std::env::var("CORPUS_SHOW").is_ok_and(|v| name.starts_with(&v)) {
            for m in &kept {
                println!("swarf line {} {:?} -> {:?}", m.line, m.kind, m.end.cl);
            }
            for c in &rec.moves {
                println!("rs274 rapid {} -> {:?} {:?}", c.rapid, c.end, c.arc);
            }
        }
        match compare(name, &kept, &rec, &retracts) {
            Ok(()) => {
                compared += 1;
                motions += kept.len();
            }
            Err(e) => failures.push(e),
        }
        let ours: Vec<&str> = p.messages.iter().map(|m| m.message.as_str()).collect();
        let theirs: Vec<&str> = rec.messages.iter().map(String::as_str).collect();
        if ours != theirs {
            failures.push(format!(
                "{name}: messages {ours:?} against rs274's {theirs:?}"
            ));
        }
    }
    println!(
        "corpus: {compared} programs ({motions} motions) match rs274, {refused} refused by both"
    );
    assert!(
        failures.is_empty(),
        "{} of {} programs differ:\n{}",
        failures.len(),
        names.len(),
        failures.join("\n")
    );
}

#[test]
fn recordings_are_current() {
    let dir = corpus();
    let out = std::process::Command::new("bash")
        .arg(dir.join("record"))
        .arg("--check")
        .current_dir(&dir)
        .output();
    match out {
        Ok(o) if o.status.success() => {}
        Ok(o) => {
            let text = format!(
                "{}{}",
                String::from_utf8_lossy(&o.stdout),
                String::from_utf8_lossy(&o.stderr)
            );
            if o.status.code() == Some(2) {
                skip_reference("rs274", &text);
            } else {
                panic!("record --check failed:\n{text}");
            }
        }
        Err(e) => skip_reference("rs274", &e.to_string()),
    }
}

/// All `.ngc` files under `dir`, recursively.
fn ngc_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    let mut paths: Vec<PathBuf> = entries.filter_map(|e| Some(e.ok()?.path())).collect();
    paths.sort();
    for p in paths {
        if p.is_dir() {
            ngc_files(&p, out);
        } else if p.extension().is_some_and(|e| e == "ngc") {
            out.push(p);
        }
    }
}

/// How swarf's reading of a LinuxCNC example compares with rs274's.
enum Verdict {
    Same,
    BothRefuse,
    /// rs274 refuses it only for a missing program end; swarf warns.
    Unended,
    /// swarf refuses it naming a feature it does not support.
    Named(String),
    Differ(String),
}

fn judge(name: &str, rec: &Recording, read: Result<swarf_nc::read::Program, String>) -> Verdict {
    let p = match read {
        Ok(p) => p,
        Err(_) if !rec.accepted => return Verdict::BothRefuse,
        Err(e) => return Verdict::Differ(format!("{name}: swarf cannot read it: {e}")),
    };
    let unended = rec
        .error
        .contains("File ended with no percent sign or program end");
    match (rec.accepted, &p.stopped) {
        (true, None) => match compare(name, &p.motions, rec, &manual_retracts(&p)) {
            Ok(()) => Verdict::Same,
            Err(e) => Verdict::Differ(e),
        },
        (true, Some(stop))
            if stop.message.contains("not supported")
                || stop.message.contains("machine's kinematics") =>
        {
            Verdict::Named(format!("{name}: {}", stop.message))
        }
        (true, Some(stop)) => Verdict::Differ(format!(
            "{name}: rs274 reads it, swarf stopped: {}",
            p.located(stop)
        )),
        (false, Some(_)) => Verdict::BothRefuse,
        (false, None)
            if unended
                && p.warnings
                    .iter()
                    .any(|w| w.message.contains("without M2/M30")) =>
        {
            Verdict::Unended
        }
        (false, None) => Verdict::Differ(format!(
            "{name}: rs274 refuses it ({}), swarf reads it",
            rec.error
        )),
    }
}

/// LinuxCNC's example programs, flattened into one new folder with the corpus tool
/// table: (the folder, the program names).
fn gather_examples(examples: &Path) -> (PathBuf, Vec<String>) {
    let mut files = Vec::new();
    ngc_files(examples, &mut files);
    let work = std::env::temp_dir().join(format!("swarf-ncfiles-{}", std::process::id()));
    std::fs::create_dir_all(&work).unwrap();
    let mut names = Vec::new();
    for f in &files {
        let name = f.file_name().unwrap().to_string_lossy().into_owned();
        if !names.contains(&name) {
            std::fs::copy(f, work.join(&name)).unwrap();
            names.push(name);
        }
    }
    std::fs::copy(corpus().join("tool.tbl"), work.join("tool.tbl")).unwrap();
    (work, names)
}

/// LinuxCNC's own example programs (Debian's `linuxcnc-uspace`), all in one folder
/// with the corpus tool table, each read by rs274 (live, full precision) and by swarf:
/// every program both accept matches point for point; every program rs274 refuses,
/// swarf refuses, except those rs274 refuses only for a missing program end (swarf
/// reads them and warns that LinuxCNC reports an error there); a program only swarf
/// refuses must name the feature swarf does not support.
#[test]
fn linuxcnc_examples_as_rs274_reads_them() {
    let examples = Path::new("/usr/share/linuxcnc/ncfiles");
    if !examples.is_dir() {
        skip_reference("rs274", "LinuxCNC's example programs are not installed");
        return;
    }
    let (work, names) = gather_examples(examples);
    let text = std::fs::read_to_string(corpus().join("tool.tbl")).unwrap();
    let tools = ToolTable::parse(&text, "tool.tbl").unwrap();
    let subs = vec![work.clone()];
    let opts = GcodeReadOptions {
        tool_table: Some(&tools),
        machine_inch: true,
        sub_path: &subs,
        ..GcodeReadOptions::default()
    };
    let (mut same, mut both, mut unended, mut named, mut failures) = (0, 0, 0, vec![], vec![]);
    for name in &names {
        if EXAMPLES_LEFT_OUT.iter().any(|(n, _)| n == name) {
            continue;
        }
        let Some(text) = swarf_testkit::rs274::run_rs274_precise(&work, name, "tool.tbl") else {
            return;
        };
        let rec = parse_recording(&text, &tools);
        let program = std::fs::read_to_string(work.join(name)).unwrap();
        match judge(
            name,
            &rec,
            parse_gcode(&program, name, &opts).map_err(|e| e.to_string()),
        ) {
            Verdict::Same => same += 1,
            Verdict::BothRefuse => both += 1,
            Verdict::Unended => unended += 1,
            Verdict::Named(n) => named.push(n),
            Verdict::Differ(d) => failures.push(d),
        }
    }
    let _ = std::fs::remove_dir_all(&work);
    println!(
        "LinuxCNC examples: {} programs; {same} match rs274 point for point, {both} refused by \
         both, {unended} read with a warning where rs274 wants a program end, {} refused by \
         swarf by name:\n  {}",
        names.len(),
        named.len(),
        named.join("\n  ")
    );
    let n = failures.len();
    assert!(
        failures.is_empty(),
        "{n} programs differ:\n{}",
        failures.join("\n")
    );
}
