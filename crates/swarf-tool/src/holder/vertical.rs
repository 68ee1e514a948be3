//! Shank and holder against a mesh for a vertical (3-axis) tool: clearance per pose
//! and the shortest stick-out that clears a path.
//!
//! Each piece ([`super::Piece`]) is a cutter with its tip at its bottom, `z0` above
//! the tool tip; its drop onto the mesh at the pose's `(x, y)` is the lowest height
//! of its bottom, so the tool tip may go no lower than `drop - z0`. The assembly's
//! limit is the highest of its pieces' ([`super`]): at a pose with tip height `z` the
//! clearance is `z - max_i (drop_i - z0_i)` (vertical, mm; negative: the piece
//! reaches that far into the part).
//!
//! The holder's pieces sit at `S + o_j` (`o_j` their height above the face), so at a
//! pose the holder clears exactly when `S >= max_j (drop_j - o_j) - z`, and the
//! shortest stick-out for a path is the largest of these over its poses (at least
//! the flute length: a tool is not held by its flutes). The shank is then checked
//! once, clipped at that stick-out: if it collides, no stick-out clears (a longer one
//! bares more shank, module doc of [`super`]).
//!
//! The drops are [`MeshDropper::drop_tool`] over the one grid of the mesh; poses run
//! in parallel, collected in order.

use super::{Assembly, Piece, PieceKind};
use crate::drop::{DropCutter, DropScratch, MeshDropper};
use crate::error::ToolError;
use rayon::prelude::*;
use swarf_geom::Point3;

/// A clearance below minus this counts as a collision (rounding of the drops), mm.
pub const CONTACT_EPS: f64 = 1e-9;

/// The tightest piece at one pose.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Clearance {
    /// Vertical clearance, mm: negative where the piece reaches into the part.
    pub clearance: f64,
    /// The piece that sets it.
    pub piece: PieceKind,
    /// Where that piece touches the part when lowered onto it, mm.
    pub contact: Point3,
}

/// A pose where the shank or holder reaches into the part.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Collision {
    /// Index of the pose in the path.
    pub pose: usize,
    /// The pose's tool tip, mm.
    pub cl: Point3,
    /// How far the piece reaches into the part, vertically, mm (> 0).
    pub depth: f64,
    /// The piece.
    pub piece: PieceKind,
    /// Where the piece touches the part when lowered onto it, mm.
    pub contact: Point3,
}

/// The shortest stick-out for a path, or why none clears.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub enum StickOut {
    /// This stick-out clears every pose (mm); `pose` is the pose that needs it (none
    /// when the flute length is enough everywhere).
    Clears {
        /// The stick-out, mm.
        stick_out: f64,
        /// The pose that sets it.
        pose: Option<usize>,
    },
    /// The holder clears at `stick_out`, but the shank bared there collides: no
    /// stick-out clears (a longer one bares more shank).
    ShankCollides {
        /// The stick-out at which the holder just clears, mm.
        stick_out: f64,
        /// The first shank collision there.
        collision: Collision,
    },
    /// Clearing needs a stick-out longer than the tool.
    TooLong {
        /// The stick-out needed, mm.
        stick_out: f64,
        /// The overall tool length, mm.
        tool_length: f64,
    },
}

/// The holder check of a path: collisions at the assembly's stick-out and the
/// shortest stick-out that clears.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct HolderReport {
    /// Number of poses checked.
    pub poses: usize,
    /// The stick-out checked, mm.
    pub stick_out: f64,
    /// Poses where the shank or holder reaches into the part, in path order.
    pub collisions: Vec<Collision>,
    /// The least clearance over the path and its pose (none when no piece is ever
    /// over the part).
    pub min_clearance: Option<(usize, f64)>,
    /// The shortest stick-out that clears the path.
    pub shortest: StickOut,
}

/// Pieces prepared for drops.
pub(crate) struct Prepared(Vec<(Piece, DropCutter)>);

impl Prepared {
    pub(crate) fn new(pieces: Vec<Piece>) -> Prepared {
        Prepared(
            pieces
                .into_iter()
                .map(|p| {
                    let d = DropCutter::new(&p.cutter);
                    (p, d)
                })
                .collect(),
        )
    }

    /// The tightest piece at `cl`; `None` when no piece is over the mesh.
    pub(crate) fn clearance(
        &self,
        mesh: &MeshDropper,
        cl: &Point3,
        scratch: &mut DropScratch,
    ) -> Option<Clearance> {
        let mut best: Option<Clearance> = None;
        for (piece, tool) in &self.0 {
            let Some(r) = mesh.drop_tool(tool, cl.x, cl.y, scratch) else {
                continue;
            };
            let clearance = cl.z - (r.z - piece.z0);
            if best.is_none_or(|b| clearance < b.clearance) {
                best = Some(Clearance {
                    clearance,
                    piece: piece.kind,
                    contact: r.cc,
                });
            }
        }
        best
    }

    /// The clearance at every pose, in order.
    fn clearances(&self, mesh: &MeshDropper, cls: &[Point3]) -> Vec<Option<Clearance>> {
        cls.par_iter()
            .map_init(DropScratch::default, |s, cl| self.clearance(mesh, cl, s))
            .collect()
    }
}

/// The poses of `cls` whose clearance `clear` is a collision.
pub(crate) fn collisions(cls: &[Point3], clear: &[Option<Clearance>]) -> Vec<Collision> {
    cls.iter()
        .zip(clear)
        .enumerate()
        .filter_map(|(pose, (cl, c))| {
            let c = (*c)?;
            (c.clearance < -CONTACT_EPS).then_some(Collision {
                pose,
                cl: *cl,
                depth: -c.clearance,
                piece: c.piece,
                contact: c.contact,
            })
        })
        .collect()
}

/// Checks the shank and holder of `assembly` at the tool tips `cls` (vertical tool)
/// against the mesh of `dropper`, and finds the shortest stick-out that clears them.
///
/// # Units
/// mm.
///
/// # Errors
/// A shank or holder segment outside the domain of tools.
pub fn check_vertical(
    assembly: &Assembly,
    dropper: &MeshDropper,
    cls: &[Point3],
) -> Result<HolderReport, ToolError> {
    let stick_out = assembly.stick_out;
    let mut pieces = assembly.shank_pieces(stick_out)?;
    pieces.extend(assembly.holder_pieces(stick_out)?);
    let at_stick_out = Prepared::new(pieces).clearances(dropper, cls);
    let min_clearance = at_stick_out
        .iter()
        .enumerate()
        .filter_map(|(i, c)| c.map(|c| (i, c.clearance)))
        .reduce(|a, b| if b.1 < a.1 { b } else { a });
    Ok(HolderReport {
        poses: cls.len(),
        stick_out,
        collisions: collisions(cls, &at_stick_out),
        min_clearance,
        shortest: shortest_stick_out(assembly, dropper, cls)?,
    })
}

/// The shortest stick-out that clears every pose (module doc).
///
/// # Errors
/// A shank or holder segment outside the domain of tools.
pub fn shortest_stick_out(
    assembly: &Assembly,
    dropper: &MeshDropper,
    cls: &[Point3],
) -> Result<StickOut, ToolError> {
    let face = Prepared::new(assembly.holder_pieces(0.0)?).clearances(dropper, cls);
    shortest_from(assembly, &face, |shank| {
        Ok(collisions(cls, &shank.clearances(dropper, cls))
            .first()
            .copied())
    })
}

/// The shortest stick-out from the holder's clearances at stick-out 0 at every pose
/// (`face`; none where no holder piece is over the part), and `shank_collision`,
/// the first collision of the shank pieces it is given (bared to that stick-out).
pub(crate) fn shortest_from(
    assembly: &Assembly,
    face: &[Option<Clearance>],
    shank_collision: impl FnOnce(&Prepared) -> Result<Option<Collision>, ToolError>,
) -> Result<StickOut, ToolError> {
    let mut stick_out = assembly.cutter.length();
    let mut pose = None;
    for (i, c) in face.iter().enumerate() {
        if let Some(c) = c
            && -c.clearance > stick_out
        {
            stick_out = -c.clearance;
            pose = Some(i);
        }
    }
    let tool_length = assembly.tool_length();
    if stick_out > tool_length {
        return Ok(StickOut::TooLong {
            stick_out,
            tool_length,
        });
    }
    let shank = Prepared::new(assembly.shank_pieces(stick_out)?);
    Ok(match shank_collision(&shank)? {
        Some(collision) => StickOut::ShankCollides {
            stick_out,
            collision,
        },
        None => StickOut::Clears { stick_out, pose },
    })
}

impl HolderReport {
    /// Ok when nothing collides at the checked stick-out.
    ///
    /// # Errors
    /// [`ToolError::HolderCollides`] naming the first collision and the stick-out that
    /// clears, or why none does.
    pub fn require_clear(&self) -> Result<(), ToolError> {
        let Some(first) = self.collisions.first() else {
            return Ok(());
        };
        let remedy = match self.shortest {
            StickOut::Clears { stick_out, .. } => {
                format!("a stick-out of at least {stick_out:.3} mm clears every pose")
            }
            StickOut::ShankCollides {
                stick_out,
                collision: c,
            } => format!(
                "no stick-out clears: at {stick_out:.3} mm, where the holder clears, {} \
                 reaches {:.3} mm into the part at pose {}",
                c.piece, c.depth, c.pose
            ),
            StickOut::TooLong {
                stick_out,
                tool_length,
            } => format!(
                "clearing needs a stick-out of {stick_out:.3} mm but the tool is only \
                 {tool_length:.3} mm long"
            ),
        };
        Err(ToolError::HolderCollides {
            collisions: self.collisions.len(),
            poses: self.poses,
            stick_out: self.stick_out,
            pose: first.pose,
            at: [first.cl.x, first.cl.y, first.cl.z],
            piece: first.piece.to_string(),
            depth: first.depth,
            remedy,
        })
    }
}
