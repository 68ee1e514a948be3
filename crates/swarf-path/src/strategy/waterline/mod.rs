//! Waterline (Z-level) finishing: closed passes at constant height around a part.
//!
//! At a level `z` the tool tip may stand wherever the cutter's drop height is at most
//! `z`; the pass is the boundary of that set, the contour `drop(x, y) = z` of the
//! drop-height field (thesis 002 §6.2.2: Z-slicing of the tool offset surface, with
//! the trimming "keep the points whose drop height is at most z" built in). The
//! contour is not sampled: one grid of exact drops (`field.rs`) tells on which side of
//! each level every node lies, marching squares (`contour.rs`) link the crossings of
//! the grid edges into closed loops, and every crossing and every point inserted to
//! keep the chords within the tolerance is an exact contour point, found by root
//! finding on the drop height (`probe.rs`). The grid serves every level, so a level
//! costs only its contour. Loops smaller than the grid step can be missed, as a
//! sampled waterline misses loops between its fibers: the default step is a quarter
//! of the tool radius, the raster's first step (a bump of the drop height is as wide
//! as the cutter over a spike).
//!
//! Levels ([`levels`]) are spaced from the scallop limit on the steepest wall that
//! must hold it, with extra levels where the wall flattens. Loops are oriented for
//! climb milling (the material on the right of travel with a clockwise spindle, as
//! `G41` compensation) or conventional milling, and cut level by level from the top,
//! each loop started at its point nearest the previous loop's end.

mod contour;
mod field;
pub mod levels;
mod nearest;
mod passes;
mod probe;

use crate::error::PathError;
use crate::params::{Cutting, Finish, check_open_angle, check_scallop, in_domain, require_spacing};
use crate::plan::{Plan, PlanReport};
use crate::stepping::side_step::SideStep;
use crate::stepping::slope_step::zlevel_spacing;
use crate::strategy::raster::pass::drop_point;
use contour::{Loop, level_loops};
use field::DropField;
use probe::Probe;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};
use std::borrow::Cow;
use swarf_geom::TriMesh;
use swarf_geom::domain::{SAMPLE, SCALLOP, STEP};
use swarf_tool::Cutter;
use swarf_tool::drop::MeshDropper;
use swarf_toolpath::PathPoint;

pub use field::MAX_FIELD_NODES;
pub use probe::{ROOT_TOL, Z_EPS};

/// Which side of the tool the material is on.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum Milling {
    /// Material on the right of travel (down milling with a clockwise spindle).
    #[default]
    Climb,
    /// Material on the left of travel (up milling).
    Conventional,
}

impl Milling {
    /// The name a job file gives it.
    pub fn name(self) -> &'static str {
        match self {
            Milling::Climb => "climb",
            Milling::Conventional => "conventional",
        }
    }
}

impl std::str::FromStr for Milling {
    type Err = String;

    /// `climb` or `conventional`; a parameter direction (`u`, `v`) is named as one.
    fn from_str(s: &str) -> Result<Milling, String> {
        match s {
            "climb" => Ok(Milling::Climb),
            "conventional" => Ok(Milling::Conventional),
            "u" | "v" => Err(format!(
                "\"{s}\" is a parameter direction (iso-parametric, iso-scallop); this strategy takes \"climb\" or \"conventional\""
            )),
            other => Err(format!(
                "unknown variant `{}`, expected `climb` or `conventional`",
                swarf_geom::domain::excerpt(other, 40)
            )),
        }
    }
}

impl<'de> Deserialize<'de> for Milling {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Milling, D::Error> {
        String::deserialize(d)?
            .parse()
            .map_err(serde::de::Error::custom)
    }
}

/// Parameters of waterline finishing.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct WaterlineParams {
    /// Tolerance (contour chords) and zigzag.
    #[serde(flatten)]
    pub finish: Finish,
    /// Scallop limit h on walls from `steep_angle` to vertical, mm (or give
    /// `level_step`).
    #[schemars(extend("unit" = "mm", "domain" = format!("{SCALLOP}, below the tool radius")))]
    pub scallop: Option<f64>,
    /// Fixed level spacing, mm (wins over `scallop`; no adaptive levels).
    #[schemars(extend("unit" = "mm", "domain" = STEP.to_string()))]
    pub level_step: Option<f64>,
    /// Slope from horizontal from which the scallop limit holds with the base level
    /// spacing, degrees.
    #[serde(with = "swarf_geom::units::serde_degrees")]
    #[schemars(with = "f64", extend("unit" = "degrees", "domain" = "(flat_angle, 90)"))]
    pub steep_angle: f64,
    /// Adaptive levels stop at walls this flat, degrees.
    #[serde(with = "swarf_geom::units::serde_degrees")]
    #[schemars(with = "f64", extend("unit" = "degrees", "domain" = "(0, steep_angle)"))]
    pub flat_angle: f64,
    /// Add levels where the wall between two levels flattens ([`levels`]).
    pub adaptive: bool,
    /// Drop-field grid step, mm (default: a quarter of the tool radius).
    #[schemars(extend("unit" = "mm", "domain" = SAMPLE.to_string()))]
    pub sampling: Option<f64>,
    /// Climb or conventional milling.
    pub direction: Milling,
    /// Highest level's ceiling, mm (default: the highest drop height; the top level
    /// itself is not cut). Set by the strategies that cut waterline bands.
    #[serde(skip)]
    #[schemars(skip)]
    pub top: Option<f64>,
    /// Lowest level, mm (default: the mesh's lowest point).
    #[serde(skip)]
    #[schemars(skip)]
    pub bottom: Option<f64>,
}

impl Default for WaterlineParams {
    /// No spacing yet; walls of 45 degrees and steeper, adaptive levels down to 15
    /// degrees, climb milling.
    fn default() -> Self {
        WaterlineParams {
            finish: Finish::default(),
            scallop: None,
            level_step: None,
            steep_angle: 45f64.to_radians(),
            flat_angle: 15f64.to_radians(),
            adaptive: true,
            sampling: None,
            direction: Milling::Climb,
            top: None,
            bottom: None,
        }
    }
}

impl WaterlineParams {
    /// Levels for scallop `h` (mm) on walls of 45 degrees and steeper, adaptive down
    /// to 15 degrees, climb milling.
    pub fn new(h: f64) -> WaterlineParams {
        WaterlineParams {
            scallop: Some(h),
            ..WaterlineParams::default()
        }
    }

    /// Checks the parameters for `tool`.
    ///
    /// # Errors
    /// [`PathError::InvalidParameter`] naming the field: a tolerance, scallop, level
    /// step, sampling or angle out of range; neither a scallop nor a level step.
    pub fn validate(&self, tool: &Cutter) -> Result<(), PathError> {
        self.finish.validate()?;
        check_scallop(self.scallop, tool)?;
        in_domain("level_step", self.level_step, STEP)?;
        in_domain("sampling", self.sampling, SAMPLE)?;
        if self.level_step.is_none() {
            require_spacing(self.scallop, None)?;
        }
        check_angles(self)
    }
}

/// One level's loops.
#[derive(Debug, Clone)]
pub struct LevelContour {
    /// Tip height, mm.
    pub z: f64,
    /// Closed loops (first point not repeated), oriented per `direction`.
    pub loops: Vec<Vec<PathPoint>>,
}

/// A mesh prepared for waterline contours of one cutter (borrowing the mesh, or
/// owning it: [`Waterline::owned`]).
pub struct Waterline<'a> {
    mesh: Cow<'a, TriMesh>,
    dropper: MeshDropper,
    field: DropField,
    tolerance: f64,
}

impl<'a> Waterline<'a> {
    /// Drops the cutter on the sampling grid over `mesh`.
    ///
    /// # Errors
    /// [`PathError::NoPath`] for a mesh without finite triangles;
    /// [`PathError::InvalidParameter`] for a sampling that is not positive or makes
    /// too large a grid, or a tolerance that is not positive.
    pub fn new(
        mesh: &'a TriMesh,
        tool: &Cutter,
        params: &WaterlineParams,
    ) -> Result<Waterline<'a>, PathError> {
        Waterline::build(Cow::Borrowed(mesh), tool, params)
    }

    /// As [`Waterline::new`], owning `mesh`: for callers that keep the waterline
    /// longer than they could lend the mesh (the Python layer's objects).
    ///
    /// # Errors
    /// As [`Waterline::new`].
    pub fn owned(
        mesh: TriMesh,
        tool: &Cutter,
        params: &WaterlineParams,
    ) -> Result<Waterline<'static>, PathError> {
        Waterline::build(Cow::Owned(mesh), tool, params)
    }

    fn build(
        mesh: Cow<'a, TriMesh>,
        tool: &Cutter,
        params: &WaterlineParams,
    ) -> Result<Waterline<'a>, PathError> {
        let sampling = params.sampling.unwrap_or(0.25 * tool.radius());
        positive("sampling", sampling)?;
        positive("tolerance", params.finish.tolerance)?;
        let dropper = MeshDropper::new(&mesh, tool);
        if dropper.is_empty() {
            return Err(PathError::NoPath(
                "waterline: the mesh has no triangle with finite corners".into(),
            ));
        }
        let field = DropField::sample(&mesh, &dropper, tool.radius(), sampling)?;
        Ok(Waterline {
            mesh,
            dropper,
            field,
            tolerance: params.finish.tolerance,
        })
    }

    /// The highest drop height over the grid, mm.
    pub fn top(&self) -> f64 {
        self.field.top()
    }

    /// The loops at tip height `z` (mm), each point exactly on the contour (to
    /// [`ROOT_TOL`] in XY), chords within the tolerance at their midpoints.
    pub fn level(&self, z: f64, direction: Milling) -> LevelContour {
        self.finish_level(z, self.raw_level(z), direction)
    }

    fn finish_level(&self, z: f64, loops: Vec<Loop>, direction: Milling) -> LevelContour {
        let loops = loops
            .into_iter()
            .map(|lp| {
                let mut pts: Vec<PathPoint> = lp
                    .iter()
                    .map(|p| drop_point(&self.mesh, p.xy, z, &p.hit))
                    .collect();
                if direction == Milling::Conventional {
                    pts.reverse();
                }
                pts
            })
            .collect();
        LevelContour { z, loops }
    }

    fn raw_level(&self, z: f64) -> Vec<Loop> {
        let probe = Probe {
            dropper: &self.dropper,
            z,
        };
        level_loops(&self.field, &probe, self.tolerance)
    }
}

fn positive(field: &str, v: f64) -> Result<(), PathError> {
    if v.is_finite() && v > 0.0 {
        return Ok(());
    }
    Err(PathError::InvalidParameter {
        field: field.into(),
        message: format!("expected a positive length in mm, found {v}"),
    })
}

/// Plans waterline passes over `mesh` (module doc).
///
/// # Units
/// mm, radians.
///
/// # Errors
/// [`PathError::InvalidParameter`] for angles outside `(0, 90)` degrees or a flat
/// angle not below the steep angle, a scallop outside `(0, tool radius)`, a level
/// step that is not positive or needs more than [`levels::MAX_LEVELS`] levels, and
/// as [`Waterline::new`]; [`PathError::NoPath`] where no level has a loop.
pub fn plan(
    mesh: &TriMesh,
    cutting: &Cutting,
    params: &WaterlineParams,
) -> Result<Plan, PathError> {
    check_angles(params)?;
    let wl = Waterline::new(mesh, &cutting.tool, params)?;
    let top = params.top.unwrap_or_else(|| wl.top());
    let bottom = params.bottom.unwrap_or(mesh.aabb().min.z);
    let contours = schedule(&wl, &cutting.tool, params, top, bottom)?;
    let passes = passes::order(&contours);
    if passes.is_empty() {
        return Err(PathError::NoPath(format!(
            "waterline: no level between {bottom:.3} and {top:.3} mm has a loop"
        )));
    }
    let steps: Vec<f64> = contours.windows(2).map(|w| w[0].z - w[1].z).collect();
    let report = PlanReport {
        predicted_max_scallop: params.scallop.filter(|_| params.level_step.is_none()),
        side_step_range: PlanReport::step_range(&steps),
        ..PlanReport::default()
    };
    Ok(Plan::from_passes(passes, cutting, report, Vec::new()))
}

fn check_angles(params: &WaterlineParams) -> Result<(), PathError> {
    for (field, a) in [
        ("steep_angle", params.steep_angle),
        ("flat_angle", params.flat_angle),
    ] {
        check_open_angle(field, Some(a), "an angle")?;
    }
    if params.flat_angle >= params.steep_angle {
        return Err(PathError::InvalidParameter {
            field: "steep_angle".into(),
            message: format!(
                "{} degrees is not above flat_angle ({} degrees): expected \
                 flat_angle < steep_angle",
                swarf_geom::units::shown_degrees(params.steep_angle),
                swarf_geom::units::shown_degrees(params.flat_angle)
            ),
        });
    }
    Ok(())
}

/// The contours of every level, descending, adaptive levels included.
fn schedule(
    wl: &Waterline,
    tool: &Cutter,
    params: &WaterlineParams,
    top: f64,
    bottom: f64,
) -> Result<Vec<LevelContour>, PathError> {
    let model = match params.scallop {
        Some(h) => Some(SideStep::new(tool, h)?),
        None => None,
    };
    let dz = match (params.level_step, &model) {
        (Some(dz), _) => {
            positive("level_step", dz)?;
            dz
        }
        (None, Some(_)) => zlevel_spacing(tool, params.scallop.unwrap_or(0.0), params.steep_angle)?,
        (None, None) => {
            return Err(PathError::InvalidParameter {
                field: "scallop".into(),
                message: "expected a scallop or a level_step".into(),
            });
        }
    };
    let zs = levels::even_levels(top, bottom, dz)?;
    let mut raw: Vec<(f64, Vec<Loop>)> = zs.iter().map(|&z| (z, wl.raw_level(z))).collect();
    if let (Some(m), true, None) = (&model, params.adaptive, params.level_step) {
        let min_dz = zlevel_spacing(tool, m.h(), params.flat_angle)?.min(dz);
        raw = levels::refine(raw, |z| wl.raw_level(z), m, params.flat_angle, min_dz)?;
    }
    Ok(raw
        .into_iter()
        .map(|(z, loops)| wl.finish_level(z, loops, params.direction))
        .collect())
}
