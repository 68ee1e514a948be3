//! Rest material and cleanup jobs (thesis 002 §4.4): a cleanup job names its parent
//! (a finishing job, or the tool that finished) and cleans up what it left, with
//! one tool or a chain of them.
//!
//! ```toml
//! name = "pocket cleanup"
//! part = "builtin:fillet-pocket"
//! tool = "ball:d=4"               # the (last) cleanup tool
//!
//! [parent]
//! job = "pocket-finish.toml"      # or: tool = "ball:d=12" (a reference tool)
//!
//! [strategy]
//! kind = "cleanup"
//! pattern = "follow-pocket"       # or "flow-cut" (pencil), with `passes` per side
//! source = "reference"            # "contacts" (a raster parent) or "stock"
//! scallop = 0.01                  # scallop height of the cleanup passes, mm
//! merge = 2                       # region boundary operations, mm (min_area mm²)
//! overlap = 1
//! min_area = 0.5
//! smoothness = 0.5
//! chain = ["ball:d=6"]            # intermediate tools: 12 -> 6 -> 4
//! ```
//!
//! The first stage finds the rest from the chosen source; every later stage of a
//! chain uses the previous stage's tool as its reference (crease scans). The last
//! stage's program goes to the job's outputs; an intermediate stage `k` (from 1)
//! writes the same files with `.k` before the extension.

use crate::error::{AppError, Context, Result, bail};
use crate::job::{Job, RestSource};
use crate::model::Model;
use crate::plan::{PlanInput, plan};
use std::borrow::Cow;
use std::path::{Path, PathBuf};
use swarf_geom::TriMesh;
use swarf_path::{Plan, PlanReport, StrategyKind};
use swarf_rest::{CleanupParams, Detection, RegionParams, Source, detect, plan_cleanup};
use swarf_sim::{Design, Quiet, StockSpec, VerifyOptions};
use swarf_tool::Cutter;

/// One stage of a cleanup: its tool, what it was asked to clean up, its plan.
#[derive(Debug)]
pub struct CleanupStage {
    /// The cleanup tool.
    pub tool: Cutter,
    /// The tool whose rest it cleans up.
    pub reference: Cutter,
    /// Where the rest came from (`reference`, `contacts`, `stock`).
    pub source: &'static str,
    /// The rest regions.
    pub detection: Detection,
    /// The cleanup tool path.
    pub plan: Plan,
}

/// The part as a mesh: a mesh part as it is, patches tessellated within a tenth of
/// `tol`.
///
/// # Errors
/// A tessellation that fails.
pub fn part_mesh(model: &Model, tol: f64) -> Result<Cow<'_, TriMesh>> {
    Ok(match model {
        Model::Mesh { mesh, .. } => Cow::Borrowed(mesh),
        Model::Patches(part) => Cow::Owned(part.tessellate(0.1 * tol)?),
    })
}

/// Reads the parent job `rel` (relative to `job_dir`).
///
/// # Errors
/// A file that cannot be read or parsed; a parent that is itself a cleanup.
pub fn read_parent(rel: &str, job_dir: &Path) -> Result<(Job, PathBuf)> {
    let path = job_dir.join(rel);
    let text = std::fs::read_to_string(&path)
        .with_context(|| format!("parent.job: {}: cannot read the parent job", path.display()))?;
    let parent = Job::parse(&text, &path.display().to_string())?;
    if parent.strategy.kind == StrategyKind::Cleanup {
        bail!(
            "parent.job: {}: the parent is a cleanup job; name the finishing job it cleans up after (or list the tools in strategy.chain)",
            path.display()
        );
    }
    let dir = path.parent().map_or_else(PathBuf::new, Path::to_path_buf);
    Ok((parent, dir))
}

/// The rest `parent` leaves on `mesh` (the tessellation of `model`) from `source`,
/// with the machining tolerance `tol` and region parameters `params`.
///
/// # Errors
/// A parent that cannot be planned or verified; `contacts` from a parent that is not
/// a raster; the detection's errors.
pub fn detect_after(
    parent: &Job,
    model: &Model,
    mesh: &TriMesh,
    source: RestSource,
    (tol, params): (f64, &RegionParams),
) -> Result<Detection> {
    let parent_plan = |input| {
        plan(parent, input)
            .map_err(|e| AppError::Message(format!("parent.job: the parent job fails: {e}")))
    };
    Ok(match source {
        RestSource::Reference => detect(mesh, &parent.tool, Source::Reference, tol, params)?,
        RestSource::Contacts => {
            if parent.strategy.kind != StrategyKind::Raster {
                bail!(
                    "strategy.source: \"contacts\" needs a raster parent (the {:?} strategy records no double contacts); use source = \"reference\"",
                    parent.strategy.kind
                );
            }
            let p = parent_plan(PlanInput::Mesh(mesh))?;
            detect(
                mesh,
                &parent.tool,
                Source::Contacts(&p.double_contacts),
                tol,
                params,
            )?
        }
        RestSource::Stock => {
            let p = parent_plan(match model {
                Model::Patches(part) => PlanInput::Part(part),
                Model::Mesh { mesh, .. } => PlanInput::Mesh(mesh),
            })?;
            let v = simulate_parent(parent, &p, mesh, tol)?;
            let source = Source::Stock {
                grid: &v.grid,
                excess: &v.deviation.values,
                design: &v.design.heights,
            };
            detect(mesh, &parent.tool, source, tol, params)?
        }
    })
}

/// The parent's program cut from a block (the design's box) and compared with the
/// design: the in-process model after it.
fn simulate_parent(
    parent: &Job,
    p: &Plan,
    mesh: &TriMesh,
    tol: f64,
) -> Result<swarf_sim::Verification> {
    let moves = p.toolpath.moves();
    let text = swarf_nc::write_gcode(&moves, &parent.feeds, &swarf_nc::GcodeOptions::default())?;
    let opts = swarf_nc::read::GcodeReadOptions::default();
    let program = swarf_nc::read::parse_gcode(&text, "parent program", &opts)?;
    let vopts = VerifyOptions {
        tol,
        stock: StockSpec::Box { top: None },
        ..VerifyOptions::default()
    };
    Ok(swarf_sim::verify(
        Design::Mesh(mesh),
        &program,
        &parent.tool,
        &vopts,
        &Quiet,
    )?)
}

/// Plans the cleanup job `job` (module doc) on `model`.
///
/// # Errors
/// A parent that cannot be read, planned or verified; a tool larger than the tool
/// before it; the detection's and the planning's errors.
pub fn plan_cleanup_job(job: &Job, model: &Model, job_dir: &Path) -> Result<Vec<CleanupStage>> {
    let Some(parent_spec) = &job.parent else {
        bail!("parent: a cleanup job needs a [parent] table");
    };
    let mesh = part_mesh(model, job.strategy.tolerance)?;
    let parent = match (&parent_spec.job, parent_spec.tool) {
        (Some(rel), _) => Some(read_parent(rel, job_dir)?.0),
        (None, _) => None,
    };
    let mut reference = parent
        .as_ref()
        .map(|p| p.tool)
        .or(parent_spec.tool)
        .with_context(|| "parent: expected `job` or `tool`".into())?;
    let tools: Vec<Cutter> = job
        .strategy
        .chain
        .iter()
        .copied()
        .chain([job.tool])
        .collect();
    let mut stages = Vec::with_capacity(tools.len());
    for (k, tool) in tools.into_iter().enumerate() {
        let start = std::time::Instant::now();
        let (detection, source) = match (&parent, k) {
            (Some(p), 0) => {
                let settings = (job.strategy.tolerance, &job.region_params());
                let d = detect_after(p, model, &mesh, job.strategy.source, settings)?;
                (d, source_name(job.strategy.source))
            }
            _ => (
                detect(
                    &mesh,
                    &reference,
                    Source::Reference,
                    job.strategy.tolerance,
                    &job.region_params(),
                )?,
                "reference",
            ),
        };
        let params = CleanupParams {
            finish: swarf_path::Finish {
                tool,
                ..job.finish()
            },
            pattern: job.strategy.pattern,
            passes: job.strategy.passes,
            scallop: job.strategy.scallop.unwrap_or(job.strategy.tolerance),
        };
        let toolpath =
            plan_cleanup(&mesh, &detection.regions, &reference, &params).map_err(|e| {
                AppError::Message(format!("stage {} ({tool} after {reference}): {e}", k + 1))
            })?;
        let report = PlanReport {
            elapsed_s: start.elapsed().as_secs_f64(),
            ..PlanReport::default()
        };
        stages.push(CleanupStage {
            tool,
            reference,
            source,
            detection,
            plan: Plan {
                toolpath,
                report,
                double_contacts: Vec::new(),
            },
        });
        reference = tool;
    }
    Ok(stages)
}

/// The name of a rest source in reports.
pub fn source_name(s: RestSource) -> &'static str {
    match s {
        RestSource::Reference => "reference",
        RestSource::Contacts => "contacts",
        RestSource::Stock => "stock",
    }
}

/// `file` with `.k` before its extension (`pocket.ngc` -> `pocket.1.ngc`).
pub fn stage_file(file: &str, k: usize) -> String {
    let p = Path::new(file);
    match (p.file_stem(), p.extension()) {
        (Some(stem), Some(ext)) => p
            .with_file_name(format!(
                "{}.{k}.{}",
                stem.to_string_lossy(),
                ext.to_string_lossy()
            ))
            .display()
            .to_string(),
        _ => format!("{file}.{k}"),
    }
}

/// The regions of a detection as JSON: per region its kinds, areas, depth, where the
/// depth is, samples, and the boundary's outer ring.
pub fn rest_json(d: &Detection) -> serde_json::Value {
    let regions: Vec<serde_json::Value> = d
        .regions
        .iter()
        .enumerate()
        .map(|(k, r)| {
            serde_json::json!({
                "region": k + 1,
                "kinds": r.kinds,
                "area_mm2": r.area,
                "raw_area_mm2": r.raw_area,
                "depth_mm": r.depth,
                "deepest": [r.deepest.x, r.deepest.y, r.deepest.z],
                "samples": r.pairs.len(),
                "boundary_points": r.boundary.exterior().0.len(),
            })
        })
        .collect();
    serde_json::json!({
        "regions": regions,
        "samples": d.samples,
        "directory_pitch_mm": d.pitch,
    })
}

/// Every region's boundary as CSV: `region,ring,x,y` (ring 0 the outer boundary,
/// then the holes), each ring closed.
pub fn boundaries_csv(d: &Detection) -> String {
    let mut s = String::from("region,ring,x,y\n");
    for (k, r) in d.regions.iter().enumerate() {
        let rings = std::iter::once(r.boundary.exterior()).chain(r.boundary.interiors());
        for (j, ring) in rings.enumerate() {
            for c in ring.coords() {
                s += &format!("{},{j},{:.6},{:.6}\n", k + 1, c.x, c.y);
            }
        }
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::load_model;

    fn job(text: &str) -> Result<Job> {
        Job::parse(text, "test.toml")
    }

    const PENCIL: &str = r#"
        part = "builtin:v-grooves"
        tool = "ball:d=4"
        [parent]
        tool = "ball:d=12"
        [strategy]
        kind = "cleanup"
        pattern = "flow-cut"
        scallop = 0.01
    "#;

    #[test]
    fn a_chain_cleans_up_after_each_tool_in_turn() {
        let text = PENCIL.replace(
            "kind = \"cleanup\"",
            "kind = \"cleanup\"\nchain = [\"ball:d=8\"]",
        );
        let j = job(&text).unwrap();
        let model = load_model(&j.part).unwrap();
        let stages = plan_cleanup_job(&j, &model, Path::new(".")).unwrap();
        assert_eq!(stages.len(), 2);
        assert_eq!(
            (stages[0].reference.to_string(), stages[0].tool.to_string()),
            ("ball:d=12".into(), "ball:d=8".into())
        );
        assert_eq!(
            (stages[1].reference.to_string(), stages[1].tool.to_string()),
            ("ball:d=8".into(), "ball:d=4".into())
        );
        // Each stage's rest is the closed form of its reference ball in the 90 degree
        // groove: R / sin 45 - R.
        for s in &stages {
            let r = s.reference.radius();
            let exact = r * 2f64.sqrt() - r;
            let groove = s
                .detection
                .regions
                .iter()
                .find(|g| (g.deepest.x - 55.0).abs() < 1.0)
                .unwrap();
            assert!(
                (groove.depth - exact).abs() < 1e-6,
                "{} vs {exact}",
                groove.depth
            );
            assert!(!s.plan.toolpath.passes.is_empty());
        }
        assert_eq!(stage_file("out/pocket.ngc", 1), "out/pocket.1.ngc");
    }

    #[test]
    fn cleanup_jobs_say_what_is_wrong() {
        let bad = |from: &str, to: &str| job(&PENCIL.replace(from, to)).unwrap_err().to_string();
        assert!(bad("[parent]\n        tool = \"ball:d=12\"", "").contains("[parent]"));
        assert!(
            bad(
                "tool = \"ball:d=12\"",
                "tool = \"ball:d=12\"\n        job = \"f.toml\""
            )
            .contains("exactly one")
        );
        assert!(
            bad(
                "pattern = \"flow-cut\"",
                "pattern = \"flow-cut\"\n        merge = 0"
            )
            .contains("strategy.merge")
        );
        assert!(
            bad(
                "pattern = \"flow-cut\"",
                "pattern = \"flow-cut\"\n        overlap = -1"
            )
            .contains("strategy.overlap")
        );
        assert!(
            bad(
                "pattern = \"flow-cut\"",
                "pattern = \"flow-cut\"\n        min_area = 0"
            )
            .contains("strategy.min_area")
        );
        assert!(
            bad(
                "pattern = \"flow-cut\"",
                "pattern = \"flow-cut\"\n        source = \"stock\""
            )
            .contains("parent job")
        );
        assert!(
            bad("pattern = \"flow-cut\"", "pattern = \"spiral\"").contains("expected `flow-cut`")
        );
        // A parent job that does not exist; a cleanup tool larger than the parent's.
        let j =
            job(&PENCIL.replace("tool = \"ball:d=12\"", "job = \"no-such-finish.toml\"")).unwrap();
        let model = load_model(&j.part).unwrap();
        let e = plan_cleanup_job(&j, &model, Path::new("/nonexistent"))
            .unwrap_err()
            .to_string();
        assert!(e.contains("no-such-finish.toml"), "{e}");
        let j = job(&PENCIL.replace("tool = \"ball:d=4\"", "tool = \"ball:d=16\"")).unwrap();
        let e = plan_cleanup_job(&j, &model, Path::new("."))
            .unwrap_err()
            .to_string();
        assert!(e.contains("ball:d=16") && e.contains("ball:d=12"), "{e}");
    }

    #[test]
    fn no_rest_gives_an_empty_program_that_says_so() {
        let dir = std::env::temp_dir().join(format!("swarf-cleanup-empty-{}", std::process::id()));
        // Rest thinner than 100 mm is left alone: none is left to clean up.
        let text = PENCIL.replace("scallop = 0.01", "scallop = 0.01\n        threshold = 100")
            + "[output]\ngcode = \"empty.ngc\"\n";
        let j = job(&text).unwrap();
        let summary =
            crate::plan_job::plan_job(&j, Path::new("."), &dir, &swarf_sim::Quiet).unwrap();
        assert_eq!(summary["passes"], 0);
        assert_eq!(summary["rest"]["regions"].as_array().unwrap().len(), 0);
        let g = std::fs::read_to_string(dir.join("empty.ngc")).unwrap();
        assert!(
            g.contains("no passes: nothing to cut") && g.contains("M30"),
            "{g}"
        );
        std::fs::remove_dir_all(&dir).ok();
    }
}
