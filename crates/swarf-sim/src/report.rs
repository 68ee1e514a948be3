//! Reports of a verification: the JSON with every figure (worst gouges with their
//! program lines), and the CSV of flagged cells.
//!
//! A verification of several programs in sequence ([`crate::stage`]) numbers the
//! motions of all programs in one list; its reports name the program of every motion
//! they cite (a `program` field in the JSON's regions and notes, a `program` column in
//! the CSV, and the program list with each one's figures). The reports of a single
//! program have none of these.

use crate::dexel::NO_MOTION;
use crate::verify::Verification;
use serde_json::{Value, json};
use std::fmt::Write;

/// Most rows of the flagged-cell CSV (about 6 MB; the JSON keeps the full counts and
/// the regions, and both say when the CSV is cut).
pub const CSV_MAX_ROWS: usize = 100_000;

/// Cells flagged (gouge and excess) and the rows the CSV holds of them.
pub fn flagged_rows(v: &Verification) -> (usize, usize) {
    let s = &v.deviation.summary;
    let flagged = s.gouge.cells + s.excess.cells;
    (flagged, flagged.min(CSV_MAX_ROWS))
}
/// Motions below the floor named one by one in the text summary.
const FLOOR_NAMED: usize = 10;
/// Most warnings listed one by one in the JSON.
pub const JSON_MAX_WARNINGS: usize = 100;

/// What the report says about the inputs (the verifier does not know file names).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ReportContext {
    /// The design part (file or name).
    pub part: String,
    /// The program file.
    pub program: String,
    /// The tool as a spec string.
    pub tool: String,
    /// The stock, described.
    pub stock: String,
    /// Reader warnings, located (`file:line:column: message`).
    pub warnings: Vec<String>,
    /// Where reading stopped, if it did.
    pub stopped: Option<String>,
}

/// The full JSON report.
pub fn json_report(v: &Verification, ctx: &ReportContext) -> Value {
    let g = &v.grid;
    let warnings: Vec<&String> = ctx.warnings.iter().take(JSON_MAX_WARNINGS).collect();
    let mut report = json!({
        "swarf": env!("CARGO_PKG_VERSION"),
        "part": ctx.part,
        "program": ctx.program,
        "tool": ctx.tool,
        "stock": ctx.stock,
        "complete": ctx.stopped.is_none(),
        "stopped": ctx.stopped,
        "reader_warnings": ctx.warnings.len(),
        "reader_warning_list": warnings,
        "grid": {
            "origin_mm": g.origin,
            "cell_mm": g.cell,
            "nx": g.nx,
            "ny": g.ny,
            "cells": g.len(),
        },
        "sample_tolerance_mm": v.sample_tol,
        "deviation_mode": if v.along_normals { "normal" } else { "vertical" },
        "normal_fallback_cells": v.normal_fallback,
        "design_approximate_cells": v.design.approximate,
        "program_stats": v.program,
        "simulation": v.sim,
        "deviation": v.deviation.summary,
        "flagged_csv": {
            "flagged_cells": flagged_rows(v).0,
            "rows": flagged_rows(v).1,
            "cap_rows": CSV_MAX_ROWS,
        },
        "timings_s": v.timings,
    });
    if let Some(floor) = &v.floor {
        report["floor"] = json!(floor);
    }
    if v.stages.len() > 1 {
        name_programs(&mut report, v);
    }
    report
}

/// The floor check's lines of the text summary (none without a floor).
fn floor_lines(t: &mut String, v: &Verification) {
    let Some(f) = &v.floor else {
        return;
    };
    let _ = writeln!(
        t,
        "floor {:.4} mm: {} below it by more than {:.4} mm",
        f.floor,
        count(f.below.len(), "motion"),
        v.deviation.summary.tol
    );
    for n in f.below.iter().take(FLOOR_NAMED) {
        let _ = writeln!(
            t,
            "warning: motion at {} goes {:.4} mm below the floor",
            at_line(v, Some(n.motion), n.line),
            n.amount
        );
    }
    if f.below.len() > FLOOR_NAMED {
        let _ = writeln!(
            t,
            "warning: {} more motions below the floor (report.json lists them)",
            f.below.len() - FLOOR_NAMED
        );
    }
}

/// Adds the program list and the program of every cited motion to a report of
/// several programs.
fn name_programs(report: &mut Value, v: &Verification) {
    for (section, list) in [
        ("deviation", "gouges"),
        ("deviation", "excesses"),
        ("simulation", "rapid_cuts"),
        ("simulation", "outside"),
        ("floor", "below"),
    ] {
        let Some(items) = report[section][list].as_array_mut() else {
            continue;
        };
        for item in items {
            let stage = item["motion"]
                .as_u64()
                .and_then(|m| v.stage_of(usize::try_from(m).ok()?));
            if let (Some(stage), Some(fields)) = (stage, item.as_object_mut()) {
                fields.insert("program".into(), Value::from(stage.source.as_str()));
            }
        }
    }
    report["programs"] = json!(v.stages);
}

/// The flagged cells as CSV: `x,y,design_z,machined_z,deviation,kind,motion,line`
/// (and `program` after them for several programs), gouges then excess, in row-major
/// order, at most [`CSV_MAX_ROWS`] rows.
pub fn flagged_csv(v: &Verification) -> String {
    let s = &v.deviation.summary;
    let several = v.stages.len() > 1;
    let mut out = String::from("x,y,design_z,machined_z,deviation,kind,motion,line");
    out += if several { ",program\n" } else { "\n" };
    let mut rows = 0;
    for (kind, keep) in [("gouge", -1.0), ("excess", 1.0)] {
        for (k, &d) in v.deviation.values.iter().enumerate() {
            let flagged = if keep < 0.0 {
                d < -s.tol
            } else {
                d > s.allowed_excess + s.tol
            };
            if !flagged {
                continue;
            }
            if rows == CSV_MAX_ROWS {
                return out;
            }
            rows += 1;
            let [x, y] = v.grid.centre(k % v.grid.nx, k / v.grid.nx);
            let m = v.stock.last_motion()[k];
            let (motion, line) = if m == NO_MOTION {
                (String::new(), String::new())
            } else {
                let line = v
                    .lines
                    .get(m as usize)
                    .map_or(String::new(), |l| l.to_string());
                (m.to_string(), line)
            };
            let _ = write!(
                out,
                "{x:.4},{y:.4},{:.6},{:.6},{d:.6},{kind},{motion},{line}",
                v.design.heights[k],
                v.stock.heights()[k]
            );
            if several {
                let program = (m != NO_MOTION)
                    .then(|| v.stage_of(m as usize))
                    .flatten()
                    .map_or("", |s| s.source.as_str());
                let _ = write!(out, ",{}", csv_field(program));
            }
            out.push('\n');
        }
    }
    out
}

/// `text` as one CSV field: quoted (with its quotes doubled) when it holds a comma, a
/// quote or a line break (RFC 4180).
fn csv_field(text: &str) -> String {
    if text.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", text.replace('"', "\"\""))
    } else {
        text.to_string()
    }
}

/// A few lines for a terminal.
pub fn text_summary(v: &Verification, ctx: &ReportContext) -> String {
    let s = &v.deviation.summary;
    let mut t = program_lines(v, ctx);
    let _ = writeln!(
        t,
        "grid {} x {} cells of {} mm; {} cells measured",
        v.grid.nx, v.grid.ny, v.grid.cell, s.measured_cells
    );
    let worst = s
        .gouges
        .first()
        .map(|g| {
            let line = g
                .line
                .map_or(String::new(), |l| format!(" ({})", at_line(v, g.motion, l)));
            format!(
                ", deepest {:.4} mm at ({:.3}, {:.3}){line}",
                g.worst, g.at[0], g.at[1]
            )
        })
        .unwrap_or_default();
    let _ = writeln!(
        t,
        "gouge: {} in {}{worst}",
        count(s.gouge.cells, "cell"),
        count(s.gouge.regions, "region")
    );
    let _ = writeln!(
        t,
        "excess (> {:.4} mm): {} in {}, worst {:.4} mm",
        s.allowed_excess + s.tol,
        count(s.excess.cells, "cell"),
        count(s.excess.regions, "region"),
        s.excess.worst
    );
    if let (Some(lo), Some(hi), Some(max)) = (s.scallop.p05, s.scallop.p95, s.scallop.max) {
        let _ = writeln!(
            t,
            "scallop crests: {lo:.4} - {hi:.4} mm (p5 - p95), highest {max:.4} mm"
        );
    }
    let (flagged, rows) = flagged_rows(v);
    if rows < flagged {
        let _ = writeln!(
            t,
            "note: flagged.csv holds the first {rows} of {flagged} flagged cells (its cap, \
             gouges first); report.json lists the regions"
        );
    }
    for r in &v.sim.rapid_cuts {
        let _ = writeln!(
            t,
            "warning: rapid at {} cuts material ({:.4} mm deep)",
            at_line(v, Some(r.motion), r.line),
            r.amount
        );
    }
    floor_lines(&mut t, v);
    for o in &v.sim.outside {
        let _ = writeln!(
            t,
            "warning: move at {} lies {:.1} mm outside the stock",
            at_line(v, Some(o.motion), o.line),
            o.amount
        );
    }
    t
}

/// The program's figures (and each program's, when there are several).
fn program_lines(v: &Verification, ctx: &ReportContext) -> String {
    let p = &v.program;
    let mut t = format!(
        "{}: {} motions ({} passes), cutting {:.1} mm, rapid {:.1} mm, time {}\n",
        ctx.program,
        p.motions,
        p.passes,
        p.cutting_length_mm,
        p.rapid_length_mm,
        clock(p.time_s)
    );
    if v.stages.len() > 1 {
        for st in &v.stages {
            let p = &st.stats;
            let _ = writeln!(
                t,
                "  {} with {}: {} motions ({} passes), cutting {:.1} mm, time {}",
                st.source,
                st.tool,
                p.motions,
                p.passes,
                p.cutting_length_mm,
                clock(p.time_s)
            );
        }
    }
    t
}

/// `line N` of `motion`, with `of PROGRAM` when the verification ran several.
fn at_line(v: &Verification, motion: Option<usize>, line: usize) -> String {
    match motion.and_then(|m| v.stage_of(m)) {
        Some(stage) if v.stages.len() > 1 => format!("line {line} of {}", stage.source),
        _ => format!("line {line}"),
    }
}

/// `n` and `noun`, plural (`noun` + "s") unless `n` is 1: `1 region`, `3 regions`.
pub fn count(n: usize, noun: &str) -> String {
    if n == 1 {
        format!("1 {noun}")
    } else {
        format!("{n} {noun}s")
    }
}

/// Seconds as `1h02'03"` or `12'34"`.
pub fn clock(seconds: f64) -> String {
    let s = seconds.max(0.0).round() as u64;
    let (h, m, s) = (s / 3600, (s / 60) % 60, s % 60);
    if h > 0 {
        format!("{h}h{m:02}'{s:02}\"")
    } else {
        format!("{m}'{s:02}\"")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clock_formats() {
        assert_eq!(clock(1520.0), "25'20\"");
        assert_eq!(clock(3723.4), "1h02'03\"");
        assert_eq!(clock(-3.0), "0'00\"");
    }

    #[test]
    fn counts_agree_with_their_number() {
        assert_eq!(count(1, "region"), "1 region");
        assert_eq!(count(0, "region"), "0 regions");
        assert_eq!(count(37707, "cell"), "37707 cells");
    }
}
