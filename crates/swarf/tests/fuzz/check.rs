//! What a run must do whatever its input: end by itself within the time limit, not be
//! killed by a signal (an abort, an allocation failure under the memory cap, a stack
//! overflow), not panic (exit status 101), write only finite numbers (no `inf`,
//! `NaN`, and no JSON `null` where a number belongs), and, when it fails, say where:
//! its standard error names the mutated file or the option.

use crate::exec::{Case, Outcome};
use serde_json::Value;
use std::os::unix::process::ExitStatusExt;

/// A broken promise: `symptom` groups failures (no case-specific numbers in it),
/// `detail` shows this one.
#[derive(Debug, Clone)]
pub struct Failure {
    /// What went wrong, the same for every case that shows the same defect.
    pub symptom: String,
    /// The evidence from this case.
    pub detail: String,
}

/// JSON keys whose value may be `null` by design, as a path suffix (`parent.key`;
/// `[]` for an array element), with the sibling that must then be 0 (a statistic of
/// an empty set), if any: a job without a name, an absent line number, a stop that
/// did not happen, a figure that does not apply. A `null` anywhere else is a number that was not
/// finite (serde_json writes NaN and infinities as `null`).
const NULL_OK: &[(&str, Option<&str>)] = &[
    ("job", None),
    ("line", None),
    ("motion", None),
    ("stopped", None),
    ("predicted_max_scallop", None),
    ("predicted_scallop_mm", None),
    ("side_step_range", None),
    ("level_step", None),
    ("sectioning_at", None),
    ("local_lead_bound_deg", None),
    ("local_lead_bound_at", None),
    ("local_lead_bound_radius", None),
    ("mean_deviation_mm", None),
    ("scallop_mm.[]", None),
    ("spin_plus", None),
    ("spin_minus", None),
    ("k1", None),
    ("k2", None),
    ("dir1", None),
    ("dir2", None),
    ("scallop.min", Some("crests")),
    ("scallop.p05", Some("crests")),
    ("scallop.p50", Some("crests")),
    ("scallop.p95", Some("crests")),
    ("scallop.max", Some("crests")),
    ("deviation.min", Some("measured_cells")),
    ("deviation.max", Some("measured_cells")),
    ("deviation.mean", Some("measured_cells")),
];

/// JSON string fields (or arrays of strings) that repeat user text (names, paths,
/// specs, messages quoting the input): words like `nan` in them are the user's, not
/// numbers swarf computed.
const ECHO_KEYS: &[&str] = &[
    "job",
    "name",
    "part",
    "program",
    "source",
    "tool",
    "stock",
    "machine",
    "file",
    "stopped",
    "message",
    "messages",
    "warning",
    "warnings",
    "reader_warning_list",
    "notes",
    "error",
];

/// Judges one run of `case`.
pub fn judge(case: &Case, o: &Outcome, timeout_s: u64) -> Option<Failure> {
    let stderr = String::from_utf8_lossy(&o.stderr);
    let fail = |symptom: String| {
        Some(Failure {
            symptom,
            detail: tail(&stderr, 1200),
        })
    };
    let Some(status) = o.status else {
        return fail(format!("did not finish within {timeout_s} s"));
    };
    if let Some(sig) = status.signal() {
        let why = if stderr.contains("memory allocation of") {
            ": memory allocation failed (over the memory cap)"
        } else if stderr.contains("overflowed its stack") {
            ": stack overflow"
        } else {
            ""
        };
        return fail(format!("killed by signal {sig}{why}"));
    }
    let code = status.code().unwrap_or(-1);
    if code == 101 {
        return fail(format!("panic {}", panic_place(&stderr)));
    }
    if !matches!(code, 0..=2) {
        return fail(format!("exit status {code}"));
    }
    if let Some(f) = nonfinite_outputs(o) {
        return Some(f);
    }
    if code != 0 && !case.places.iter().any(|p| stderr.contains(p.as_str())) {
        return Some(Failure {
            symptom: format!("error names no place: {}", normalise(first_line(&stderr))),
            detail: format!(
                "expected one of: {}\n{}",
                case.places.join(", "),
                tail(&stderr, 1200)
            ),
        });
    }
    None
}

/// Where a panic happened: the first frame of the backtrace in the workspace's
/// crates (`crates/NAME/src/FILE.rs:LINE`), else the panic's own place, and its
/// message.
fn panic_place(stderr: &str) -> String {
    let Some(at) = stderr.find("panicked at ") else {
        return "(no message)".into();
    };
    let rest = &stderr[at + "panicked at ".len()..];
    let own = rest
        .split([':', '\n'])
        .take(2)
        .collect::<Vec<_>>()
        .join(":");
    let msg = rest.lines().nth(1).unwrap_or("");
    let frame = rest
        .lines()
        .filter_map(|l| l.trim().strip_prefix("at "))
        .find_map(|l| l.find("crates/").map(|i| &l[i..]));
    let place = frame.map_or(own, |f| f.rsplitn(2, ':').last().unwrap_or(f).to_string());
    format!("at {place}: {}", normalise(msg))
}

/// The error line of `s` (the first that says `error`), else its first line.
fn first_line(s: &str) -> &str {
    s.lines()
        .find(|l| l.contains("error"))
        .or_else(|| s.lines().find(|l| !l.trim().is_empty()))
        .unwrap_or("")
}

/// `s` with numbers (`inf` and `NaN` too) and quoted text made generic and cut to 100
/// characters, so that messages of one defect group together.
pub fn normalise(s: &str) -> String {
    let s = s
        .replace("-inf", "#")
        .replace("inf", "#")
        .replace("NaN", "#");
    let mut out = String::new();
    let mut quoted: Option<char> = None;
    for c in s.chars() {
        match quoted {
            Some(q) if c == q => {
                quoted = None;
                out.push(c);
            }
            Some(_) => {}
            None if c == '"' || c == '`' => {
                quoted = Some(c);
                out += &format!("{c}…");
            }
            None if c.is_ascii_digit() => {
                if !out.ends_with('#') {
                    out.push('#');
                }
            }
            None => out.push(c),
        }
    }
    out.chars().take(100).collect()
}

/// The first `n` bytes of `s`, at a character boundary.
pub fn head(s: &str, n: usize) -> String {
    let mut end = n.min(s.len());
    while !s.is_char_boundary(end) {
        end -= 1;
    }
    s[..end].to_string()
}

/// The last `n` bytes of `s`, at a character boundary.
pub fn tail(s: &str, n: usize) -> String {
    let mut start = s.len().saturating_sub(n);
    while !s.is_char_boundary(start) {
        start += 1;
    }
    s[start..].to_string()
}

/// The first output (stdout or a file) holding a number that is not finite.
fn nonfinite_outputs(o: &Outcome) -> Option<Failure> {
    let streams = std::iter::once(("stdout".to_string(), &o.stdout))
        .chain(o.outputs.iter().map(|(n, b)| (n.clone(), b)));
    for (name, bytes) in streams {
        if let Some(what) = scan(&name, bytes) {
            let kind = name.rsplit('.').next().filter(|e| e.len() < 5);
            return Some(Failure {
                symptom: format!(
                    "non-finite number in {}: {}",
                    kind.map_or(name.clone(), |e| format!(".{e} output")),
                    what.0
                ),
                detail: format!("{name}: {}", what.1),
            });
        }
    }
    None
}

/// What is wrong with output `name`, if anything: (generic, specific).
pub fn scan(name: &str, bytes: &[u8]) -> Option<(String, String)> {
    let ext = name.rsplit('.').next().unwrap_or("");
    match ext {
        "png" => (!bytes.starts_with(b"\x89PNG"))
            .then(|| ("not a PNG".to_string(), format!("{} bytes", bytes.len()))),
        "stl" => scan_stl(bytes),
        _ => {
            let text = String::from_utf8_lossy(bytes);
            let trimmed = text.trim_start();
            if ext == "json" || trimmed.starts_with('{') || trimmed.starts_with('[') {
                match serde_json::from_str::<Value>(&text) {
                    Ok(v) => return scan_json(&v, &mut Vec::new()),
                    Err(e) if ext == "json" => {
                        return Some(("invalid JSON".into(), e.to_string()));
                    }
                    Err(_) => {}
                }
            }
            scan_text(&strip_comments(&text, ext))
        }
    }
}

/// A binary STL's triangle count must match its length and every float be finite.
fn scan_stl(b: &[u8]) -> Option<(String, String)> {
    if b.len() < 84 {
        return Some(("short STL".into(), format!("{} bytes", b.len())));
    }
    let n = u32::from_le_bytes(b[80..84].try_into().unwrap()) as usize;
    if b.len() != 84 + 50 * n {
        let d = format!("{n} triangles in {} bytes", b.len());
        return Some(("STL length".into(), d));
    }
    for (t, tri) in b[84..].chunks(50).enumerate() {
        for f in tri[..48].chunks(4) {
            let x = f32::from_le_bytes(f.try_into().unwrap());
            if !x.is_finite() {
                return Some(("STL float".into(), format!("triangle {t}: {x}")));
            }
        }
    }
    None
}

fn path_text(path: &[String]) -> String {
    path.join(".")
}

/// Whether a `null` at `path` (in object `parent`, when it is in one) is by design.
fn null_ok(path: &str, parent: Option<&serde_json::Map<String, Value>>) -> bool {
    NULL_OK.iter().any(|(suffix, zero)| {
        let at = path == *suffix || path.ends_with(&format!(".{suffix}"));
        let empty = zero.is_none_or(|z| {
            parent
                .and_then(|m| m.get(z))
                .and_then(Value::as_u64)
                .is_some_and(|n| n == 0)
        });
        at && empty
    })
}

/// A `null` that [`null_ok`] does not allow, or a word `nan`/`inf` in a string
/// outside [`ECHO_KEYS`].
fn scan_json(v: &Value, path: &mut Vec<String>) -> Option<(String, String)> {
    scan_json_in(v, path, None)
}

fn scan_json_in(
    v: &Value,
    path: &mut Vec<String>,
    parent: Option<&serde_json::Map<String, Value>>,
) -> Option<(String, String)> {
    match v {
        Value::Null => {
            let p = path_text(path);
            (!null_ok(&p, parent)).then(|| (format!("JSON null at {p}"), p.clone()))
        }
        Value::String(s) => {
            let key = path
                .iter()
                .rev()
                .find(|k| *k != "[]")
                .map_or("", String::as_str);
            if ECHO_KEYS.contains(&key) {
                return None;
            }
            scan_text(s).map(|(g, d)| (format!("{g} in JSON {}", path_text(path)), d))
        }
        Value::Array(items) => items.iter().find_map(|x| {
            path.push("[]".into());
            let r = scan_json_in(x, path, None);
            path.pop();
            r
        }),
        Value::Object(map) => map.iter().find_map(|(k, x)| {
            path.push(k.clone());
            let r = scan_json_in(x, path, Some(map));
            path.pop();
            r
        }),
        _ => None,
    }
}

/// `text` without the comments of its format: `( ... )` and `; ...` in G-code,
/// `PARTNO` and `$$` lines in APT CL; user text lives there.
fn strip_comments(text: &str, ext: &str) -> String {
    match ext {
        "ngc" | "nc" | "tap" | "gcode" => {
            let mut out = String::with_capacity(text.len());
            for line in text.lines() {
                let mut depth = 0;
                for c in line.split(';').next().unwrap_or("").chars() {
                    match c {
                        '(' => depth += 1,
                        ')' if depth > 0 => depth -= 1,
                        _ if depth == 0 => out.push(c),
                        _ => {}
                    }
                }
                out.push('\n');
            }
            out
        }
        "cl" | "apt" | "cls" => text
            .lines()
            .filter(|l| !l.starts_with("PARTNO") && !l.contains("$$"))
            .collect::<Vec<_>>()
            .join("\n"),
        _ => text.to_string(),
    }
}

/// The first word that spells a non-finite number: `inf`, `infinity`, `nan` in any
/// case, alone or after one address letter (`XNaN`, `Z-inf`).
pub fn scan_text(text: &str) -> Option<(String, String)> {
    let bad = |w: &str| matches!(w.to_ascii_lowercase().as_str(), "inf" | "infinity" | "nan");
    for (lineno, line) in text.lines().enumerate() {
        for word in line.split(|c: char| !c.is_ascii_alphabetic()) {
            let lettered = word.len() > 3
                && word.starts_with(|c: char| c.is_ascii_uppercase())
                && bad(&word[1..]);
            if bad(word) || lettered {
                let shown: String = line.chars().take(160).collect();
                return Some((format!("`{word}`"), format!("line {}: {shown}", lineno + 1)));
            }
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn non_finite_words_and_nulls_are_found() {
        assert!(scan_text("G1 X1.5 Y2 Z-inf").is_some());
        assert!(scan_text("G1 XNaN Y2").is_some());
        assert!(scan_text("max 1e308, infinite loop, nano, info").is_none());
        assert!(scan("a.ngc", b"(part nan)\nG1 X1\n").is_none());
        assert!(scan("a.ngc", b"G1 X1 Ynan\n").is_some());
        let json = br#"{"line": null, "deviation": {"max": null}, "job": "nan"}"#;
        let (what, _) = scan("r.json", json).unwrap();
        assert_eq!(what, "JSON null at deviation.max");
        let empty = br#"{"scallop": {"crests": 0, "max": null}, "line": null}"#;
        assert!(scan("r.json", empty).is_none());
        let nan = br#"{"scallop": {"crests": 3, "max": null}}"#;
        assert!(scan("r.json", nan).is_some());
        assert!(scan("x.png", b"\x89PNG...").is_none());
    }

    #[test]
    fn messages_group_without_their_numbers() {
        assert_eq!(
            normalise("p.toml: line 12: value \"1e308\" is too large (max 1000)"),
            "p.toml: line #: value \"…\" is too large (max #)"
        );
    }
}
