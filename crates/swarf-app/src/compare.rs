//! The comparison (`swarf compare JOB...`): plan each job, verify the G-code it
//! wrote, and tabulate paper 004's Table 1 for the tool paths: machining time (from the program's feeds and
//! rapids), scallop height range, remaining-material points, gouge points, plus passes
//! and cutting length. Writes `compare.md`, `compare.json` and, per job, the plan, the
//! program, the verification report and pictures under `--out`.
//!
//! "Points" are grid cells: remaining material = cells more than the job's scallop
//! limit plus its tolerance above the design, gouge = cells more than the tolerance
//! below it (regions in brackets). The scallop range is the 5th to 95th percentile of
//! the scallop crest heights, with the highest crest after it. Deviations are measured
//! along the design normals by default (a scallop height is a distance normal to the
//! surface; vertically it reads `1 / cos(slope)` taller on the wave's flanks).
//!
//! Five-axis jobs (a `positioning` table) are verified through their APT CL, whose
//! poses are in the part frame (their G-code, written when the job names a machine,
//! holds machine axes). A tilted tool is traced cell by cell under its whole
//! footprint, so they default to cells of [`FIVE_AXIS_CELL`] mm and motions sampled
//! within [`FIVE_AXIS_SAMPLE_TOL`] mm (`--cell`, `--sample-tol` override both), and
//! they get a second table (`compare-5x.md`, [`five_axis_markdown`]): the lead angle
//! range, the least lead the design's curvature along the feed allows
//! ([`swarf_fiveaxis::lead_bound`]), the sectioning gouge report of the plan, the
//! dexel's gouges and scallops, and the planning time (thesis 000 ch. 8).

use crate::error::{Context, Result};
use crate::gate::Gate;
use crate::job::Job;
use crate::model::load_model_with;
use crate::outputs::Outputs;
use crate::plan_job::{part_arg, plan_model};
use crate::report::Reporter;
use crate::verify::{SimSettings, context, verify_and_write};
use serde::Serialize;
use std::fmt::Write;
use std::path::{Path, PathBuf};
use std::time::Instant;
use swarf_sim::report::{clock, count};
use swarf_sim::{Stage, Verification};

/// Default dexel cell for five-axis programs, mm.
pub const FIVE_AXIS_CELL: f64 = 0.5;
/// Default sampling bound of five-axis motions, mm.
pub const FIVE_AXIS_SAMPLE_TOL: f64 = 0.1;

/// One row of the table.
#[derive(Debug, Clone, Serialize)]
pub struct Row {
    /// Job name (or file stem).
    pub job: String,
    /// Strategy.
    pub strategy: String,
    /// Machining time from the program, s.
    pub time_s: f64,
    /// Scallop crest heights: 5th percentile, 95th percentile, highest, mm.
    pub scallop_mm: [Option<f64>; 3],
    /// Scallop height the strategy predicted, mm.
    pub predicted_scallop_mm: Option<f64>,
    /// Remaining-material points (cells).
    pub remaining_points: usize,
    /// Gouge points (cells).
    pub gouge_points: usize,
    /// Gouge regions.
    pub gouge_regions: usize,
    /// Deepest gouge, mm (0 when none).
    pub deepest_gouge_mm: f64,
    /// Passes.
    pub passes: usize,
    /// Cutting length, mm.
    pub cutting_length_mm: f64,
    /// Cell size used, mm.
    pub cell_mm: f64,
    /// The program stopped early (the row covers what was read).
    pub incomplete: bool,
}

/// One row of the five-axis table (thesis 000 ch. 8).
#[derive(Debug, Clone, Serialize)]
pub struct FiveAxisRow {
    /// Job name (or file stem).
    pub job: String,
    /// `inclined` or `gouge-free`.
    pub method: String,
    /// Smallest and largest lead angle, degrees.
    pub alpha_range_deg: [f64; 2],
    /// The least lead the design's curvature along the feed allows, degrees (`None`
    /// when the plan gives none: a cone, a side tilt).
    pub local_lead_bound_deg: Option<f64>,
    /// Where that bound is reached, mm.
    pub local_lead_bound_at: Option<[f64; 3]>,
    /// CC points where no lead fits the design's curvature.
    pub local_lead_unfit: usize,
    /// Poses.
    pub poses: usize,
    /// Poses the sectioning check finds gouging.
    pub gouging_poses: usize,
    /// Deepest point below the design by sectioning, mm (negative: clearance).
    pub sectioning_worst_mm: f64,
    /// Where the deepest gouging pose of the sectioning check is, mm.
    pub sectioning_at: Option<[f64; 3]>,
    /// Gouge cells of the dexel check.
    pub dexel_gouge_cells: usize,
    /// Gouge regions of the dexel check.
    pub dexel_gouge_regions: usize,
    /// Deepest gouge of the dexel check, mm below the design (0 when none).
    pub dexel_deepest_mm: f64,
    /// Scallop crests: highest and median, mm.
    pub scallop_mm: [Option<f64>; 2],
    /// Mean deviation over the measured cells, mm.
    pub mean_deviation_mm: Option<f64>,
    /// Passes.
    pub passes: usize,
    /// Cutting length, mm.
    pub cutting_length_mm: f64,
    /// Planning time (3-axis plan, positioning and outputs), s.
    pub planning_s: f64,
    /// Verification time, s.
    pub verify_s: f64,
    /// Cell size, mm.
    pub cell_mm: f64,
    /// Sampling bound of the motions, mm.
    pub sample_tol_mm: f64,
    /// The program stopped early.
    pub incomplete: bool,
}

/// What planning and verifying one job gave.
struct Checked {
    name: String,
    summary: serde_json::Value,
    v: Verification,
    incomplete: bool,
    planning_s: f64,
    verify_s: f64,
}

/// Plans, verifies and tabulates `jobs`, staging everything in `out` (committed by
/// the caller: the whole comparison is one set).
///
/// # Errors
/// A job that does not parse or plan, a program that cannot be read, a verification
/// that cannot run (grid too large, ...), or an output that cannot be written.
pub fn compare_jobs(
    jobs: &[PathBuf],
    sim: &SimSettings,
    out: &mut Outputs,
    reporter: &dyn Reporter,
) -> Result<Vec<Row>> {
    Ok(compare_all(jobs, sim, out, reporter)?.0)
}

/// [`compare_jobs`], with the five-axis rows of the jobs that have a positioning
/// (also written as `compare-5x.md` and `compare-5x.json` when there are any).
///
/// # Errors
/// As [`compare_jobs`].
pub fn compare_all(
    jobs: &[PathBuf],
    sim: &SimSettings,
    out: &mut Outputs,
    reporter: &dyn Reporter,
) -> Result<(Vec<Row>, Vec<FiveAxisRow>)> {
    compare_all_views(jobs, sim, out, reporter, false)
}

/// [`compare_all`], writing the 3D view of each verified program into
/// `{stem}.view/` when `views` is set ([`crate::view`]; `swarf demo`).
///
/// # Errors
/// As [`compare_jobs`]; a view that cannot be written.
pub fn compare_all_views(
    jobs: &[PathBuf],
    sim: &SimSettings,
    out: &mut Outputs,
    reporter: &dyn Reporter,
    views: bool,
) -> Result<(Vec<Row>, Vec<FiveAxisRow>)> {
    let (mut rows, mut five) = (Vec::new(), Vec::new());
    for (k, path) in jobs.iter().enumerate() {
        let name = path
            .file_name()
            .map_or_else(String::new, |n| n.to_string_lossy().into_owned());
        reporter.job(k, jobs.len(), &name);
        let c = check_one(path, sim, out, reporter, views)
            .with_context(|| format!("{}: planning and verifying the job", path.display()));
        if c.is_err() {
            reporter.jobs_done();
        }
        let c = c?;
        rows.push(row(&c));
        if let Some(f) = five_axis_row(&c) {
            five.push(f);
        }
    }
    reporter.jobs_done();
    out.write_json("compare.json", &rows)?;
    out.write("compare.md", markdown(&rows).as_bytes())?;
    if !five.is_empty() {
        out.write_json("compare-5x.json", &five)?;
        out.write("compare-5x.md", five_axis_markdown(&five).as_bytes())?;
    }
    Ok((rows, five))
}

/// Sets `job` up to be planned and then measured (by `swarf compare` and `swarf
/// view`): its program written as `STEM.ngc`, a five-axis one also as `STEM.cl`
/// (part-frame poses, so that the verifier needs no machine), its summary as
/// `STEM.plan.json`, nothing else; in mm; written even where the gate finds it
/// unsafe (its header says what the gate found: the measurement shows it). Returns
/// the program file to verify and whether the job is five-axis.
pub(crate) fn for_measurement(job: &mut Job, stem: &str) -> (String, bool) {
    job.gate = Gate::AllowUnsafe;
    let five = job.tilted();
    let program_file = format!("{stem}.{}", if five { "cl" } else { "ngc" });
    job.output.gcode = (!five || job.output.machine.is_some()).then(|| format!("{stem}.ngc"));
    job.output.cl = five.then(|| program_file.clone());
    job.output.summary = Some(format!("{stem}.plan.json"));
    job.output.csv = None;
    job.output.double_contacts = None;
    job.output.contacts = None;
    job.output.units = swarf_nc::Units::Mm;
    (program_file, five)
}

/// Plans the job at `path` into `out` and verifies its program (G-code; APT CL for a
/// five-axis job), writing the plan, the program, the report and the pictures.
fn check_one(
    path: &Path,
    sim: &SimSettings,
    out: &mut Outputs,
    reporter: &dyn Reporter,
    views: bool,
) -> Result<Checked> {
    let text = out
        .read_text(path)
        .with_context(|| format!("{}: cannot read the job file", path.display()))?;
    let mut job = Job::parse(&text, &path.display().to_string())?;
    let stem = path
        .file_stem()
        .map_or_else(|| "job".to_string(), |s| s.to_string_lossy().into_owned());
    let job_dir = path.parent().unwrap_or(Path::new("."));
    let (program_file, five) = for_measurement(&mut job, &stem);
    let part = part_arg(&job, job_dir);
    let start = Instant::now();
    let model = load_model_with(&part, &job.load_options())?;
    let summary = plan_model(&job, &model, job_dir, out, reporter)?;
    let planning_s = start.elapsed().as_secs_f64();
    let program = out.read_program(&program_file)?;
    let scallop = job.strategy.scallop().unwrap_or(0.0);
    let mut opts = sim.options(job.tolerance(), scallop, job.feeds.rapid, true)?;
    if opts.floor.is_none() {
        let [bottom, top] = model.z_range()?;
        opts.floor = Some(job.stock.floor(bottom, top)?);
    }
    if five {
        opts.cell = opts.cell.or(Some(FIVE_AXIS_CELL));
        opts.sample_tol = opts.sample_tol.or(Some(FIVE_AXIS_SAMPLE_TOL));
    }
    let stages = [Stage {
        program: &program,
        cutter: &job.tool,
    }];
    let ctx = context(&part, &stages, &opts);
    let start = Instant::now();
    let prefix = format!("{stem}.");
    let v = verify_and_write(&model, &stages, &opts, (out, &prefix), &ctx, reporter)?;
    if views {
        let input = crate::view::ViewInput {
            model: &model,
            tol: job.tolerance(),
            program: &program,
            cutter: &job.tool,
            verification: &v,
        };
        let opts = swarf_report::gltf::StockMeshOptions::default();
        crate::view::write_view(out, &format!("{stem}.view"), &input, &opts)?;
    }
    Ok(Checked {
        name: job.name.clone().unwrap_or(stem),
        summary,
        v,
        incomplete: ctx.stopped.is_some(),
        planning_s,
        verify_s: start.elapsed().as_secs_f64(),
    })
}

/// The Table 1 row of a checked job.
fn row(c: &Checked) -> Row {
    let (s, summary, v) = (&c.v.deviation.summary, &c.summary, &c.v);
    Row {
        job: c.name.clone(),
        strategy: summary["strategy"].as_str().unwrap_or("?").to_string(),
        time_s: v.program.time_s,
        scallop_mm: [s.scallop.p05, s.scallop.p95, s.scallop.max],
        predicted_scallop_mm: summary["report"]["predicted_max_scallop"].as_f64(),
        remaining_points: s.excess.cells,
        gouge_points: s.gouge.cells,
        gouge_regions: s.gouge.regions,
        deepest_gouge_mm: s.gouge.worst,
        passes: summary["passes"]
            .as_u64()
            .unwrap_or(v.program.passes as u64) as usize,
        cutting_length_mm: summary["cutting_length_mm"]
            .as_f64()
            .unwrap_or(v.program.cutting_length_mm),
        cell_mm: v.grid.cell,
        incomplete: c.incomplete,
    }
}

/// The five-axis row of a checked job; `None` without a positioning report.
fn five_axis_row(c: &Checked) -> Option<FiveAxisRow> {
    let p = c.summary.get("positioning")?;
    let s = &c.v.deviation.summary;
    let num = |v: &serde_json::Value| v.as_f64().unwrap_or(f64::NAN);
    let count = |v: &serde_json::Value| v.as_u64().unwrap_or(0) as usize;
    let point = |v: &serde_json::Value| v.as_array().map(|a| [0, 1, 2].map(|k| num(&a[k])));
    let at = point(&p["gouges"][0]["at"]);
    Some(FiveAxisRow {
        job: c.name.clone(),
        method: p["method"].as_str().unwrap_or("?").to_string(),
        alpha_range_deg: [num(&p["alpha_range_deg"][0]), num(&p["alpha_range_deg"][1])],
        local_lead_bound_deg: p["local_lead_bound_deg"].as_f64(),
        local_lead_bound_at: point(&p["local_lead_bound_at"]),
        local_lead_unfit: count(&p["local_lead_unfit"]),
        poses: count(&p["poses"]),
        gouging_poses: count(&p["gouging_poses"]),
        sectioning_worst_mm: num(&p["worst_depth"]),
        sectioning_at: at,
        dexel_gouge_cells: s.gouge.cells,
        dexel_gouge_regions: s.gouge.regions,
        dexel_deepest_mm: (-s.gouge.worst).max(0.0),
        scallop_mm: [s.scallop.max, s.scallop.p50],
        mean_deviation_mm: s.mean,
        passes: count(&c.summary["passes"]),
        cutting_length_mm: num(&c.summary["cutting_length_mm"]),
        planning_s: c.planning_s,
        verify_s: c.verify_s,
        cell_mm: c.v.grid.cell,
        sample_tol_mm: c.v.sample_tol,
        incomplete: c.incomplete,
    })
}

/// The five-axis table in Markdown.
pub fn five_axis_markdown(rows: &[FiveAxisRow]) -> String {
    let mut t = String::from(
        "| job | lead angle | least lead from curvature | gouging poses (sectioning) | deepest (sectioning) | gouge (dexel) | scallop max / median crest | mean deviation | passes | cutting length | planning |\n\
         |---|---|---|---|---|---|---|---|---|---|---|\n",
    );
    let mm = |v: Option<f64>| v.map_or("-".to_string(), |x| format!("{x:.3} mm"));
    for r in rows {
        let [lo, hi] = r.alpha_range_deg;
        let alpha = if (hi - lo).abs() < 1e-9 {
            format!("{lo:.2} deg")
        } else {
            format!("{lo:.2}-{hi:.2} deg")
        };
        let least = least_lead(r);
        let worst = match r.sectioning_at {
            Some([x, y, z]) if r.gouging_poses > 0 => format!(
                "{:.3} mm at ({x:.1}, {y:.1}, {z:.1})",
                r.sectioning_worst_mm
            ),
            _ => format!("{:.3} mm", r.sectioning_worst_mm),
        };
        let dexel = if r.dexel_gouge_cells == 0 {
            "none".to_string()
        } else {
            format!(
                "{:.3} mm, {} ({})",
                r.dexel_deepest_mm,
                count(r.dexel_gouge_cells, "cell"),
                count(r.dexel_gouge_regions, "region")
            )
        };
        let _ = writeln!(
            t,
            "| {}{} | {alpha} | {least} | {} of {} | {worst} | {dexel} | {} / {} | {} | {} | {:.0} mm | {:.1} s |",
            r.job,
            if r.incomplete { " (incomplete)" } else { "" },
            r.gouging_poses,
            r.poses,
            mm(r.scallop_mm[0]),
            mm(r.scallop_mm[1]),
            mm(r.mean_deviation_mm),
            r.passes,
            r.cutting_length_mm,
            r.planning_s
        );
    }
    if let Some(r) = rows.first() {
        let _ = writeln!(
            t,
            "\nleast lead from curvature: the largest over the CC points of asin(R / (rho - r)), \
             rho the design's concave radius of curvature along the feed, R the tool's axis to \
             insert centre, r its insert radius: with less lead the back of the tool enters the \
             design there, whatever the positioning.\n\
             sectioning: the plan's gouge check (depth below the design, negative: clearance); \
             dexel: cells of {} mm, motions sampled within {} mm, deviation along the design normals",
            r.cell_mm, r.sample_tol_mm
        );
    }
    t
}

/// The least-lead cell of a five-axis row.
fn least_lead(r: &FiveAxisRow) -> String {
    match (r.local_lead_bound_deg, r.local_lead_bound_at) {
        (Some(_), _) if r.local_lead_unfit > 0 => format!(
            "none: the tool does not fit the curvature at {} CC points",
            r.local_lead_unfit
        ),
        (Some(d), Some([x, y, _])) => format!("{d:.2} deg at ({x:.1}, {y:.1})"),
        (Some(d), None) => format!("{d:.2} deg"),
        (None, _) => "-".to_string(),
    }
}

/// The table in Markdown.
pub fn markdown(rows: &[Row]) -> String {
    let mut t = String::from(
        "| job | strategy | machining time | scallop height (p5-p95, max) | remaining material | tool gouge | passes | cutting length |\n\
         |---|---|---|---|---|---|---|---|\n",
    );
    for r in rows {
        let scallop = match r.scallop_mm {
            [Some(a), Some(b), Some(m)] => format!("{a:.3}-{b:.3} mm ({m:.3})"),
            _ => "none".into(),
        };
        let _ = writeln!(
            t,
            "| {} | {} | {}{} | {} | {} points | {} points ({}) | {} | {:.0} mm |",
            r.job,
            r.strategy,
            clock(r.time_s),
            if r.incomplete { " (incomplete)" } else { "" },
            scallop,
            r.remaining_points,
            r.gouge_points,
            count(r.gouge_regions, "region"),
            r.passes,
            r.cutting_length_mm
        );
    }
    if let Some(cell) = rows.first().map(|r| r.cell_mm) {
        let _ = writeln!(t, "\npoints are grid cells of {cell} mm");
    }
    t
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn markdown_rows() {
        let row = Row {
            job: "wave, iso-scallop".into(),
            strategy: "iso-scallop".into(),
            time_s: 1463.0,
            scallop_mm: [Some(0.131), Some(0.149), Some(0.152)],
            predicted_scallop_mm: Some(0.15),
            remaining_points: 21,
            gouge_points: 0,
            gouge_regions: 0,
            deepest_gouge_mm: 0.0,
            passes: 48,
            cutting_length_mm: 9876.4,
            cell_mm: 0.05,
            incomplete: false,
        };
        let t = markdown(&[row]);
        assert!(t.contains("| wave, iso-scallop | iso-scallop | 24'23\" | 0.131-0.149 mm (0.152) | 21 points | 0 points (0 regions) | 48 | 9876 mm |"), "{t}");
    }

    #[test]
    fn five_axis_markdown_rows() {
        let row = FiveAxisRow {
            job: "die, inclined tool, alpha = 3".into(),
            method: "inclined".into(),
            alpha_range_deg: [3.0, 3.0],
            local_lead_bound_deg: Some(12.951),
            local_lead_bound_at: Some([-4.9, -74.76, 28.14]),
            local_lead_unfit: 0,
            poses: 1498,
            gouging_poses: 1386,
            sectioning_worst_mm: 6.2349,
            sectioning_at: Some([-12.51, -99.65, 37.84]),
            dexel_gouge_cells: 38934,
            dexel_gouge_regions: 1,
            dexel_deepest_mm: 4.62,
            scallop_mm: [None, None],
            mean_deviation_mm: Some(-3.2012),
            passes: 39,
            cutting_length_mm: 3062.9,
            planning_s: 1.14,
            verify_s: 10.8,
            cell_mm: 0.5,
            sample_tol_mm: 0.1,
            incomplete: false,
        };
        let auto = FiveAxisRow {
            job: "die, automatic".into(),
            method: "gouge-free".into(),
            alpha_range_deg: [0.056, 14.858],
            gouging_poses: 0,
            sectioning_worst_mm: 0.009,
            dexel_gouge_cells: 0,
            scallop_mm: [Some(0.074), Some(0.014)],
            ..row.clone()
        };
        let cone = FiveAxisRow {
            job: "cone".into(),
            local_lead_bound_deg: None,
            ..row.clone()
        };
        let tight = FiveAxisRow {
            job: "tight".into(),
            local_lead_bound_deg: Some(90.0),
            local_lead_unfit: 12,
            ..row.clone()
        };
        let t = five_axis_markdown(&[row, auto, cone, tight]);
        assert!(t.contains("| cone | 3.00 deg | - | 1386 of 1498 |"), "{t}");
        assert!(
            t.contains(
                "| tight | 3.00 deg | none: the tool does not fit the curvature at 12 CC points |"
            ),
            "{t}"
        );
        assert!(
            t.contains(
                "least lead from curvature: the largest over the CC points of asin(R / (rho - r))"
            ),
            "{t}"
        );
        assert!(t.contains("| die, inclined tool, alpha = 3 | 3.00 deg | 12.95 deg at (-4.9, -74.8) | 1386 of 1498 | 6.235 mm at (-12.5, -99.7, 37.8) | 4.620 mm, 38934 cells (1 region) | - / - | -3.201 mm | 39 | 3063 mm | 1.1 s |"), "{t}");
        assert!(t.contains("| die, automatic | 0.06-14.86 deg | 12.95 deg at (-4.9, -74.8) | 0 of 1498 | 0.009 mm | none | 0.074 mm / 0.014 mm |"), "{t}");
        assert!(
            t.contains("cells of 0.5 mm, motions sampled within 0.1 mm"),
            "{t}"
        );
    }

    /// Paper 004's comparison on wave.toml, once the iso-strategy jobs exist
    /// (`jobs/wave-iso-*.toml` at the repository root): every strategy's scallop is at
    /// most h + tol, none gouges, iso-scallop's range is the narrowest, and the measured
    /// scallop agrees with the planner's prediction within the cell size.
    #[test]
    fn wave_compare_table_when_jobs_exist() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
        let mut jobs: Vec<PathBuf> = std::fs::read_dir(root.join("jobs"))
            .map(|d| d.filter_map(|e| e.ok().map(|e| e.path())).collect())
            .unwrap_or_default();
        jobs.retain(|p| {
            p.file_name()
                .and_then(|n| n.to_str())
                .is_some_and(|n| n.starts_with("wave-iso-") && n.ends_with(".toml"))
        });
        jobs.sort();
        if jobs.is_empty() {
            eprintln!("no jobs/wave-iso-*.toml yet: the wave compare table is not checked");
            return;
        }
        let out = std::env::temp_dir().join(format!("swarf-compare-test-{}", std::process::id()));
        let sim = SimSettings::normal_with_cell(0.1);
        let mut set = Outputs::new(&out);
        let rows = compare_jobs(&jobs, &sim, &mut set, &swarf_sim::Quiet).unwrap();
        set.commit().unwrap();
        let h = 0.15;
        for r in &rows {
            let max = r.scallop_mm[2].unwrap_or(0.0);
            assert!(max <= h + 0.01 + r.cell_mm, "{}: scallop {max}", r.job);
            assert_eq!(r.gouge_points, 0, "{} gouges", r.job);
            if let (Some(p), true) = (r.predicted_scallop_mm, r.strategy == "iso-scallop") {
                assert!(
                    (max - p).abs() <= r.cell_mm,
                    "{}: measured {max} vs predicted {p}",
                    r.job
                );
            }
        }
        let width = |r: &Row| match r.scallop_mm {
            [Some(a), Some(b), _] => b - a,
            _ => f64::INFINITY,
        };
        if let Some(iso) = rows.iter().find(|r| r.strategy == "iso-scallop") {
            assert!(rows.iter().all(|r| width(iso) <= width(r)), "{rows:?}");
        }
        let _ = std::fs::remove_dir_all(&out);
    }
}
