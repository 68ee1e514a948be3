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
//! restmaterial = ["valley", "ramp"] # and/or "steep" (after a raster parent job)
//! ```
//!
//! Steep rest ([`swarf_rest::steep`]) is the walls the parent raster's passes lie
//! too far apart on: the job's tool cleans them up with Z-levels at the job's
//! scallop (`direction` climb or conventional, `sampling`, `overlap` past the
//! walls), after its own region passes in the last stage. A job that cleans up only
//! steep rest has one stage; where the parent leaves none, its program is empty and
//! says why.
//!
//! The first stage finds the rest from the chosen source; every later stage of a
//! chain uses the previous stage's tool as its reference (crease scans). The last
//! stage's program goes to the job's outputs; an intermediate stage `k` (from 1)
//! writes the same files with `.k` before the extension.

use crate::error::{AppError, Context, Result, bail};
use crate::job::Job;
use crate::model::Model;
use crate::outputs::Outputs;
use crate::plan::{PlanInput, plan};
use crate::strategy::Strategy;
use std::borrow::Cow;
use std::path::{Path, PathBuf};
use swarf_geom::TriMesh;
use swarf_path::strategy::waterline::WaterlineParams;
use swarf_path::{Plan, PlanReport};
use swarf_rest::steep::SteepRest;
use swarf_rest::{
    Detection, RasterParent, RegionParams, RestKind, Source, SteepParams, detect, plan_cleanup,
    plan_steep,
};
use swarf_rest::{RestMaterial, RestSource};
use swarf_sim::{Design, Quiet, StockSpec, VerifyOptions};
use swarf_tool::Cutter;
use swarf_toolpath::top_z;

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
    /// The steep rest the stage cleans up too (the last stage of a job with
    /// `restmaterial` "steep").
    pub steep: Option<SteepRest>,
    /// What the program's header says besides the usual (why it is empty).
    pub notes: Vec<String>,
}

/// The part as a mesh: a mesh part as it is, patches tessellated within a tenth of
/// `tol`.
///
/// # Errors
/// A tessellation that fails.
pub fn part_mesh(model: &Model, tol: f64) -> Result<Cow<'_, TriMesh>> {
    model.triangles(0.1 * tol)
}

/// Reads the parent job `rel` (relative to `job_dir`): as staged in `staged` when the
/// command wrote it there (the demo stages the jobs it runs), else from disk.
///
/// # Errors
/// A file that cannot be read or parsed; a parent that is itself a cleanup.
pub fn read_parent(rel: &str, job_dir: &Path, staged: Option<&Outputs>) -> Result<(Job, PathBuf)> {
    let path = job_dir.join(rel);
    let text = staged
        .map_or_else(
            || Ok(swarf_io::read_input_text(&path)?),
            |o| o.read_text(&path),
        )
        .with_context(|| format!("parent.job: {}: cannot read the parent job", path.display()))?;
    let parent = Job::parse(&text, &path.display().to_string())?;
    if matches!(parent.strategy, Strategy::Cleanup(_)) {
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
            if !matches!(parent.strategy, Strategy::Raster(_)) {
                bail!(
                    "strategy.source: \"contacts\" needs a raster parent (the {:?} strategy records no double contacts); use source = \"reference\"",
                    parent.strategy.kind()
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

/// Plans the cleanup job `job` (module doc) on `model`; its parent job is read as
/// [`read_parent`] reads it.
///
/// # Errors
/// A parent that cannot be read, planned or verified; a tool larger than the tool
/// before it; steep rest after a parent that is not a raster; the detection's and
/// the planning's errors.
pub fn plan_cleanup_job(
    job: &Job,
    model: &Model,
    job_dir: &Path,
    staged: Option<&Outputs>,
) -> Result<Vec<CleanupStage>> {
    let Some(parent_spec) = &job.parent else {
        bail!("parent: a cleanup job needs a [parent] table");
    };
    let c = params_of(job)?;
    let mesh = part_mesh(model, job.tolerance())?;
    let parent = match (&parent_spec.job, parent_spec.tool) {
        (Some(rel), _) => Some(read_parent(rel, job_dir, staged)?.0),
        (None, _) => None,
    };
    let reference = parent
        .as_ref()
        .map(|p| p.tool)
        .or(parent_spec.tool)
        .with_context(|| "parent: expected `job` or `tool`".into())?;
    let kinds = &c.restmaterial;
    let mut stages = if kinds.iter().any(|k| *k != RestMaterial::Steep) {
        region_stages(job, parent.as_ref(), model, &mesh, reference)?
    } else {
        vec![CleanupStage {
            tool: job.tool,
            reference,
            source: "raster",
            detection: Detection::default(),
            plan: Plan::from_passes(
                Vec::new(),
                &job.cutting(),
                PlanReport::default(),
                Vec::new(),
            ),
            steep: None,
            notes: Vec::new(),
        }]
    };
    if let (true, Some(parent), Some(last)) = (
        kinds.contains(&RestMaterial::Steep),
        &parent,
        stages.last_mut(),
    ) {
        add_steep(job, parent, &mesh, last)?;
    }
    for stage in &mut stages {
        crate::plan::clip_to_reach(job, &mut stage.plan)?;
    }
    Ok(stages)
}

/// The cleanup parameters of `job`.
///
/// # Errors
/// A job whose strategy is not a cleanup.
pub fn params_of(job: &Job) -> Result<&swarf_rest::CleanupParams> {
    match &job.strategy {
        Strategy::Cleanup(c) => Ok(c),
        other => bail!("strategy.kind: {:?} is not a cleanup", other.kind()),
    }
}

/// The stages that clean up the rest regions (valley and ramp rest): the job's chain
/// of tools, then its own.
fn region_stages(
    job: &Job,
    parent: Option<&Job>,
    model: &Model,
    mesh: &TriMesh,
    mut reference: Cutter,
) -> Result<Vec<CleanupStage>> {
    let c = params_of(job)?;
    let tools: Vec<Cutter> = c.chain.iter().copied().chain([job.tool]).collect();
    let kinds = &c.restmaterial;
    let wanted = |k: &RestKind| match k {
        RestKind::Valley => kinds.contains(&RestMaterial::Valley),
        RestKind::Ramp => kinds.contains(&RestMaterial::Ramp),
        RestKind::Stock => true,
    };
    let mut stages = Vec::with_capacity(tools.len());
    for (k, tool) in tools.into_iter().enumerate() {
        let start = std::time::Instant::now();
        let settings = (job.tolerance(), &c.regions());
        let (mut detection, source) = match (parent, k) {
            (Some(p), 0) => {
                let d = detect_after(p, model, mesh, c.source, settings)?;
                (d, source_name(c.source))
            }
            _ => (
                detect(mesh, &reference, Source::Reference, settings.0, settings.1)?,
                "reference",
            ),
        };
        detection.regions.retain(|r| r.kinds.iter().any(wanted));
        let cutting = swarf_path::Cutting {
            tool,
            ..job.cutting()
        };
        let toolpath =
            plan_cleanup(mesh, &detection.regions, &reference, &cutting, c).map_err(|e| {
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
            steep: None,
            notes: Vec::new(),
        });
        reference = tool;
    }
    Ok(stages)
}

/// Adds the steep cleanup after the raster `parent` to `stage` (the job's tool): its
/// Z-level passes after the stage's own, its steep rest, and a note where there is
/// none.
fn add_steep(job: &Job, parent: &Job, mesh: &TriMesh, stage: &mut CleanupStage) -> Result<()> {
    let start = std::time::Instant::now();
    let Strategy::Raster(parent_raster) = &parent.strategy else {
        bail!(
            "strategy.restmaterial: \"steep\" is the rest a raster leaves on walls, but the parent job is {:?}; use a raster parent or leave \"steep\" out",
            parent.strategy.kind()
        );
    };
    let c = params_of(job)?;
    let spacing = swarf_path::strategy::raster::spacing(mesh, &parent.tool, parent_raster)
        .map_err(|e| AppError::Message(format!("parent.job: the parent job fails: {e}")))?;
    let raster = RasterParent {
        tool: parent.tool,
        spacing,
        feed_angle: parent_raster.angle,
    };
    let cutting = job.cutting();
    let threshold = c.regions().threshold;
    let params = SteepParams {
        waterline: WaterlineParams {
            finish: c.finish,
            direction: c.direction.unwrap_or_default(),
            sampling: c.sampling,
            ..WaterlineParams::new(c.scallop.unwrap_or(threshold))
        },
        threshold,
        overlap: c.overlap,
    };
    let (rest, passes) = plan_steep(mesh, &raster, &cutting, &params)?;
    if rest.region.cells == 0 {
        stage.notes.push(format!(
            "no steep rest: passes {spacing:.4} mm apart leave more than {threshold} mm only on slopes above {:.2} degrees across them, and the part has none",
            rest.angle.to_degrees()
        ));
    }
    let tp = &mut stage.plan.toolpath;
    tp.passes.extend(passes);
    tp.linking = cutting.linking_for(top_z(&tp.passes));
    stage.plan.report.elapsed_s += start.elapsed().as_secs_f64();
    stage.steep = Some(rest);
    Ok(())
}

/// The steep rest of a stage as JSON: the angle, the area, the level steps.
pub fn steep_json(rest: &SteepRest) -> serde_json::Value {
    let mut json = serde_json::json!({
        "angle_deg": rest.angle.to_degrees(),
        "xy_area_mm2": rest.region.xy_area,
        "surface_area_mm2": rest.region.surface_area,
        "triangles": rest.region.triangles,
        "cells": rest.region.cells,
    });
    // Levels exist only where there is steep rest to cut: no field (rather than a
    // null where a number belongs) when there is none.
    if let Some(step) = rest.level_step {
        json["level_step_mm"] = serde_json::json!(step);
    }
    json
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
mod tests;
