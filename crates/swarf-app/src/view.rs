//! The 3D view of a verified program (`swarf view`, and `swarf demo` for every
//! program it verifies): a self-contained folder with the design, the tool path, the
//! cutter and the simulated stock as glTF (GLB) files ([`swarf_report::gltf`]),
//! `view.json` (the program's motions, poses and source lines, its operations, the
//! stock mesh and the deviation scale) and the viewer page ([`page`], embedded in
//! the binary).
//!
//! A program of several operations (a sequence job, a program that changes tools)
//! is shown per operation: `view.json` lists each operation's motions, tool, cutter
//! file and the stock after it (`stock-K.glb` for operation K but the last, whose
//! stock is `stock.glb`), verified on the same stock as the whole program.
//!
//! Everything is staged in the command's [`Outputs`] and committed as one set: a
//! failure leaves no half-written folder. The inputs are checked before the
//! verification runs: a program with no moves, and a program whose tool path does
//! not come near the part (their XY extents, widened by the cutter's radius, do not
//! overlap), are refused with their extents named.

pub mod page;
mod request;

use crate::error::{Result, bail};
use crate::model::Model;
use crate::outputs::Outputs;
use serde_json::{Value, json};
use std::path::Path;
use swarf_nc::read::{Motion, Program};
use swarf_report::gltf::{self, StockMesh, StockMeshOptions, toolpath::classify};
use swarf_sim::{Stage, Verification};
use swarf_tool::Cutter;

pub use request::{ViewRequest, ViewSource, Viewed, view_request};

/// Lines of program source copied into `view.json` at most.
const MAX_SOURCE_LINES: usize = 2_000_000;

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

/// The motions for the page: their source lines, classes and end poses (the motions
/// of every stage, in order).
fn motions_json(motions: &[Motion]) -> Value {
    let r = |x: f64| (x * 1e5).round() / 1e5;
    let mut pose = Vec::with_capacity(6 * (motions.len() + 1));
    if let Some(first) = motions.first() {
        let (c, a) = (first.start.cl, first.start.axis);
        pose.extend([c.x, c.y, c.z, a.x, a.y, a.z].map(r));
    }
    for m in motions {
        let (c, a) = (m.end.cl, m.end.axis);
        pose.extend([c.x, c.y, c.z, a.x, a.y, a.z].map(r));
    }
    json!({
        "count": motions.len(),
        "line": motions.iter().map(|m| m.line).collect::<Vec<_>>(),
        "kind": motions.iter().map(|m| classify(m).letter()).collect::<String>(),
        "pose": pose,
    })
}

/// What a view of programs run in order on one stock needs (module doc): the
/// design, the stages, the verification of them all, and the verification after
/// each stage but the last.
#[derive(Clone, Copy)]
pub struct StagedView<'a> {
    /// The design.
    pub model: &'a Model,
    /// Chordal tolerance for tessellating a patch design, mm.
    pub tol: f64,
    /// The programs with their cutters, in order (at least one).
    pub stages: &'a [Stage<'a>],
    /// The operations' names, one per stage (missing ones are named by their tool).
    pub names: &'a [String],
    /// The program's file and source text, which the stages' lines index (when
    /// `None`: the first stage's file, read).
    pub source: Option<(&'a str, &'a str)>,
    /// The verification of all the stages.
    pub verification: &'a Verification,
    /// The verification after stage k, for each k before the last (empty: the
    /// operations are shown on the final stock).
    pub after: &'a [Verification],
}

/// Stages the view of `input` under `dir` (relative to `out`'s directory; "" for it)
/// (module doc).
///
/// # Errors
/// A design that does not tessellate; a GLB beyond 4 GiB; an output that cannot be
/// staged.
pub fn write_view(
    out: &mut Outputs,
    dir: &str,
    input: &ViewInput<'_>,
    opts: &StockMeshOptions,
) -> Result<ViewWritten> {
    let stages = [Stage {
        program: input.program,
        cutter: input.cutter,
    }];
    let staged = StagedView {
        model: input.model,
        tol: input.tol,
        stages: &stages,
        names: &[],
        source: None,
        verification: input.verification,
        after: &[],
    };
    write_staged_view(out, dir, &staged, opts)
}

/// Stages the view of programs run in order on one stock (module doc), as
/// [`write_view`] does for one.
///
/// # Errors
/// As [`write_view`]; no stage.
pub fn write_staged_view(
    out: &mut Outputs,
    dir: &str,
    input: &StagedView<'_>,
    opts: &StockMeshOptions,
) -> Result<ViewWritten> {
    let Some(first) = input.stages.first() else {
        bail!("a view needs at least one program");
    };
    let v = input.verification;
    let file = |name: &str| Path::new(dir).join(name);
    let mesh = input.model.triangles(input.tol)?;
    out.write(file("part.glb"), &gltf::part_glb(&mesh)?)?;
    let motions: Vec<Motion> = input
        .stages
        .iter()
        .flat_map(|s| s.program.motions.iter().copied())
        .collect();
    out.write(
        file("toolpath.glb"),
        &gltf::toolpath_glb(&motions, first.cutter)?,
    )?;
    let (stock_bytes, stock) = gltf::stock_glb(v, opts)?;
    out.write(file("stock.glb"), &stock_bytes)?;
    let operations = write_operations(out, dir, input, opts)?;
    let (program, text) = match input.source {
        Some((file, text)) => (file.to_string(), text.to_string()),
        None => (
            first.program.source.clone(),
            out.read_text(Path::new(&first.program.source))
                .unwrap_or_default(),
        ),
    };
    let source: Vec<&str> = text.lines().take(MAX_SOURCE_LINES).collect();
    let s = &v.deviation.summary;
    let tools: Vec<String> = input.stages.iter().map(|s| s.cutter.to_string()).collect();
    let view = json!({
        "swarf": env!("CARGO_PKG_VERSION"),
        "program": program,
        "tool": tools.join(" + "),
        "files": { "part": "part.glb", "toolpath": "toolpath.glb", "cutter": "cutter.glb", "stock": "stock.glb" },
        "operations": operations,
        "motions": motions_json(&motions),
        "source": source,
        "grid": { "origin_mm": v.grid.origin, "cell_mm": v.grid.cell, "nx": v.grid.nx, "ny": v.grid.ny },
        "stock": stock,
        "deviation": {
            "mode": if v.along_normals { "normal" } else { "vertical" },
            "tolerance_mm": s.tol,
            "allowed_excess_mm": s.allowed_excess,
            "min_mm": s.min,
            "max_mm": s.max,
        },
    });
    out.write_json(file("view.json"), &view)?;
    page::write_page(out, Path::new(dir))?;
    Ok(ViewWritten { stock })
}

/// Stages each operation's cutter (at the program's start) and the stock after it;
/// the operations' entries for `view.json`.
fn write_operations(
    out: &mut Outputs,
    dir: &str,
    input: &StagedView<'_>,
    opts: &StockMeshOptions,
) -> Result<Vec<Value>> {
    let file = |name: &str| Path::new(dir).join(name);
    let home = input.stages[0].program.motions.first().map_or_else(
        || swarf_tool::Pose::vertical(swarf_geom::Point3::origin()),
        |m| m.start,
    );
    let (mut ops, mut first_motion) = (Vec::with_capacity(input.stages.len()), 0);
    let mut cutters: Vec<(Cutter, String)> = Vec::new();
    for (k, stage) in input.stages.iter().enumerate() {
        let cutter = match cutters.iter().find(|c| c.0 == *stage.cutter) {
            Some(c) => c.1.clone(),
            None => {
                let name = if cutters.is_empty() {
                    "cutter.glb".to_string()
                } else {
                    format!("cutter-{}.glb", k + 1)
                };
                out.write(file(&name), &gltf::cutter_glb(stage.cutter, &home)?)?;
                cutters.push((*stage.cutter, name.clone()));
                name
            }
        };
        let stock = match input.after.get(k) {
            Some(after) if k + 1 < input.stages.len() => {
                let name = format!("stock-{}.glb", k + 1);
                out.write(file(&name), &gltf::stock_glb(after, opts)?.0)?;
                name
            }
            _ => "stock.glb".to_string(),
        };
        let n = stage.program.motions.len();
        ops.push(json!({
            "name": input.names.get(k).cloned().unwrap_or_else(|| stage.cutter.to_string()),
            "tool": stage.cutter.to_string(),
            "first_motion": first_motion,
            "motions": n,
            "cutter": cutter,
            "stock": stock,
        }));
        first_motion += n;
    }
    Ok(ops)
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
        let m = motions_json(&p.motions);
        assert_eq!(m["count"], 3);
        assert_eq!(m["line"], json!([2, 3, 4]));
        assert_eq!(m["kind"], "rlc");
        let pose: Vec<f64> = serde_json::from_value(m["pose"].clone()).unwrap();
        assert_eq!(pose.len(), 6 * 4);
        assert_eq!(&pose[..6], &[0.0, 0.0, 0.0, 0.0, 0.0, 1.0]);
        assert_eq!(&pose[18..], &[9.0, 2.0, 3.0, 0.0, 0.0, 1.0]);
    }
}
