//! The holder and shank check of NC programs (`swarf verify --tool-library`): the
//! poses of each program, sampled along its motions, against the design's triangles
//! with a tool of the library ([`swarf_tool::holder`]).
//!
//! Vertical poses go through [`check_vertical`], which also gives the shortest
//! stick-out that clears them; tilted poses are checked one axis at a time
//! ([`Views`], one re-laid grid per distinct axis) and add their collisions. With
//! tilted poses the shortest stick-out is found over all of them, each in its own
//! axis's frame ([`shortest_stick_out_posed`]).
//!
//! Without `--tool`, each tool section of a program (a program that changes tools
//! is cut at its tool changes, [`Program::split_by_tool`]) takes the library tool of
//! its T number ([`stage_tools`]). A planned job's path is checked the same way
//! ([`path`]); the resolution of library tools in job files is [`library`].

pub mod avoid;
pub mod library;
pub mod path;

use crate::error::{AppError, Result, bail};
use crate::model::load_model;
use crate::programs::{GcodeSetup, read_programs};
use serde::Serialize;
use std::path::{Path, PathBuf};
use swarf_geom::{Point3, TriMesh, Vec3};
use swarf_nc::read::{MotionKind, Program};
use swarf_tool::drop::MeshDropper;
use swarf_tool::holder::PieceKind;
use swarf_tool::holder::tilted::{Views, shortest_stick_out_posed};
use swarf_tool::holder::vertical::{CONTACT_EPS, HolderReport, StickOut, check_vertical};
use swarf_tool::library::{LibraryTool, ToolLibrary};

/// Distance between checked poses along a motion for `swarf verify`, mm.
pub const POSE_SPACING: f64 = 1.0;

/// Arcs are sampled at least this many times.
const ARC_SAMPLES: usize = 16;

/// A collision, with the program line that commanded its pose (and, for a planned
/// path, its pass and pose).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct LineCollision {
    /// Source line of the motion (none for a planned path with no G-code written).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub line: Option<usize>,
    /// A planned path's pass and pose within it, from 0.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub pass: Option<[usize; 2]>,
    /// Tool tip, mm.
    pub cl: Point3,
    /// Tool axis.
    pub axis: Vec3,
    /// How far the piece reaches into the part, mm.
    pub depth: f64,
    /// The piece (`holder[0]`, `shank[1]`).
    pub piece: PieceKind,
    /// Where the piece touches the part when moved onto it along the axis, mm.
    pub contact: Point3,
}

/// The holder check of one program.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct HolderCheck {
    /// The program.
    pub program: String,
    /// The tool's T number.
    pub number: u32,
    /// The tool's name.
    pub name: String,
    /// Poses checked (motion ends and samples along the motions).
    pub poses: usize,
    /// Of which tilted.
    pub tilted: usize,
    /// Collisions at the library's stick-out, in program order.
    pub collisions: Vec<LineCollision>,
    /// The least clearance over every pose, vertical and tilted, mm.
    pub min_clearance: Option<f64>,
    /// The shortest stick-out that clears every pose, vertical and tilted.
    pub shortest: StickOut,
    /// The check of the vertical poses alone (their shortest stick-out and least
    /// clearance).
    pub vertical: HolderReport,
}

/// The holder check of a program or path that cleared.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct HolderSummary {
    /// The library's stick-out, mm.
    pub stick_out: f64,
    /// Poses checked.
    pub poses: usize,
    /// Of which tilted.
    pub tilted: usize,
    /// The least clearance of shank or holder over the part, mm.
    pub min_clearance: Option<f64>,
    /// The shortest stick-out that clears every pose (the flute length when no
    /// holder piece is over the part).
    pub shortest: StickOut,
}

/// What `swarf verify --tool-library` asks for.
#[derive(Debug, Clone, Copy)]
pub struct HolderRequest<'a> {
    /// Design part, as `--part` names it.
    pub part: &'a str,
    /// The programs.
    pub programs: &'a [PathBuf],
    /// The tool library file.
    pub library: &'a Path,
    /// Tool names or numbers, the k-th for the k-th program (the last for the rest).
    pub tools: &'a [String],
    /// How G-code is read.
    pub gcode: &'a GcodeSetup,
    /// Machine for five-axis G-code.
    pub machine: Option<&'a str>,
    /// Spindle gauge line to tool tip, mm (head machines).
    pub tool_length: Option<f64>,
    /// Chord tolerance of the design's triangles and sampling of arcs, mm.
    pub tol: f64,
    /// Distance between checked poses along a motion, mm.
    pub spacing: f64,
}

/// The library's tools for the `--tool` keys, one per program.
///
/// # Errors
/// No key, more keys than programs, a key the library lacks (listing its tools).
pub fn library_tools<'l>(
    library: &'l ToolLibrary,
    keys: &[String],
    programs: usize,
) -> Result<Vec<&'l LibraryTool>> {
    let Some(last) = keys.last() else {
        bail!("--tool-library: give --tool NAME|NUMBER for the programs' tool");
    };
    if keys.len() > programs {
        bail!("--tool: {} tools for {programs} programs", keys.len());
    }
    (0..programs)
        .map(|k| Ok(library.get(keys.get(k).unwrap_or(last))?))
        .collect()
}

/// The library tool of each stage (a program's section with one tool): the
/// `--tool` keys in order when given ([`library_tools`]), else the tool of the
/// stage's T number.
///
/// # Errors
/// As [`library_tools`]; without keys, a stage with no T word, or a T number the
/// library lacks (naming the line where that tool first cuts and the library file).
pub fn stage_tools<'l>(
    library: &'l ToolLibrary,
    file: &Path,
    keys: &[String],
    stages: &[Program],
) -> Result<Vec<&'l LibraryTool>> {
    if !keys.is_empty() {
        return library_tools(library, keys, stages.len());
    }
    stages
        .iter()
        .map(|p| {
            let Some(t) = p.tools.first() else {
                bail!(
                    "{}: no T word to look up in the tool library {}: give --tool NAME|NUMBER",
                    p.source,
                    file.display()
                );
            };
            library.get(&t.number.to_string()).map_err(|e| {
                AppError::Message(format!(
                    "{}: line {}: T{} (the tool cutting from this line) is not in the tool \
                     library {}: {e}",
                    p.source,
                    t.line,
                    t.number,
                    file.display()
                ))
            })
        })
        .collect()
}

/// The programs of `req`, cut at their tool changes, and the library.
fn read_stages(req: &HolderRequest<'_>) -> Result<(ToolLibrary, Vec<Program>)> {
    let library = ToolLibrary::read(req.library)?;
    let (programs, _) = read_programs(
        req.programs,
        req.gcode,
        req.machine,
        req.tool_length,
        req.tol,
    )?;
    let stages = programs
        .into_iter()
        .flat_map(Program::split_by_tool)
        .collect();
    Ok((library, stages))
}

/// The cutter spec strings of the library tools of `req` ([`stage_tools`]), one per
/// stage, for the simulation ([`crate::verify::VerifyRequest::tools`]).
///
/// # Errors
/// A library or program that cannot be read; as [`stage_tools`].
pub fn library_specs(req: &HolderRequest<'_>) -> Result<Vec<String>> {
    let (library, stages) = read_stages(req)?;
    Ok(stage_tools(&library, req.library, req.tools, &stages)?
        .iter()
        .map(|t| t.assembly.cutter.to_string())
        .collect())
}

/// Poses along the motions of `program`: each motion's end and points about
/// `spacing` apart along it (the first motion: its end only), with their source
/// lines.
pub fn program_poses(program: &Program, spacing: f64) -> Vec<(swarf_tool::Pose, usize)> {
    let mut out = Vec::new();
    for (i, m) in program.motions.iter().enumerate() {
        let chord = (m.end.cl - m.start.cl).norm();
        let mut n = (chord / spacing.max(1e-3)).ceil().max(1.0) as usize;
        if matches!(m.kind, MotionKind::Arc { .. }) {
            n = n.max(ARC_SAMPLES);
        }
        if i == 0 {
            // The first motion starts where the reader assumes the tool is, not at a
            // commanded position: only its end counts.
            n = 1;
        }
        out.extend((1..=n).map(|k| (m.point_at(k as f64 / n as f64), m.line)));
    }
    out
}

/// The collisions of poses tagged `tag` (a line, or an index the caller maps),
/// in tag order, the least clearance over all, and the vertical poses' report.
pub(crate) struct PoseCheck {
    pub(crate) collisions: Vec<(usize, LineCollision)>,
    pub(crate) min_clearance: Option<f64>,
    pub(crate) tilted: usize,
    pub(crate) shortest: StickOut,
    pub(crate) vertical: HolderReport,
}

impl PoseCheck {
    /// The check of `poses` poses of `program` with `tool`, each collision placed
    /// by `place` from its pose's tag.
    pub(crate) fn into_check(
        self,
        program: String,
        tool: &LibraryTool,
        poses: usize,
        place: impl Fn(usize, LineCollision) -> LineCollision,
    ) -> HolderCheck {
        HolderCheck {
            program,
            number: tool.number,
            name: tool.name.clone(),
            poses,
            tilted: self.tilted,
            collisions: self
                .collisions
                .into_iter()
                .map(|(tag, c)| place(tag, c))
                .collect(),
            min_clearance: self.min_clearance,
            shortest: self.shortest,
            vertical: self.vertical,
        }
    }
}

/// Checks the shank and holder of `tool` at `poses` (each with a tag) against
/// `mesh`: vertical poses at once with the shortest stick-out, tilted ones one
/// axis at a time (module doc).
pub(crate) fn check_poses(
    mesh: &TriMesh,
    poses: &[(swarf_tool::Pose, usize)],
    tool: &LibraryTool,
) -> Result<PoseCheck> {
    let a = &tool.assembly;
    type Sample<'p> = &'p (swarf_tool::Pose, usize);
    let (vertical, tilted): (Vec<Sample>, Vec<Sample>) =
        poses.iter().partition(|p| p.0.is_vertical());
    let cls: Vec<Point3> = vertical.iter().map(|p| p.0.cl).collect();
    let dropper = MeshDropper::new(mesh, &a.cutter);
    let report = check_vertical(a, &dropper, &cls)?;
    let collision =
        |pose: &swarf_tool::Pose, depth: f64, piece: PieceKind, contact: Point3| LineCollision {
            line: None,
            pass: None,
            cl: pose.cl,
            axis: pose.axis,
            depth,
            piece,
            contact,
        };
    let mut collisions: Vec<(usize, LineCollision)> = report
        .collisions
        .iter()
        .map(|c| {
            let (pose, tag) = &vertical[c.pose];
            (*tag, collision(pose, c.depth, c.piece, c.contact))
        })
        .collect();
    let mut min_clearance = report.min_clearance.map(|(_, c)| c);
    let mut views = Views::new(mesh);
    for (pose, tag) in &tilted {
        let Some(view) = views.along(&pose.axis, a) else {
            continue;
        };
        if let Some(c) = view.clearance(a, &pose.cl)? {
            min_clearance = Some(min_clearance.map_or(c.clearance, |m| m.min(c.clearance)));
            if c.clearance < -CONTACT_EPS {
                collisions.push((*tag, collision(pose, -c.clearance, c.piece, c.contact)));
            }
        }
    }
    collisions.sort_by_key(|c| c.0);
    let shortest = if tilted.is_empty() {
        report.shortest
    } else {
        let all: Vec<swarf_tool::Pose> = poses.iter().map(|p| p.0).collect();
        shortest_stick_out_posed(a, &dropper, &mut views, &all)?
    };
    Ok(PoseCheck {
        collisions,
        min_clearance,
        tilted: tilted.len(),
        shortest,
        vertical: report,
    })
}

/// Checks the poses of `program` with `tool` against `mesh` (module doc).
///
/// # Errors
/// A shank or holder segment the kernel refuses.
pub fn check_program(
    mesh: &TriMesh,
    program: &Program,
    tool: &LibraryTool,
    spacing: f64,
) -> Result<HolderCheck> {
    let poses = program_poses(program, spacing);
    let check = check_poses(mesh, &poses, tool)?;
    Ok(
        check.into_check(program.source.clone(), tool, poses.len(), |line, c| {
            LineCollision {
                line: Some(line),
                ..c
            }
        }),
    )
}

/// Reads the part, the programs and the library of `req` and checks each tool
/// section of each program with its tool ([`stage_tools`]).
///
/// # Errors
/// A part, program or library that cannot be read; a tool key or T number the
/// library lacks; the errors of [`check_program`].
pub fn check_request(req: &HolderRequest<'_>) -> Result<Vec<HolderCheck>> {
    let (library, stages) = read_stages(req)?;
    let tools = stage_tools(&library, req.library, req.tools, &stages)?;
    let model = load_model(req.part)?;
    let mesh = model.triangles(req.tol)?;
    stages
        .iter()
        .zip(tools)
        .map(|(p, t)| check_program(&mesh, p, t, req.spacing))
        .collect()
}

impl LineCollision {
    /// Where it is: `pass P, pose K, line L`, whichever are known.
    pub fn place(&self) -> String {
        let mut parts = Vec::new();
        if let Some([pass, pose]) = self.pass {
            parts.push(format!("pass {pass}, pose {pose}"));
        }
        if let Some(line) = self.line {
            parts.push(format!("line {line}"));
        }
        parts.join(", ")
    }
}

impl HolderCheck {
    /// The summary of a check that cleared.
    ///
    /// # Errors
    /// A collision: [`HolderCheck::summary`] (where, how deep, the shortest
    /// stick-out that clears).
    pub fn cleared(&self) -> Result<HolderSummary> {
        if !self.collisions.is_empty() {
            return Err(AppError::Message(self.summary()));
        }
        Ok(HolderSummary {
            stick_out: self.vertical.stick_out,
            poses: self.poses,
            tilted: self.tilted,
            min_clearance: self.min_clearance,
            shortest: self.shortest,
        })
    }

    /// A few lines for the terminal: the tool, the collisions, the shortest
    /// stick-out.
    pub fn summary(&self) -> String {
        let a = &self.vertical;
        let mut s = format!(
            "holder: {} with T{} \"{}\" at stick-out {} mm: {} poses",
            self.program, self.number, self.name, a.stick_out, self.poses
        );
        match self.collisions.first() {
            None => s += ", no collision",
            Some(c) => {
                s += &format!(
                    ", {} collide (first: {}, {} {:.3} mm into the part at ({:.3}, {:.3}, \
                     {:.3}))",
                    self.collisions.len(),
                    c.place(),
                    c.piece,
                    c.depth,
                    c.cl.x,
                    c.cl.y,
                    c.cl.z
                );
            }
        }
        s += &match self.shortest {
            StickOut::Clears { stick_out, .. } => {
                format!("\nholder: shortest stick-out that clears: {stick_out:.3} mm")
            }
            StickOut::ShankCollides {
                stick_out,
                collision,
            } => format!(
                "\nholder: no stick-out clears: at {stick_out:.3} mm {} reaches {:.3} mm into \
                 the part",
                collision.piece, collision.depth
            ),
            StickOut::TooLong {
                stick_out,
                tool_length,
            } => format!(
                "\nholder: clearing needs a stick-out of {stick_out:.3} mm; the tool is only \
                 {tool_length:.3} mm long"
            ),
        };
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const LIBRARY: &str = "[[tool]]
number = 3
name = \"ball6-long\"
cutter = \"ball:d=6\"
flute_length = 12
stick_out = 30
shank = [{ d0 = 5, d1 = 6, length = 8 }, { d = 6, length = 40 }]
holder = [{ d0 = 20, d1 = 32, length = 20 }, { d = 63, length = 30 }]
";

    /// Down into the deep pocket's floor, then 10 mm along it while tilting: one
    /// vertical pose and ten tilted ones; the holder (face 30 above the tip, radius
    /// 10) sits 10 mm into the top at the floor.
    #[test]
    fn vertical_and_tilted_poses_are_checked_with_their_lines() {
        let csv = "x,y,z,i,j,k\n30,20,50,0,0,1\n30,20,0,0,0,1\n30,30,0,0.2,0,1\n";
        let program = swarf_nc::read::parse_pose_csv(csv, "p.csv").unwrap();
        let poses = program_poses(&program, 1.0);
        assert_eq!(poses.len(), 11);
        assert_eq!((poses[0].1, poses[10].1), (3, 4));
        let library = ToolLibrary::parse(LIBRARY, "lib.toml").unwrap();
        let tools = library_tools(&library, &["ball6-long".into()], 1).unwrap();
        let mesh = swarf_io::builtin_mesh("deep-pocket").unwrap();
        let check = check_program(&mesh, &program, tools[0], 1.0).unwrap();
        assert_eq!((check.poses, check.tilted), (11, 10));
        let first = check.collisions[0];
        assert_eq!((first.line, first.piece), (Some(3), PieceKind::Holder(0)));
        assert!((first.depth - 10.0).abs() < 1e-9, "{first:?}");
        assert!(check.collisions.iter().skip(1).all(|c| c.line == Some(4)));
        assert_eq!(
            check.vertical.shortest,
            StickOut::Clears {
                stick_out: 40.0,
                pose: Some(0)
            }
        );
        let s = check.summary();
        // Over the tilted poses too. They lean toward the pocket's wall at x = 35:
        // from one on, the shank's side, extended up its axis, meets the wall below
        // the top (z = 40), so whatever stick-out holds the holder clear bares shank
        // against the wall. Closed form at tilt t (axis x slope 0.02 k at sample k):
        // the side of the radius 3 shank reaches x = 35 at h = (5 - 3 cos t) / sin t
        // along the axis, at height h cos t - 3 sin t.
        let StickOut::ShankCollides {
            stick_out,
            collision,
        } = check.shortest
        else {
            panic!("{:?}", check.shortest);
        };
        let meets_wall = |k: usize| {
            let t = (0.02 * k as f64).atan();
            let h = (5.0 - 3.0 * t.cos()) / t.sin();
            h * t.cos() - 3.0 * t.sin() < 40.0
        };
        let first = (1..=10).find(|&k| meets_wall(k)).unwrap();
        println!(
            "no stick-out clears: at {stick_out:.3} mm, pose {}",
            collision.pose
        );
        assert!(stick_out >= 40.0, "{stick_out}");
        assert_eq!(collision.pose, first);
        assert!(matches!(collision.piece, PieceKind::Shank(_)));
        assert!(s.contains("no stick-out clears"), "{s}");
        let e = library_tools(&library, &[], 1).unwrap_err().to_string();
        assert!(e.contains("give --tool NAME|NUMBER"), "{e}");
    }
}
