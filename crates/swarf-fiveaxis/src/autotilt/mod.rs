//! Automatic gouge-free tilt (thesis 000 §7.3): at every CC point the smallest lead
//! angle in `[0, max_alpha]` whose tool is gouge-free within the tolerance by the
//! sectioning check, then smoothed along the pass and checked again.
//!
//! **Search.** The thesis starts from `alpha = 0` (most material removed, smallest
//! scallop) and increases alpha "progressively" until the gouge disappears. Here the
//! predicate `gouges(alpha)` is the sectioning check ([`crate::gouge::pose_gouge`]) of
//! the pose with its two neighbours placed at the same alpha (the motion at a pose
//! depends on its neighbours, which are not known yet): first with the generating
//! curves alone, then, from that answer upward, with the whole tool and the design's
//! edges as well (a few more checks, ten times dearer, that the curves cannot replace:
//! see [`crate::gouge`]). The search tests alpha = 0, then brackets the answer upward
//! from a hint (the previous point's answer, the path being smooth) by doubling steps,
//! and bisects the bracket `[lo, hi]` (`lo` gouging, `hi` gouge-free) down to
//! `resolution`; it returns `hi`, so the answer is always an alpha that was checked
//! gouge-free. Monotonicity: for the inclined tool the back of the tool rises by about
//! `2 R sin(alpha)` as alpha grows and the front contact stays put, so the gouge depth
//! falls with alpha; but a side gouge, the front dipping onto a rising edge of the
//! design, or a contact jumping between profile segments can break this. The bisection
//! needs the predicate to change once inside the final bracket only; a pose where a
//! larger alpha gouges again is caught by the final check below and raised. The tests
//! sweep alpha on sampled poses at a quarter-degree scale (every smaller alpha gouges)
//! and check the answer against a dense independent check a tenth of a degree either
//! side.
//!
//! **Smoothing.** Each searched alpha other than 0 gets a margin of 0.05 degree (the
//! check below sees the real neighbours, which smoothing moves). Rotary axes should not
//! jerk: alpha may change by at most `max_rate` per mm of CC travel. The smallest such
//! sequence above the searched one is its upper envelope
//! `alpha_s(i) = max_j (alpha_j - max_rate |s_i - s_j|)` (a forward and a backward
//! sweep). It only raises alpha.
//!
//! **Check.** With the smoothed alphas every pose is checked with its real neighbours
//! and with its whole tool ([`crate::gouge`]: the generating curves miss the patch of
//! the tool where the motion turns); a pose that gouges is raised by the same search
//! starting at its current alpha (its neighbours held), the pass is smoothed again, and
//! the poses whose alpha or neighbours changed are checked again (at most `max_rounds`
//! times). A pose that no alpha up to `max_alpha` clears is an error naming
//! the pass, the point, the CC point and the remaining depth: no gouging pose is ever
//! returned.

mod pass;

use crate::design::DesignSurface;
use crate::error::FiveAxisError;
use crate::gouge::GougeOptions;
use crate::inclined::feed_directions;
use pass::{PassResult, PassTilt, tilt_pass};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use swarf_tool::ProfileTable;
use swarf_tool::{Cutter, Pose};
use swarf_toolpath::{Contact, Pass, PathPoint};

/// Options of the automatic tilt.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct TiltOptions {
    /// Largest lead angle allowed, radians.
    pub max_alpha: f64,
    /// Fixed tilt (side) angle, radians.
    pub tilt: f64,
    /// Bisection stops when the bracket is this narrow, radians.
    pub resolution: f64,
    /// Largest change of alpha per mm of CC travel after smoothing, radians/mm.
    pub max_rate: f64,
    /// The sectioning check.
    pub gouge: GougeOptions,
    /// Most check-and-raise rounds after smoothing.
    pub max_rounds: usize,
}

/// What the automatic tilt did.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct TiltReport {
    /// Smallest gouge-free alpha found per pass and point (before smoothing), radians.
    pub searched: Vec<Vec<f64>>,
    /// Final alpha per pass and point, radians.
    pub alphas: Vec<Vec<f64>>,
    /// The largest final alpha, radians, and where (pass, point).
    pub max_alpha: f64,
    /// Pass and point of the largest final alpha.
    pub max_alpha_at: [usize; 2],
    /// Gouge predicate evaluations.
    pub evaluations: usize,
    /// Of these, the ones with the whole tool and the design's edges.
    pub whole_tool_evaluations: usize,
    /// Poses raised by the check after smoothing.
    pub raised: usize,
    /// Deepest point of the final check, mm (at most the tolerance).
    pub worst_depth: f64,
    /// Largest change of the tool axis per mm of CC travel in the result, rad/mm.
    pub max_axis_rate: f64,
}

/// Raises `alphas` to their smallest upper envelope with slope `rate` in `s`.
pub fn smooth(alphas: &mut [f64], s: &[f64], rate: f64) {
    for i in 1..alphas.len() {
        alphas[i] = alphas[i].max(alphas[i - 1] - rate * (s[i] - s[i - 1]));
    }
    for i in (0..alphas.len().saturating_sub(1)).rev() {
        alphas[i] = alphas[i].max(alphas[i + 1] - rate * (s[i + 1] - s[i]));
    }
}

/// Tilts every pass (module doc). Passes run in parallel; results are in pass order.
///
/// # Errors
/// [`FiveAxisError::NoGougeFreeTilt`] for the first pass (in order) with a point that no
/// lead angle up to `max_alpha` clears; [`FiveAxisError::Positioning`] where the tool
/// cannot be placed or the check did not settle; [`FiveAxisError::InvalidParameter`]
/// for out-of-range options or a pass of fewer than two points.
pub fn gouge_free_tilt(
    cutter: &Cutter,
    design: &DesignSurface,
    passes: &[Vec<Contact>],
    opts: &TiltOptions,
) -> Result<(Vec<Pass>, TiltReport), FiveAxisError> {
    check_options(opts)?;
    let profile = cutter.profile();
    let table = ProfileTable::new(&profile);
    let results: Vec<_> = passes
        .par_iter()
        .enumerate()
        .map(|(pass, contacts)| {
            let points: Vec<_> = contacts.iter().map(|c| c.point).collect();
            let feeds = feed_directions(&points).ok_or_else(|| {
                FiveAxisError::parameter(
                    format!("pass {pass}"),
                    "a pass needs at least two contact points to give a feed direction",
                )
            })?;
            let mut t = PassTilt {
                profile: &profile,
                table: &table,
                design,
                contacts,
                feeds,
                opts,
                pass,
                evaluations: 0,
                whole_tool_evaluations: 0,
                strict: false,
            };
            let r = tilt_pass(&mut t)?;
            Ok((r, [t.evaluations, t.whole_tool_evaluations]))
        })
        .collect::<Result<Vec<_>, FiveAxisError>>()?;
    let mut report = TiltReport {
        worst_depth: f64::NEG_INFINITY,
        ..TiltReport::default()
    };
    let mut out = Vec::with_capacity(passes.len());
    for (k, (r, evals)) in results.into_iter().enumerate() {
        let PassResult {
            poses,
            searched,
            alphas,
            raised,
            worst,
        } = r;
        report.evaluations += evals[0];
        report.whole_tool_evaluations += evals[1];
        report.raised += raised;
        report.worst_depth = report.worst_depth.max(worst);
        for (i, a) in alphas.iter().enumerate() {
            if *a > report.max_alpha {
                report.max_alpha = *a;
                report.max_alpha_at = [k, i];
            }
        }
        report.max_axis_rate = report.max_axis_rate.max(axis_rate(&poses, &passes[k]));
        report.searched.push(searched);
        report.alphas.push(alphas);
        out.push(Pass {
            points: poses
                .into_iter()
                .zip(&passes[k])
                .map(|(pose, c)| PathPoint {
                    pose,
                    contact: Some(*c),
                    lifted: 0.0,
                })
                .collect(),
            ..Pass::default()
        });
    }
    Ok((out, report))
}

/// Largest angle between consecutive tool axes per mm of CC travel, rad/mm.
fn axis_rate(poses: &[Pose], contacts: &[Contact]) -> f64 {
    poses
        .windows(2)
        .zip(contacts.windows(2))
        .map(|(p, c)| {
            let ds = (c[1].point - c[0].point).norm();
            let da = p[0].axis.dot(&p[1].axis).clamp(-1.0, 1.0).acos();
            if ds > 0.0 { da / ds } else { 0.0 }
        })
        .fold(0.0, f64::max)
}

fn check_options(o: &TiltOptions) -> Result<(), FiveAxisError> {
    let bad = |field: &str, msg: String| Err(FiveAxisError::parameter(field, msg));
    if !(o.max_alpha.is_finite() && o.max_alpha > 0.0 && o.max_alpha < std::f64::consts::FRAC_PI_2)
    {
        return bad(
            "positioning.max_alpha",
            format!(
                "expected 0 < max_alpha < 90 degrees, found {}",
                o.max_alpha.to_degrees()
            ),
        );
    }
    if !(o.resolution.is_finite() && o.resolution > 0.0) {
        return bad(
            "positioning.resolution",
            format!("expected > 0, found {}", o.resolution),
        );
    }
    if !(o.max_rate.is_finite() && o.max_rate > 0.0) {
        return bad(
            "positioning.max_rate",
            format!(
                "expected a rate > 0 degrees per mm, found {}",
                o.max_rate.to_degrees()
            ),
        );
    }
    if !(o.gouge.tolerance.is_finite() && o.gouge.tolerance >= 0.0) {
        return bad(
            "positioning.tolerance",
            format!("expected a tolerance >= 0 mm, found {}", o.gouge.tolerance),
        );
    }
    if !o.tilt.is_finite() {
        return bad("positioning.tilt", "expected a finite angle".into());
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::design::tests::die;
    use crate::gencurve::CurveOptions;
    use crate::sections::Sections;
    use swarf_path::Cutting;
    use swarf_path::strategy::iso::planar::IsoPlanarParams;

    #[test]
    fn smoothing_is_the_least_envelope_within_the_rate() {
        let s: Vec<f64> = (0..7).map(|i| i as f64).collect();
        let mut a = vec![0.0, 0.0, 1.0, 0.0, 0.0, 0.2, 0.0];
        smooth(&mut a, &s, 0.25);
        let expected = [0.5, 0.75, 1.0, 0.75, 0.5, 0.25, 0.0];
        for (x, e) in a.iter().zip(expected) {
            assert!((x - e).abs() < 1e-15, "{a:?}");
        }
    }

    pub(super) fn opts(max_alpha_deg: f64) -> TiltOptions {
        TiltOptions {
            max_alpha: max_alpha_deg.to_radians(),
            tilt: 0.0,
            resolution: 0.01f64.to_radians(),
            max_rate: 0.5f64.to_radians(),
            gouge: GougeOptions {
                sections: Sections::along(60f64.to_radians(), 1.0).unwrap(),
                tolerance: 0.01,
                curve: CurveOptions::default(),
                cap_meridians: 96,
                whole_tool: false,
            },
            max_rounds: 50,
        }
    }

    /// Three passes through the middle of the die: iso-planar, 60 degrees off X,
    /// cross feed 3.5 mm, steps of about 2 mm (chordal tolerance 0.005 mm).
    pub(super) fn die_passes() -> Vec<Vec<Contact>> {
        let cut = Cutting::new("bull:d=38.1,r=6.35".parse().unwrap());
        let mut params = IsoPlanarParams {
            stepover: Some(3.5),
            angle: 60f64.to_radians(),
            ..IsoPlanarParams::default()
        };
        params.finish.tolerance = 0.005;
        let plan = swarf_path::strategy::iso::planar::plan(&die(), &cut, &params).unwrap();
        let all = crate::cc_paths::cc_paths(&plan.toolpath);
        let mid = all.len() / 2;
        all[mid - 1..=mid + 1].to_vec()
    }

    #[test]
    fn too_small_a_max_alpha_is_an_error_naming_the_point() {
        let design = DesignSurface::new(&die()).unwrap();
        let passes = die_passes();
        let cutter: Cutter = "bull:d=38.1,r=6.35".parse().unwrap();
        let e = gouge_free_tilt(&cutter, &design, &passes[..1], &opts(2.0)).unwrap_err();
        match &e {
            FiveAxisError::NoGougeFreeTilt { pass, depth, .. } => {
                assert_eq!(*pass, 0);
                assert!(*depth > 0.01);
            }
            other => panic!("{other}"),
        }
        assert!(e.to_string().contains("max_alpha = 2"), "{e}");
        let mut bad = opts(10.0);
        bad.max_rate = 0.0;
        assert!(gouge_free_tilt(&cutter, &design, &passes, &bad).is_err());
    }
}
