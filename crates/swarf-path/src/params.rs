//! The strategies' parameters: what each finishing strategy needs, and nothing of
//! the job file around it (the TOML schema lives in the application layer, which
//! fills these from a job). Lengths in mm, angles in radians.

use serde::{Deserialize, Serialize};
use swarf_geom::domain::show;
use swarf_geom::math::display_degrees;
use swarf_tool::Cutter;
use swarf_toolpath::{Feeds, LinkingSpec};

/// The finishing strategies.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum StrategyKind {
    /// Passes along constant-parameter curves of each patch (paper 004).
    IsoParametric,
    /// Passes are sections of the part by parallel vertical drive planes (paper 004).
    IsoPlanar,
    /// Each pass is placed so that the scallop to the previous one equals h (paper 004).
    IsoScallop,
    /// Drop-cutter raster on a triangle mesh (iso-planar for meshes).
    Raster,
    /// Cleanup of the rest material a parent job leaves (planned by swarf-rest).
    Cleanup,
    /// Closed passes at constant heights around the part ([`crate::waterline`]).
    Waterline,
    /// Raster on the shallow areas, waterline on the steep ones
    /// ([`crate::steep_shallow`]).
    SteepShallow,
    /// Five-axis multipoint passes along the common edge of two faces, by drop and
    /// spin (paper 003; planned by `swarf_fiveaxis::dsm`).
    DropSpin,
    /// Z-level roughing from a box stock down to the part plus an allowance
    /// ([`crate::roughing`]).
    Roughing,
}

/// Which parameter a pass follows (iso-parametric) or which boundary the first pass
/// starts on (iso-scallop).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ParamDir {
    /// Passes run along u (v constant on each pass).
    #[default]
    U,
    /// Passes run along v (u constant on each pass).
    V,
}

/// Which end of the side-step range the first pass is on.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum StartSide {
    /// Start at the low end (smallest v, or the lowest drive plane offset).
    #[default]
    Min,
    /// Start at the high end.
    Max,
}

/// What every finishing strategy takes: the cutter, the chordal tolerance, the
/// cutting direction of consecutive passes, feeds and the linking rule.
#[derive(Debug, Clone, PartialEq)]
pub struct Finish {
    /// The cutter.
    pub tool: Cutter,
    /// Chordal tolerance along a pass (and gouge tolerance), mm.
    pub tolerance: f64,
    /// Alternate the cutting direction of consecutive passes.
    pub zigzag: bool,
    /// Feeds and speeds.
    pub feeds: Feeds,
    /// Clearance plane and approach.
    pub linking: LinkingSpec,
}

impl Finish {
    /// `tool` with a chordal tolerance of 0.01 mm, zigzag passes, default feeds and
    /// linking.
    pub fn new(tool: Cutter) -> Finish {
        Finish {
            tool,
            tolerance: 0.01,
            zigzag: true,
            feeds: Feeds::default(),
            linking: LinkingSpec::default(),
        }
    }
}

/// Parameters of the iso strategies (iso-parametric, iso-planar, iso-scallop).
#[derive(Debug, Clone, PartialEq)]
pub struct IsoParams {
    /// Cutter, tolerance, feeds, linking.
    pub finish: Finish,
    /// Scallop height limit h, mm (the side step follows from it). Required unless
    /// `stepover` is given (iso-planar only).
    pub scallop: Option<f64>,
    /// Fixed distance between iso-planar drive planes ("cross feed", thesis 000 ch.
    /// 8), mm; then no boundary passes are added.
    pub stepover: Option<f64>,
    /// Feed direction along a parameter (iso-parametric, iso-scallop).
    pub direction: ParamDir,
    /// Feed direction in the XY plane from +X, radians (iso-planar).
    pub angle: f64,
    /// Side the first pass starts on.
    pub start: StartSide,
}

impl IsoParams {
    /// Passes spaced by the scallop limit `scallop` (mm), along u from the low end,
    /// iso-planar planes along +X.
    pub fn new(finish: Finish, scallop: f64) -> IsoParams {
        IsoParams {
            finish,
            scallop: Some(scallop),
            stepover: None,
            direction: ParamDir::U,
            angle: 0.0,
            start: StartSide::Min,
        }
    }
}

/// Parameters of the drop-cutter raster.
#[derive(Debug, Clone, PartialEq)]
pub struct RasterParams {
    /// Cutter, tolerance, feeds, linking.
    pub finish: Finish,
    /// Scallop height limit on a flat floor, mm (the line spacing follows from it).
    pub scallop: Option<f64>,
    /// Fixed distance between raster lines, mm (wins over `scallop`).
    pub stepover: Option<f64>,
    /// Feed direction in the XY plane from +X, radians.
    pub angle: f64,
    /// Side the first line is on.
    pub start: StartSide,
    /// Raster boundary `[xmin, ymin, xmax, ymax]`, mm (default: the mesh outline).
    pub boundary: Option<[f64; 4]>,
    /// Ramp angle limit, radians in `(0, pi/2)`: passes climb and descend no steeper
    /// (thesis 002 §3.1.3, [`crate::ramp`]); none by default.
    pub max_ramp: Option<f64>,
    /// Steepest slope across the passes on which the scallop limit must hold,
    /// radians in `(0, pi/2)`: with `scallop`, the stepover is the slope-aware
    /// spacing of [`crate::slope_step::raster_spacing`] and the predicted scallop
    /// the largest over slopes up to it; none by default (a level floor).
    pub max_slope: Option<f64>,
}

impl RasterParams {
    /// Lines `stepover` mm apart along +X over the whole mesh.
    pub fn new(finish: Finish, stepover: f64) -> RasterParams {
        RasterParams {
            finish,
            scallop: None,
            stepover: Some(stepover),
            angle: 0.0,
            start: StartSide::Min,
            boundary: None,
            max_ramp: None,
            max_slope: None,
        }
    }
}

/// An angle in radians as the degrees a user gave ([`display_degrees`]: a plane at
/// 60 degrees reads 60 again in messages after the conversion to radians).
pub fn degrees(angle: f64) -> f64 {
    display_degrees(angle.to_degrees(), angle, f64::to_radians)
}

/// [`degrees`] for a message ([`show`]: no hundreds of digits for an absurd value).
pub fn shown_degrees(angle: f64) -> String {
    show(degrees(angle))
}
