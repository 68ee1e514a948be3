//! The tool above its flutes: shank and holder as stacked cylinders and cones, and
//! the collision of that assembly with a part.
//!
//! The whole tool in the holder is a solid of revolution about the tool axis whose
//! radius at height `h` above the tip is, from the tip up: the cutter's profile up to
//! the flute length, the shank's segments from the flute length up to the stick-out
//! (the gauge length from the tip to the holder face), and the holder's segments
//! above the face. Each shank or holder segment is a frustum (a cylinder `d`, or a
//! cone from `d0` at its bottom to `d1` at its top) and, as a solid of its own, a
//! special case of the APT tool with a flat bottom and no corner radius
//! ([`crate::apt`]: `d = d0`, `r = 0`, `alpha = 0`, `beta = atan((d1 - d0) / 2L)`,
//! `h = L`), so the drop-cutter kernels and the exact signed distance of the cutters
//! serve it unchanged:
//!
//! - the assembly is the union of its pieces, so its lowest height at a distance
//!   `rho` from the axis is the least of the pieces' there and its drop onto a mesh
//!   is the highest of the pieces' drops, each lowered by the piece's height above
//!   the tip ([`vertical`]); a tilted tool is the same in its own frame
//!   ([`tilted`], with the search for the extra tilt that clears);
//! - its signed distance is the least of the pieces' (exact outside, where the sign
//!   and the clearance are read).
//!
//! The shank is the tool's own: its pieces sit at fixed heights above the tip, and
//! the part of it above the stick-out is inside the holder (clipped there). The holder
//! moves with the stick-out. So a longer stick-out lifts the holder (fewer holder
//! collisions) and bares more shank (more shank collisions): the stick-outs that
//! clear a path are an interval, and the shortest is where the holder just clears.
//!
//! Units: mm.

pub mod tilted;
pub mod vertical;

use crate::apt::Apt;
use crate::cutter::Cutter;
use crate::error::ToolError;
use crate::pose::Pose;
use crate::profile::Profile;
use swarf_geom::Point3;

/// One stacked segment of a shank or holder, from its bottom up.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub enum StackSegment {
    /// A cylinder of diameter `d`.
    Cylinder {
        /// Diameter, mm.
        d: f64,
        /// Height, mm.
        length: f64,
    },
    /// A cone (frustum) from diameter `d0` at its bottom to `d1` at its top.
    Cone {
        /// Bottom diameter, mm.
        d0: f64,
        /// Top diameter, mm.
        d1: f64,
        /// Height, mm.
        length: f64,
    },
}

impl StackSegment {
    /// Height of the segment, mm.
    pub fn length(&self) -> f64 {
        match *self {
            StackSegment::Cylinder { length, .. } | StackSegment::Cone { length, .. } => length,
        }
    }

    /// Radius at height `t` above its bottom (clamped to the segment), mm.
    pub fn radius_at(&self, t: f64) -> f64 {
        match *self {
            StackSegment::Cylinder { d, .. } => 0.5 * d,
            StackSegment::Cone { d0, d1, length } => {
                let f = (t / length).clamp(0.0, 1.0);
                0.5 * (d0 + (d1 - d0) * f)
            }
        }
    }

    /// The lower `length` of this segment (the same segment when `length` is not
    /// shorter).
    pub fn clipped(&self, length: f64) -> StackSegment {
        if length >= self.length() {
            return *self;
        }
        match *self {
            StackSegment::Cylinder { d, .. } => StackSegment::Cylinder { d, length },
            StackSegment::Cone { d0, .. } => StackSegment::Cone {
                d0,
                d1: 2.0 * self.radius_at(length),
                length,
            },
        }
    }

    /// The segment as a cutter with its own tip at its bottom (module doc).
    ///
    /// # Errors
    /// A diameter or length outside the domain of tools, named as APT fields.
    pub fn as_cutter(&self) -> Result<Cutter, ToolError> {
        match *self {
            StackSegment::Cylinder { d, length } => Cutter::flat(d, Some(length)),
            StackSegment::Cone { d0, d1, length } => {
                let beta = (0.5 * (d1 - d0) / length).atan();
                Apt::from_corner(d0, 0.0, 0.0, beta, length).map(Cutter::Apt)
            }
        }
    }
}

/// Which part of the tool a piece belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize)]
pub enum PieceKind {
    /// Shank segment `k` (from the flutes up).
    Shank(usize),
    /// Holder segment `k` (from the face up).
    Holder(usize),
}

impl std::fmt::Display for PieceKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            PieceKind::Shank(k) => write!(f, "shank[{k}]"),
            PieceKind::Holder(k) => write!(f, "holder[{k}]"),
        }
    }
}

/// One piece of the assembly above the flutes, placed on the tool axis.
#[derive(Debug, Clone, PartialEq)]
pub struct Piece {
    /// Which segment it is.
    pub kind: PieceKind,
    /// Height of its bottom above the tool tip, mm.
    pub z0: f64,
    /// The segment (clipped at the holder face for the shank).
    pub segment: StackSegment,
    /// The segment as a cutter with its tip at its bottom.
    pub cutter: Cutter,
}

/// A cutter with its shank, holder and stick-out.
#[derive(Debug, Clone, PartialEq)]
pub struct Assembly {
    /// The cutter; its length is the flute length.
    pub cutter: Cutter,
    /// Shank segments from the top of the flutes up.
    pub shank: Vec<StackSegment>,
    /// Holder segments from the holder face up.
    pub holder: Vec<StackSegment>,
    /// Gauge length from the tool tip to the holder face, mm.
    pub stick_out: f64,
}

impl Assembly {
    /// Overall length of the tool (flutes and shank), mm: the longest stick-out.
    pub fn tool_length(&self) -> f64 {
        self.cutter.length() + self.shank.iter().map(StackSegment::length).sum::<f64>()
    }

    /// The pieces of the shank below `stick_out`, from the flutes up.
    ///
    /// # Errors
    /// A segment outside the domain of tools.
    pub fn shank_pieces(&self, stick_out: f64) -> Result<Vec<Piece>, ToolError> {
        let mut out = Vec::new();
        let mut z0 = self.cutter.length();
        for (k, seg) in self.shank.iter().enumerate() {
            let bare = stick_out - z0;
            if bare <= swarf_geom::tol::LENGTH_EPS {
                break;
            }
            let segment = seg.clipped(bare);
            out.push(Piece {
                kind: PieceKind::Shank(k),
                z0,
                segment,
                cutter: segment.as_cutter()?,
            });
            z0 += seg.length();
        }
        Ok(out)
    }

    /// The pieces of the holder with its face at `stick_out` above the tip.
    ///
    /// # Errors
    /// A segment outside the domain of tools.
    pub fn holder_pieces(&self, stick_out: f64) -> Result<Vec<Piece>, ToolError> {
        let mut z0 = stick_out;
        self.holder
            .iter()
            .enumerate()
            .map(|(k, seg)| {
                let piece = Piece {
                    kind: PieceKind::Holder(k),
                    z0,
                    segment: *seg,
                    cutter: seg.as_cutter()?,
                };
                z0 += seg.length();
                Ok(piece)
            })
            .collect()
    }

    /// Signed distance from `p` to the shank and holder (at this assembly's
    /// stick-out) at `pose`, any orientation: the least of the pieces' exact signed
    /// distances, negative inside. `None` when a segment is invalid.
    ///
    /// # Units
    /// mm.
    pub fn signed_distance(&self, pose: &Pose, p: &Point3) -> Option<f64> {
        let pieces = self.shank_pieces(self.stick_out).ok()?;
        let holder = self.holder_pieces(self.stick_out).ok()?;
        let (rho, z) = Pose::new(pose.cl, pose.axis)?.to_rho_z(p);
        pieces
            .iter()
            .chain(&holder)
            .map(|pc| pc.profile().signed_distance_rho_z(rho, z - pc.z0))
            .reduce(f64::min)
    }
}

impl Piece {
    /// The piece's profile in its own frame (tip at its bottom).
    pub fn profile(&self) -> Profile {
        self.cutter.profile()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn assembly() -> Assembly {
        Assembly {
            cutter: Cutter::ball(6.0, Some(12.0)).unwrap(),
            shank: vec![
                StackSegment::Cone {
                    d0: 5.0,
                    d1: 6.0,
                    length: 8.0,
                },
                StackSegment::Cylinder {
                    d: 6.0,
                    length: 40.0,
                },
            ],
            holder: vec![
                StackSegment::Cone {
                    d0: 20.0,
                    d1: 32.0,
                    length: 20.0,
                },
                StackSegment::Cylinder {
                    d: 63.0,
                    length: 30.0,
                },
            ],
            stick_out: 30.0,
        }
    }

    #[test]
    fn pieces_stack_and_the_shank_is_clipped_at_the_face() {
        let a = assembly();
        assert_eq!(a.tool_length(), 60.0);
        let shank = a.shank_pieces(30.0).unwrap();
        assert_eq!(shank.len(), 2);
        assert_eq!((shank[0].z0, shank[1].z0), (12.0, 20.0));
        assert_eq!(shank[1].segment.length(), 10.0);
        let short = a.shank_pieces(16.0).unwrap();
        assert_eq!(short.len(), 1);
        assert_eq!(
            short[0].segment,
            StackSegment::Cone {
                d0: 5.0,
                d1: 5.5,
                length: 4.0
            }
        );
        let holder = a.holder_pieces(30.0).unwrap();
        assert_eq!((holder[0].z0, holder[1].z0), (30.0, 50.0));
    }

    #[test]
    fn segment_cutters_have_the_segments_radii() {
        for seg in assembly().shank.iter().chain(&assembly().holder) {
            let c = seg.as_cutter().unwrap();
            let l = seg.length();
            for i in 0..=10 {
                let t = l * f64::from(i) / 10.0;
                let r = c.radius_at_height(t).unwrap();
                assert!((r - seg.radius_at(t)).abs() < 1e-9, "{seg:?} at {t}");
            }
            assert_eq!(c.height_at_radius(0.5 * seg.radius_at(0.0)), Some(0.0));
        }
    }

    #[test]
    fn signed_distance_is_the_closed_form_beside_the_pieces() {
        let a = assembly();
        let pose = Pose::vertical(Point3::new(1.0, 2.0, 3.0));
        // Beside the holder cylinder (radius 31.5, from z 50 to 80 above the tip).
        let d = a.signed_distance(&pose, &Point3::new(41.0, 2.0, 3.0 + 60.0));
        assert!((d.unwrap() - 8.5).abs() < 1e-9);
        // Inside the shank cylinder at height 25 (radius 3).
        let d = a.signed_distance(&pose, &Point3::new(2.0, 2.0, 28.0));
        assert!((d.unwrap() + 2.0).abs() < 1e-9);
        // Under the holder face, 1 mm below it, off the shank.
        let d = a.signed_distance(&pose, &Point3::new(9.0, 2.0, 3.0 + 29.0));
        assert!((d.unwrap() - 1.0).abs() < 1e-9);
    }
}
