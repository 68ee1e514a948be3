//! The 3D view of a verified program (`swarf view`, and `swarf demo` for every
//! program it verifies): a self-contained folder with the design, the tool path, the
//! cutter and the simulated stock as glTF (GLB) files ([`swarf_report::gltf`]),
//! `view.json` (the program's motions, poses and source lines, the stock mesh and the
//! deviation scale) and, where the viewer page has been built
//! ([`VIEWER_BUILD`]), the page itself (`index.html` and its script).
//!
//! Everything is staged in the command's [`Outputs`] and committed as one set: a
//! failure leaves no half-written folder. The inputs are checked before the
//! verification runs: a program with no moves, and a program whose tool path does
//! not come near the part (their XY extents, widened by the cutter's radius, do not
//! overlap), are refused with their extents named.

use crate::error::{AppError, Result, bail};
use crate::model::Model;
use crate::outputs::Outputs;
use serde_json::{Value, json};
use std::path::{Path, PathBuf};
use swarf_nc::read::Program;
use swarf_report::gltf::{self, StockMesh, StockMeshOptions, toolpath::classify};
use swarf_sim::Verification;
use swarf_tool::Cutter;

/// The command that builds the viewer page (from the repository root).
pub const VIEWER_BUILD: &str = "cd viewer && npm ci && npm run build";

/// Environment variable naming the built page's folder (default: `viewer/dist` of
/// the source tree swarf was built from).
pub const VIEWER_ENV: &str = "SWARF_VIEWER_DIST";

/// Lines of program source copied into `view.json` at most.
const MAX_SOURCE_LINES: usize = 2_000_000;

/// The folder of the built viewer page, if it has been built (it holds
/// `index.html`).
pub fn viewer_dist() -> Option<PathBuf> {
    let dir = std::env::var_os(VIEWER_ENV).map_or_else(
        || Path::new(env!("CARGO_MANIFEST_DIR")).join("../../viewer/dist"),
        PathBuf::from,
    );
    dir.join("index.html").is_file().then_some(dir)
}

/// The note for a view written without its page.
pub fn missing_viewer_note() -> String {
    format!(
        "note: the viewer page is not built, so the view has its GLB files and view.json but no \
         index.html: build it with `{VIEWER_BUILD}` (or set {VIEWER_ENV} to a built page)"
    )
}

/// What a view needs: the design, the program with its cutter, and the
/// verification of the program.
#[derive(Clone, Copy)]
pub struct ViewInput<'a> {
    /// The design.
    pub model: &'a Model,
    /// Chordal tolerance for tessellating a patch design, mm.
    pub tol: f64,
    /// The program.
    pub program: &'a Program,
    /// Its cutter.
    pub cutter: &'a Cutter,
    /// The verification of the program.
    pub verification: &'a Verification,
}

/// What a view wrote.
#[derive(Debug, Clone)]
pub struct ViewWritten {
    /// The stock mesh (stride, counts, stated height error).
    pub stock: StockMesh,
    /// Whether the page was copied in.
    pub page: bool,
}

/// Refuses a program that cannot be shown against `model` (module doc).
///
/// # Errors
/// No moves; XY extents that do not overlap, naming both.
pub fn check_view_inputs(model: &Model, program: &Program, cutter: &Cutter) -> Result<()> {
    if program.motions.is_empty() {
        bail!(
            "{}: the program has no moves: nothing to show",
            program.source
        );
    }
    let b = match model {
        Model::Patches(p) => p.control_box(),
        Model::Mesh { mesh, .. } => mesh.aabb(),
    };
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    // Where the motions go (the first motion's start is the control's initial
    // position, not a point of the program).
    for p in program.motions.iter().map(|m| m.end.cl) {
        for k in 0..2 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let r = cutter.radius();
    let apart = (0..2).any(|k| hi[k] + r < b.min[k] || lo[k] - r > b.max[k]);
    if apart {
        bail!(
            "{}: the tool path (x {:.3} to {:.3}, y {:.3} to {:.3} mm) and the part (x {:.3} to \
             {:.3}, y {:.3} to {:.3} mm) do not overlap, even with the cutter's radius {r} mm: is \
             it the program for this part (and in the same units)?",
            program.source,
            lo[0],
            hi[0],
            lo[1],
            hi[1],
            b.min.x,
            b.max.x,
            b.min.y,
            b.max.y
        );
    }
    Ok(())
}

/// The motions for the page: their source lines, classes and end poses.
fn motions_json(program: &Program) -> Value {
    let r = |x: f64| (x * 1e5).round() / 1e5;
    let mut pose = Vec::with_capacity(6 * (program.motions.len() + 1));
    if let Some(first) = program.motions.first() {
        let (c, a) = (first.start.cl, first.start.axis);
        pose.extend([c.x, c.y, c.z, a.x, a.y, a.z].map(r));
    }
    for m in &program.motions {
        let (c, a) = (m.end.cl, m.end.axis);
        pose.extend([c.x, c.y, c.z, a.x, a.y, a.z].map(r));
    }
    json!({
        "count": program.motions.len(),
        "line": program.motions.iter().map(|m| m.line).collect::<Vec<_>>(),
        "kind": program.motions.iter().map(|m| classify(m).letter()).collect::<String>(),
        "pose": pose,
    })
}

/// Stages the view of `input` under `dir` (relative to `out`'s directory; "" for it)
/// (module doc).
///
/// # Errors
/// A design that does not tessellate; a GLB beyond 4 GiB; the page's files that
/// cannot be read; an output that cannot be staged.
pub fn write_view(
    out: &mut Outputs,
    dir: &str,
    input: &ViewInput<'_>,
    opts: &StockMeshOptions,
) -> Result<ViewWritten> {
    let ViewInput {
        model,
        program,
        cutter,
        verification: v,
        ..
    } = *input;
    let file = |name: &str| Path::new(dir).join(name);
    let mesh = model.triangles(input.tol)?;
    out.write(file("part.glb"), &gltf::part_glb(&mesh)?)?;
    out.write(
        file("toolpath.glb"),
        &gltf::toolpath_glb(&program.motions, cutter)?,
    )?;
    let first = program.motions.first().map(|m| m.start);
    let home = first.unwrap_or(swarf_tool::Pose {
        cl: swarf_geom::Point3::origin(),
        axis: swarf_geom::Vec3::z(),
    });
    out.write(file("cutter.glb"), &gltf::cutter_glb(cutter, &home)?)?;
    let (stock_bytes, stock) = gltf::stock_glb(v, opts)?;
    out.write(file("stock.glb"), &stock_bytes)?;
    let text = out
        .read_text(Path::new(&program.source))
        .unwrap_or_default();
    let source: Vec<&str> = text.lines().take(MAX_SOURCE_LINES).collect();
    let s = &v.deviation.summary;
    let ramp: Vec<Value> = (-10..=10)
        .map(|k| {
            json!([
                f64::from(k) / 10.0,
                swarf_report::picture::diverging(f64::from(k) / 10.0)
            ])
        })
        .collect();
    let view = json!({
        "swarf": env!("CARGO_PKG_VERSION"),
        "program": program.source,
        "tool": cutter.to_string(),
        "files": { "part": "part.glb", "toolpath": "toolpath.glb", "cutter": "cutter.glb", "stock": "stock.glb" },
        "motions": motions_json(program),
        "source": source,
        "grid": { "origin_mm": v.grid.origin, "cell_mm": v.grid.cell, "nx": v.grid.nx, "ny": v.grid.ny },
        "stock": stock,
        "deviation": {
            "mode": if v.along_normals { "normal" } else { "vertical" },
            "tolerance_mm": s.tol,
            "allowed_excess_mm": s.allowed_excess,
            "min_mm": s.min,
            "max_mm": s.max,
            "ramp": ramp,
        },
    });
    out.write_json(file("view.json"), &view)?;
    let page = match viewer_dist() {
        Some(dist) => {
            copy_page(out, &dist, &file(""))?;
            true
        }
        None => false,
    };
    Ok(ViewWritten { stock, page })
}

/// Stages the built page's files (the folder `dist`, one level of subfolders) under
/// `to`.
fn copy_page(out: &mut Outputs, dist: &Path, to: &Path) -> Result<()> {
    let read = |p: &Path| {
        std::fs::read_dir(p)
            .map_err(|e| AppError::Message(format!("{}: {e} (the viewer page)", p.display())))
    };
    for entry in read(dist)? {
        let path = entry
            .map_err(|e| AppError::Message(format!("{}: {e}", dist.display())))?
            .path();
        let name = path.file_name().map(PathBuf::from).unwrap_or_default();
        if path.is_dir() {
            for inner in read(&path)? {
                let p = inner
                    .map_err(|e| AppError::Message(format!("{}: {e}", path.display())))?
                    .path();
                if p.is_file() {
                    copy_file(
                        out,
                        &p,
                        &to.join(&name).join(p.file_name().unwrap_or_default()),
                    )?;
                }
            }
        } else if path.is_file() {
            copy_file(out, &path, &to.join(name))?;
        }
    }
    Ok(())
}

fn copy_file(out: &mut Outputs, from: &Path, to: &Path) -> Result<()> {
    let bytes = std::fs::read(from)
        .map_err(|e| AppError::Message(format!("{}: {e} (the viewer page)", from.display())))?;
    out.write(to, &bytes)
}

/// A view as `swarf view` asks for it: a part and a program, or a job.
#[derive(Debug, Clone, Copy)]
pub struct ViewRequest<'a> {
    /// What to show.
    pub source: ViewSource<'a>,
    /// Verification settings (cell size, tolerance, stock, ...).
    pub sim: &'a crate::verify::SimSettings,
    /// The stock mesh's vertex budget.
    pub stock: StockMeshOptions,
    /// The view folder.
    pub out: &'a Path,
}

/// What `swarf view` shows.
#[derive(Debug, Clone, Copy)]
pub enum ViewSource<'a> {
    /// A program on a part.
    Program {
        /// The design: a part file, a mesh or a built-in part.
        part: &'a str,
        /// The NC program (G-code, APT CL or pose CSV).
        program: &'a Path,
        /// Tool spec (default: the program's CUTTER record).
        tool: Option<&'a str>,
        /// Machine for five-axis G-code.
        machine: Option<&'a str>,
    },
    /// A job file, planned first.
    Job(&'a Path),
}

/// What `swarf view` did: the view and the notes for the user.
#[derive(Debug)]
pub struct Viewed {
    /// The view.
    pub written: ViewWritten,
    /// Deviation range and cells, for the console.
    pub summary: String,
    /// Notes for the user.
    pub notes: Vec<String>,
}

/// Verifies what `req` names and writes its view folder (with the verification's
/// report, flagged cells and pictures beside the view's files) as one set.
///
/// # Errors
/// Inputs that cannot be read; a program with no moves or away from the part
/// ([`check_view_inputs`]); a program that stops before its end; the verification's
/// and [`write_view`]'s errors.
pub fn view_request(
    req: &ViewRequest<'_>,
    progress: &dyn crate::report::Reporter,
) -> Result<Viewed> {
    let mut out = Outputs::new(req.out);
    let (model, program, cutter, opts, part, mut notes) = match req.source {
        ViewSource::Program {
            part,
            program,
            tool,
            machine,
        } => {
            let (model, program, cutter, opts, notes) =
                read_program_input(req, part, program, tool, machine)?;
            (model, program, cutter, opts, part.to_string(), notes)
        }
        ViewSource::Job(path) => {
            let (model, program, cutter, opts, part) =
                plan_job_input(req, path, &mut out, progress)?;
            (model, program, cutter, opts, part, Vec::new())
        }
    };
    check_view_inputs(&model, &program, &cutter)?;
    let stages = [swarf_sim::Stage {
        program: &program,
        cutter: &cutter,
    }];
    let ctx = crate::verify::context(&part, &stages, &opts);
    if let Some(stop) = &ctx.stopped {
        bail!(
            "{}: the program stops before its end ({stop}): nothing written",
            program.source
        );
    }
    let v =
        crate::verify::verify_and_write(&model, &stages, &opts, (&mut out, ""), &ctx, progress)?;
    let input = ViewInput {
        model: &model,
        tol: opts.tol,
        program: &program,
        cutter: &cutter,
        verification: &v,
    };
    let written = write_view(&mut out, "", &input, &req.stock)?;
    if !written.page {
        notes.push(missing_viewer_note());
    }
    out.commit()?;
    let summary = swarf_sim::report::text_summary(&v, &ctx);
    Ok(Viewed {
        written,
        summary,
        notes,
    })
}

/// Inputs of a view of a program on a part.
type Inputs = (
    Model,
    Program,
    Cutter,
    swarf_sim::VerifyOptions,
    Vec<String>,
);

fn read_program_input(
    req: &ViewRequest<'_>,
    part: &str,
    program: &Path,
    tool: Option<&str>,
    machine: Option<&str>,
) -> Result<Inputs> {
    let model = crate::model::load_model(part)?;
    model.check_covers_xy(part)?;
    let paths = [program.to_path_buf()];
    let planned = crate::programs::planned(&paths)?;
    let tools: Vec<String> = match tool {
        Some(t) => vec![t.to_string()],
        None => planned.tools.iter().take(1).cloned().collect(),
    };
    let tools = crate::programs::parse_tools(&tools, 1)?;
    let opts = req.sim.program_options(&planned)?;
    let gcode = crate::programs::GcodeSetup::default();
    let (mut programs, notes) =
        crate::programs::read_programs(&paths, &gcode, machine, None, opts.sample_tol())?;
    let cutter = crate::programs::stage_cutters(&tools, &programs)?[0];
    let program = programs.remove(0);
    Ok((model, program, cutter, opts, notes))
}

/// Inputs of a view of a job.
type JobInputs = (Model, Program, Cutter, swarf_sim::VerifyOptions, String);

fn plan_job_input(
    req: &ViewRequest<'_>,
    path: &Path,
    out: &mut Outputs,
    reporter: &dyn crate::report::Reporter,
) -> Result<JobInputs> {
    let text = swarf_io::read_input_text(path)?;
    let mut job = crate::Job::parse(&text, &path.display().to_string())?;
    let stem = path
        .file_stem()
        .map_or_else(|| "job".into(), |s| s.to_string_lossy().into_owned());
    let (program_file, five) = crate::compare::for_measurement(&mut job, &stem);
    let job_dir = path.parent().unwrap_or(Path::new("."));
    let part = crate::plan_job::part_arg(&job, job_dir);
    let model = crate::model::load_model_with(&part, &job.load_options())?;
    crate::plan_job::plan_model(&job, &model, job_dir, out, reporter)?;
    let program = out.read_program(&program_file)?;
    let scallop = job.strategy.scallop().unwrap_or(0.0);
    let mut opts = req
        .sim
        .options(job.tolerance(), scallop, job.feeds.rapid, true)?;
    if five {
        opts.cell = opts.cell.or(Some(crate::compare::FIVE_AXIS_CELL));
        opts.sample_tol = opts
            .sample_tol
            .or(Some(crate::compare::FIVE_AXIS_SAMPLE_TOL));
    }
    Ok((model, program, job.tool, opts, part))
}

#[cfg(test)]
mod tests {
    use super::*;
    use swarf_geom::Point3;
    use swarf_nc::read::{Motion, MotionKind};
    use swarf_tool::Pose;

    /// A program of straight moves through `points` (the first from the origin).
    fn program(points: &[[f64; 3]]) -> Program {
        let mut p = Program::new("p.ngc");
        let mut at = Pose::vertical(Point3::origin());
        for (k, &q) in points.iter().enumerate() {
            let end = Pose::vertical(Point3::from(q));
            let kind = if k == 0 {
                MotionKind::Rapid
            } else {
                MotionKind::Linear
            };
            p.motions.push(Motion {
                kind,
                start: at,
                end,
                feed: 300.0,
                line: k + 2,
            });
            at = end;
        }
        p
    }

    fn wave() -> Model {
        crate::model::load_model("builtin:wave").unwrap()
    }

    #[test]
    fn inputs_are_checked_before_verifying() {
        let ball: Cutter = "ball:d=8".parse().unwrap();
        let err = check_view_inputs(&wave(), &program(&[]), &ball)
            .unwrap_err()
            .to_string();
        assert!(err.contains("p.ngc") && err.contains("no moves"), "{err}");
        let apart = program(&[[1000.0, 1000.0, 50.0], [1100.0, 1000.0, 0.0]]);
        let err = check_view_inputs(&wave(), &apart, &ball)
            .unwrap_err()
            .to_string();
        assert!(
            err.contains("do not overlap") && err.contains("x 1000.000 to 1100.000"),
            "{err}"
        );
        // Just off the part's edge, within the cutter's radius, is near enough.
        let edge = program(&[[-3.0, 10.0, 50.0], [-3.0, 20.0, 0.0]]);
        check_view_inputs(&wave(), &edge, &ball).unwrap();
    }

    #[test]
    fn motions_hold_the_start_then_each_end_pose() {
        let p = program(&[[1.0, 2.0, 30.0], [1.0, 2.0, 3.0], [9.0, 2.0, 3.0]]);
        let m = motions_json(&p);
        assert_eq!(m["count"], 3);
        assert_eq!(m["line"], json!([2, 3, 4]));
        assert_eq!(m["kind"], "rlc");
        let pose: Vec<f64> = serde_json::from_value(m["pose"].clone()).unwrap();
        assert_eq!(pose.len(), 6 * 4);
        assert_eq!(&pose[..6], &[0.0, 0.0, 0.0, 0.0, 0.0, 1.0]);
        assert_eq!(&pose[18..], &[9.0, 2.0, 3.0, 0.0, 0.0, 1.0]);
    }
}
