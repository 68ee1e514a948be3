//! Five-axis positioning of a job's CC paths, as a job file asks for it:
//!
//! ```toml
//! positioning = { method = "inclined", alpha = 3 }                      # thesis §7.3.1
//! positioning = { method = "gouge-free", max_alpha = 15, sections = 1.0 } # thesis §7.3
//! ```
//!
//! Angles in degrees, lengths in mm, at this edge only. Both methods run the sectioning
//! gouge check ([`crate::gouge`]) on planes parallel to the passes' mean direction
//! (`sections` mm apart): the fixed lead reports where it gouges (it is the user's
//! choice, as in the thesis's first experiments), the gouge-free method raises the lead
//! until nothing does ([`crate::autotilt`]) and fails where it cannot. Both report the
//! least lead the design's curvature along the feed allows at the CC points
//! ([`crate::lead_bound`]): no positioning of the tool can use less.
//!
//! The job-file form, [`Positioning`], is plain data ([`spec`]).

use crate::autotilt::{TiltOptions, TiltReport, gouge_free_tilt};
use crate::design::DesignSurface;
use crate::error::FiveAxisError;
use crate::gencurve::CurveOptions;
use crate::gouge::{GougeOptions, check_pass};
use crate::inclined::incline_pass;
use crate::lead_bound::lead_bound;
use crate::sections::Sections;
use rayon::current_num_threads;
use rayon::prelude::*;
use serde::Serialize;
use swarf_geom::Part;
use swarf_tool::ProfileTable;
use swarf_tool::{Cutter, Pose};
use swarf_toolpath::{Contact, Pass};

pub mod spec;

pub use spec::Positioning;

/// Largest number of gouging poses listed in a report (the count is always given).
pub const MAX_LISTED_GOUGES: usize = 100;

/// A gouging pose.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct GougeSpot {
    /// Pass index.
    pub pass: usize,
    /// Point index in the pass.
    pub index: usize,
    /// Depth below the design, mm.
    pub depth: f64,
    /// Where, mm.
    pub at: [f64; 3],
    /// `front` or `back`.
    pub half: &'static str,
}

/// What positioning did.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PositioningReport {
    /// `inclined` or `gouge-free`.
    pub method: &'static str,
    /// Number of poses.
    pub poses: usize,
    /// Smallest and largest lead angle used, degrees.
    pub alpha_range_deg: [f64; 2],
    /// Pass and point of the largest lead.
    pub max_alpha_at: [usize; 2],
    /// Section planes: direction (degrees from X) and spacing (mm).
    pub sections: [f64; 2],
    /// Gouge tolerance, mm.
    pub tolerance: f64,
    /// Poses deeper than the tolerance below the design.
    pub gouging_poses: usize,
    /// The deepest point found, mm (negative: clearance).
    pub worst_depth: f64,
    /// The deepest gouging poses, deepest first (at most [`MAX_LISTED_GOUGES`]).
    pub gouges: Vec<GougeSpot>,
    /// Gouge checks evaluated (gouge-free method).
    pub evaluations: usize,
    /// Of these, with the whole tool and the design's edges.
    pub whole_tool_evaluations: usize,
    /// Poses raised after smoothing (gouge-free method).
    pub raised: usize,
    /// Largest turn of the tool axis per mm of feed, degrees/mm.
    pub max_axis_rate_deg_per_mm: f64,
    /// The least lead any positioning can have on these CC paths from the design's
    /// curvature along the feed, degrees ([`crate::lead_bound`]; 90 where the tool
    /// cannot fit). `None` for a cutter without a torus bottom (cones), with a side
    /// tilt, or without a CC point on a patch.
    pub local_lead_bound_deg: Option<f64>,
    /// The CC point where that bound is reached, mm.
    pub local_lead_bound_at: Option<[f64; 3]>,
    /// The design's concave radius of curvature along the feed there, mm (`None` where
    /// no CC point is concave along the feed).
    pub local_lead_bound_radius: Option<f64>,
    /// CC points where no lead fits (concave radius along the feed below `R + r`).
    pub local_lead_unfit: usize,
}

/// Places the tool on the CC paths `cc` of `part` (module doc). `tolerance` is the
/// job's gouge tolerance (mm), used unless the positioning gives its own.
///
/// # Errors
/// [`FiveAxisError::InvalidParameter`] naming the field for out-of-range values
/// (`positioning.alpha` ...); the errors of [`incline_pass`] and [`gouge_free_tilt`].
pub fn position(
    cutter: &Cutter,
    part: &Part,
    cc: &[Vec<Contact>],
    positioning: &Positioning,
    tolerance: f64,
) -> Result<(Vec<Pass>, PositioningReport), FiveAxisError> {
    position_with_progress(cutter, part, cc, positioning, tolerance, &|_, _| {})
}

/// [`position`], calling `progress(done, total)` as passes are finished (from the
/// calling thread; `total` is the number of passes).
///
/// # Errors
/// As [`position`].
pub fn position_with_progress(
    cutter: &Cutter,
    part: &Part,
    cc: &[Vec<Contact>],
    positioning: &Positioning,
    tolerance: f64,
    progress: &dyn Fn(usize, usize),
) -> Result<(Vec<Pass>, PositioningReport), FiveAxisError> {
    positioning
        .validate()
        .map_err(|(field, message)| FiveAxisError::parameter(field, message))?;
    let design = DesignSurface::new(part)?;
    let angle = mean_direction(cc);
    let (passes, mut report) = match *positioning {
        Positioning::Inclined {
            alpha,
            tilt,
            sections,
        } => {
            let gouge = gouge_options(angle, sections, tolerance)?;
            let passes = cc
                .iter()
                .enumerate()
                .map(|(k, c)| incline_pass(cutter, c, &[alpha.to_radians()], tilt.to_radians(), k))
                .collect::<Result<Vec<_>, _>>()?;
            let mut report = report("inclined", &passes, &gouge, angle);
            report.alpha_range_deg = [alpha, alpha];
            check(&design, cutter, &passes, &gouge, &mut report);
            progress(cc.len(), cc.len());
            (passes, report)
        }
        Positioning::GougeFree {
            max_alpha,
            sections,
            tilt,
            max_rate,
            tolerance: own,
        } => {
            let gouge = gouge_options(angle, sections, own.unwrap_or(tolerance))?;
            let opts = TiltOptions {
                max_alpha: max_alpha.to_radians(),
                tilt: tilt.to_radians(),
                resolution: 0.01f64.to_radians(),
                max_rate: max_rate.to_radians(),
                gouge,
                max_rounds: 50,
            };
            let (passes, t) = tilt_in_chunks(cutter, &design, cc, &opts, progress)?;
            let mut report = report("gouge-free", &passes, &gouge, angle);
            let flat = t.alphas.iter().flatten().copied();
            let lo = flat.clone().fold(f64::INFINITY, f64::min);
            report.alpha_range_deg = [lo.to_degrees(), t.max_alpha.to_degrees()];
            report.max_alpha_at = t.max_alpha_at;
            report.evaluations = t.evaluations;
            report.whole_tool_evaluations = t.whole_tool_evaluations;
            report.raised = t.raised;
            report.max_axis_rate_deg_per_mm = t.max_axis_rate.to_degrees();
            check(&design, cutter, &passes, &gouge, &mut report);
            (passes, report)
        }
    };
    let tilted = match *positioning {
        Positioning::Inclined { tilt, .. } | Positioning::GougeFree { tilt, .. } => tilt != 0.0,
    };
    if !tilted {
        fill_lead_bound(cutter, part, cc, &mut report);
    }
    Ok((passes, report))
}

/// The local lead bound of the CC paths ([`lead_bound`]) into the report.
fn fill_lead_bound(cutter: &Cutter, part: &Part, cc: &[Vec<Contact>], r: &mut PositioningReport) {
    if let Some(b) = lead_bound(cutter, part, cc) {
        r.local_lead_bound_deg = Some(b.lead.to_degrees());
        r.local_lead_bound_at = Some([b.at.x, b.at.y, b.at.z]);
        r.local_lead_bound_radius = b.radius.is_finite().then_some(b.radius);
        r.local_lead_unfit = b.unfit;
    }
}

/// [`gouge_free_tilt`] on chunks of passes (a few per thread, so that progress can
/// be shown), merged in pass order; pass indices in reports and errors are those of
/// `cc`.
fn tilt_in_chunks(
    cutter: &Cutter,
    design: &DesignSurface,
    cc: &[Vec<Contact>],
    opts: &TiltOptions,
    progress: &dyn Fn(usize, usize),
) -> Result<(Vec<Pass>, TiltReport), FiveAxisError> {
    let chunk = 2 * current_num_threads().max(1);
    let mut passes = Vec::with_capacity(cc.len());
    let mut all = TiltReport {
        worst_depth: f64::NEG_INFINITY,
        ..TiltReport::default()
    };
    for (c, part) in cc.chunks(chunk).enumerate() {
        let first = c * chunk;
        let (p, t) = gouge_free_tilt(cutter, design, part, opts).map_err(|e| offset(e, first))?;
        if t.max_alpha > all.max_alpha || passes.is_empty() {
            all.max_alpha = t.max_alpha;
            all.max_alpha_at = [t.max_alpha_at[0] + first, t.max_alpha_at[1]];
        }
        all.evaluations += t.evaluations;
        all.whole_tool_evaluations += t.whole_tool_evaluations;
        all.raised += t.raised;
        all.worst_depth = all.worst_depth.max(t.worst_depth);
        all.max_axis_rate = all.max_axis_rate.max(t.max_axis_rate);
        all.searched.extend(t.searched);
        all.alphas.extend(t.alphas);
        passes.extend(p);
        progress(passes.len(), cc.len());
    }
    Ok((passes, all))
}

/// `e` with its pass index moved by `first` (a chunk's errors count from its start).
fn offset(e: FiveAxisError, first: usize) -> FiveAxisError {
    match e {
        FiveAxisError::Positioning {
            pass,
            index,
            message,
        } => FiveAxisError::Positioning {
            pass: pass + first,
            index,
            message,
        },
        FiveAxisError::NoGougeFreeTilt {
            pass,
            index,
            cc,
            max_alpha_deg,
            depth,
            at,
            half,
        } => FiveAxisError::NoGougeFreeTilt {
            pass: pass + first,
            index,
            cc,
            max_alpha_deg,
            depth,
            at,
            half,
        },
        FiveAxisError::Unreachable {
            pass,
            index,
            axis,
            message,
        } => FiveAxisError::Unreachable {
            pass: pass + first,
            index,
            axis,
            message,
        },
        FiveAxisError::InvalidParameter { field, message } if field.starts_with("pass ") => {
            let k = field[5..]
                .parse::<usize>()
                .map_or(field.clone(), |k| format!("pass {}", k + first));
            FiveAxisError::InvalidParameter { field: k, message }
        }
        other => other,
    }
}

fn gouge_options(angle: f64, spacing: f64, tolerance: f64) -> Result<GougeOptions, FiveAxisError> {
    if !(tolerance.is_finite() && tolerance >= 0.0) {
        return Err(FiveAxisError::parameter(
            "positioning.tolerance",
            format!("expected a tolerance >= 0 mm, found {tolerance}"),
        ));
    }
    let sections = Sections::along(angle, spacing).map_err(|_| {
        FiveAxisError::parameter(
            "positioning.sections",
            format!("expected a section spacing > 0 mm, found {spacing}"),
        )
    })?;
    Ok(GougeOptions {
        sections,
        tolerance,
        curve: CurveOptions::default(),
        cap_meridians: 96,
        whole_tool: false,
    })
}

fn report(
    method: &'static str,
    passes: &[Pass],
    g: &GougeOptions,
    angle: f64,
) -> PositioningReport {
    PositioningReport {
        method,
        poses: passes.iter().map(|p| p.points.len()).sum(),
        alpha_range_deg: [0.0, 0.0],
        max_alpha_at: [0, 0],
        sections: [angle.to_degrees(), g.sections.spacing],
        tolerance: g.tolerance,
        gouging_poses: 0,
        worst_depth: f64::NEG_INFINITY,
        gouges: Vec::new(),
        evaluations: 0,
        whole_tool_evaluations: 0,
        raised: 0,
        max_axis_rate_deg_per_mm: max_axis_rate(passes).to_degrees(),
        local_lead_bound_deg: None,
        local_lead_bound_at: None,
        local_lead_bound_radius: None,
        local_lead_unfit: 0,
    }
}

/// The sectioning check of every pose (passes in parallel), into the report.
fn check(
    design: &DesignSurface,
    cutter: &Cutter,
    passes: &[Pass],
    g: &GougeOptions,
    r: &mut PositioningReport,
) {
    let profile = cutter.profile();
    let table = ProfileTable::new(&profile);
    let g = &GougeOptions {
        whole_tool: true,
        ..*g
    };
    let checked: Vec<_> = passes
        .par_iter()
        .map(|pass| {
            let poses: Vec<Pose> = pass.points.iter().map(|p| p.pose).collect();
            check_pass(design, &table, &poses, g)
        })
        .collect();
    let mut spots = Vec::new();
    for (k, pass) in checked.into_iter().enumerate() {
        for (i, pg) in pass.into_iter().enumerate() {
            r.worst_depth = r.worst_depth.max(pg.depth);
            if pg.gouges(g.tolerance) {
                spots.push(GougeSpot {
                    pass: k,
                    index: i,
                    depth: pg.depth,
                    at: [pg.at.x, pg.at.y, pg.at.z],
                    half: pg.half.name(),
                });
            }
        }
    }
    r.gouging_poses = spots.len();
    spots.sort_by(|a, b| b.depth.total_cmp(&a.depth));
    spots.truncate(MAX_LISTED_GOUGES);
    r.gouges = spots;
}

/// The sectioning check of `passes` (positioned with `cutter` on `part`) run again
/// after their axes changed (holder avoidance tilts them): the report's gouges,
/// worst depth and axis rate replaced, on its own section planes and tolerance.
///
/// # Errors
/// A part the design surface cannot be built from; a report whose sections or
/// tolerance are out of their domains.
pub fn recheck(
    cutter: &Cutter,
    part: &Part,
    passes: &[Pass],
    r: &mut PositioningReport,
) -> Result<(), FiveAxisError> {
    let design = DesignSurface::new(part)?;
    let g = gouge_options(r.sections[0].to_radians(), r.sections[1], r.tolerance)?;
    r.worst_depth = f64::NEG_INFINITY;
    r.max_axis_rate_deg_per_mm = max_axis_rate(passes).to_degrees();
    check(&design, cutter, passes, &g, r);
    Ok(())
}

/// Largest angle between consecutive tool axes per mm of tip travel, rad/mm.
fn max_axis_rate(passes: &[Pass]) -> f64 {
    passes
        .iter()
        .flat_map(|p| p.points.windows(2))
        .map(|w| {
            let ds = (w[1].pose.cl - w[0].pose.cl).norm();
            let da = w[0].pose.axis.angle(&w[1].pose.axis);
            if ds > 1e-6 { da / ds } else { 0.0 }
        })
        .fold(0.0, f64::max)
}

/// The mean XY direction of the passes (radians from X, modulo pi), weighted by
/// length: the angle of the summed doubled-angle vectors, halved.
pub fn mean_direction(cc: &[Vec<Contact>]) -> f64 {
    let (mut c, mut s) = (0.0, 0.0);
    for pass in cc {
        if let (Some(a), Some(b)) = (pass.first(), pass.last()) {
            let d = (b.point - a.point).xy();
            let len = d.norm();
            if len > 0.0 {
                let t = d.y.atan2(d.x);
                c += len * (2.0 * t).cos();
                s += len * (2.0 * t).sin();
            }
        }
    }
    0.5 * s.atan2(c)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn chunk_errors_count_passes_from_the_start() {
        let e = FiveAxisError::NoGougeFreeTilt {
            pass: 1,
            index: 7,
            cc: [1.0, 2.0, 3.0],
            max_alpha_deg: 2.0,
            depth: 0.5,
            at: [0.0; 3],
            half: "back",
        };
        let moved = offset(e, 8).to_string();
        assert!(
            moved.starts_with("pass 9, point 7 (CC [1.0, 2.0, 3.0])"),
            "{moved}"
        );
        let short = FiveAxisError::parameter("pass 2", "a pass needs two points");
        assert_eq!(
            offset(short, 4).to_string(),
            "pass 6: a pass needs two points"
        );
        let other = FiveAxisError::parameter("positioning.alpha", "bad");
        assert_eq!(offset(other.clone(), 4), other);
    }

    #[test]
    fn mean_direction_ignores_pass_orientation() {
        let c = |x: f64, y: f64| Contact {
            point: swarf_geom::Point3::new(x, y, 0.0),
            normal: swarf_geom::Vec3::z(),
            face: 0,
            uv: [0.0; 2],
        };
        let (s, co) = 60f64.to_radians().sin_cos();
        let passes = vec![
            vec![c(0.0, 0.0), c(10.0 * co, 10.0 * s)],
            vec![c(10.0 * co, 10.0 * s + 3.0), c(0.0, 3.0)],
        ];
        assert!((mean_direction(&passes) - 60f64.to_radians()).abs() < 1e-12);
    }
}
