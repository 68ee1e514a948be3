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
//! see [`crate::gouge`]). The search tests alpha = 0,
//! then brackets the answer upward from a hint (the previous point's answer, the path
//! being smooth) by doubling steps, and bisects the bracket `[lo, hi]` (`lo` gouging,
//! `hi` gouge-free) down to `resolution`; it returns `hi`, so the answer is always an
//! alpha that was checked gouge-free. Monotonicity: for the inclined tool the back of
//! the tool rises by about `2 R sin(alpha)` as alpha grows and the front contact stays
//! put, so the gouge depth falls with alpha, but a side gouge or a contact jumping
//! between profile segments can break this. The bisection needs the predicate to change
//! once inside the final bracket only; a pose where a larger alpha gouges again is
//! caught by the final check below and raised. The tests compare the result with a
//! brute-force sweep of alpha on sampled poses.
//!
//! **Smoothing.** Each searched alpha other than 0 gets a margin of 0.05 degree (the
//! check below sees the real neighbours, which smoothing moves). Rotary axes should not
//! jerk: alpha may change by at most `max_rate` per mm of CC travel. The smallest such sequence above the searched one is its upper
//! envelope `alpha_s(i) = max_j (alpha_j - max_rate |s_i - s_j|)` (a forward and a
//! backward sweep). It only raises alpha.
//!
//! **Check.** With the smoothed alphas every pose is checked with its real neighbours
//! and with its whole tool ([`crate::gouge`]: the generating curves miss the patch of
//! the tool where the motion turns);
//! a pose that gouges is raised by the same search starting at its current alpha (its
//! neighbours held), the pass is smoothed again, and the check repeats (at most
//! `max_rounds` times). A pose that no alpha up to `max_alpha` clears is an error naming
//! the pass, the point, the CC point and the remaining depth: no gouging pose is ever
//! returned.

use crate::design::DesignSurface;
use crate::error::FiveAxisError;
use crate::gouge::{GougeOptions, PoseGouge, pose_gouge};
use crate::inclined::{Inclination, feed_directions, inclined_pose};
use crate::profile_point::ProfileTable;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use swarf_geom::Vec3;
use swarf_path::{Contact, Pass, PathPoint};
use swarf_tool::{Cutter, Pose, Profile};

/// The first upward step of the bracket search when there is no hint (radians, 1
/// degree).
const FIRST_STEP: f64 = 0.017_453_292_519_943_295;

/// The first upward step from a nonzero start (radians, 0.05 degree).
const SMALL_STEP: f64 = 0.000_872_664_625_997_164_8;

/// Below a free upper end the search probes this much lower first, where the answer
/// usually is when the hint was good (radians, 0.25 degree).
const NEAR: f64 = 0.004_363_323_129_985_824;

/// Searched alphas (when not 0) and poses raised after smoothing get this much more
/// than the alpha that clears them: smoothing moves the neighbours, and with them the
/// motion that the generating curves follow (radians, 0.05 degree).
const RAISE_MARGIN: f64 = 0.000_872_664_625_997_164_8;

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

/// Where the neighbours of a checked pose come from.
#[derive(Clone, Copy)]
enum Neighbours<'p> {
    /// Placed at the same alpha as the pose (the search before smoothing).
    SameAlpha,
    /// The poses of the pass as they are (the check after smoothing).
    Fixed(&'p [Pose]),
}

/// One pass being tilted.
struct PassTilt<'a> {
    profile: &'a Profile,
    table: &'a ProfileTable<'a>,
    design: &'a DesignSurface,
    contacts: &'a [Contact],
    feeds: Vec<Vec3>,
    opts: &'a TiltOptions,
    pass: usize,
    evaluations: usize,
    whole_tool_evaluations: usize,
    /// Check the whole tool at every pose (the final check and its raises).
    strict: bool,
}

impl PassTilt<'_> {
    fn pose(&self, i: usize, alpha: f64) -> Result<Pose, FiveAxisError> {
        let incl = Inclination {
            lead: alpha,
            tilt: self.opts.tilt,
        };
        inclined_pose(self.profile, &self.contacts[i], &self.feeds[i], incl).ok_or_else(|| {
            FiveAxisError::Positioning {
                pass: self.pass,
                index: i,
                message: "cannot place the tool tangent at this contact (feed parallel to the \
                          normal, or a normal facing the top of the tool)"
                    .into(),
            }
        })
    }

    /// The check of pose `i` at `alpha` with its neighbours.
    fn check(
        &mut self,
        i: usize,
        alpha: f64,
        nb: Neighbours<'_>,
    ) -> Result<PoseGouge, FiveAxisError> {
        self.evaluations += 1;
        self.whole_tool_evaluations += usize::from(self.strict);
        let lo = i.saturating_sub(1);
        let hi = (i + 1).min(self.contacts.len() - 1);
        let mut poses = Vec::with_capacity(3);
        for j in lo..=hi {
            poses.push(match nb {
                _ if j == i => self.pose(i, alpha)?,
                Neighbours::SameAlpha => self.pose(j, alpha)?,
                Neighbours::Fixed(p) => p[j],
            });
        }
        let mut g = self.opts.gouge;
        g.whole_tool |= self.strict;
        Ok(pose_gouge(self.design, self.table, &poses, i - lo, &g))
    }

    /// Smallest gouge-free alpha at `i` not below `start` (module doc, search).
    fn search(
        &mut self,
        i: usize,
        start: f64,
        hint: f64,
        nb: Neighbours<'_>,
    ) -> Result<f64, FiveAxisError> {
        let tol = self.opts.gouge.tolerance;
        let max = self.opts.max_alpha;
        if !self.check(i, start, nb)?.gouges(tol) {
            return Ok(start);
        }
        // Upward from a known answer (the whole-tool stage, a raise) the gap is usually
        // small: start with small steps there.
        let first = if start > 0.0 { SMALL_STEP } else { FIRST_STEP };
        let (mut lo, mut step) = (start, first.min(max - start).max(self.opts.resolution));
        let mut hi = if hint > start {
            hint.min(max)
        } else {
            (start + step).min(max)
        };
        loop {
            let g = self.check(i, hi, nb)?;
            if !g.gouges(tol) {
                break;
            }
            if hi >= max {
                return Err(self.no_tilt(i, &g));
            }
            lo = hi;
            hi = (hi + step).min(max);
            step *= 2.0;
        }
        let probe = hi - NEAR;
        if probe > lo + self.opts.resolution {
            if self.check(i, probe, nb)?.gouges(tol) {
                lo = probe;
            } else {
                hi = probe;
            }
        }
        while hi - lo > self.opts.resolution {
            let mid = 0.5 * (lo + hi);
            if self.check(i, mid, nb)?.gouges(tol) {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        Ok(hi)
    }

    fn no_tilt(&self, i: usize, g: &PoseGouge) -> FiveAxisError {
        let cc = self.contacts[i].point;
        FiveAxisError::NoGougeFreeTilt {
            pass: self.pass,
            index: i,
            cc: [cc.x, cc.y, cc.z],
            max_alpha_deg: self.opts.max_alpha.to_degrees(),
            depth: g.depth,
            at: [g.at.x, g.at.y, g.at.z],
            half: g.half.name(),
        }
    }

    /// Arc length of the CC path at each point, mm.
    fn stations(&self) -> Vec<f64> {
        let mut s = vec![0.0; self.contacts.len()];
        for i in 1..s.len() {
            s[i] = s[i - 1] + (self.contacts[i].point - self.contacts[i - 1].point).norm();
        }
        s
    }
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

/// Tilts one pass (module doc: search, smoothing, check).
fn tilt_pass(t: &mut PassTilt<'_>) -> Result<PassResult, FiveAxisError> {
    let n = t.contacts.len();
    let mut searched = Vec::with_capacity(n);
    let mut hint = 0.0;
    for i in 0..n {
        // The generating curves first (cheap), then up from there with the whole tool.
        let a = t.search(i, 0.0, hint, Neighbours::SameAlpha)?;
        t.strict = true;
        let a = t.search(i, a, a, Neighbours::SameAlpha);
        t.strict = false;
        let a = a?;
        searched.push(a);
        hint = a;
    }
    let s = t.stations();
    let mut alphas: Vec<f64> = searched
        .iter()
        .map(|a| {
            if *a > 0.0 {
                (a + RAISE_MARGIN).min(t.opts.max_alpha)
            } else {
                0.0
            }
        })
        .collect();
    smooth(&mut alphas, &s, t.opts.max_rate);
    let mut depth = vec![f64::NEG_INFINITY; n];
    let mut dirty = vec![true; n];
    let mut raised = 0;
    t.strict = true;
    let mut strict = t.opts.gouge;
    strict.whole_tool = true;
    for _ in 0..t.opts.max_rounds.max(1) {
        let poses = alphas
            .iter()
            .enumerate()
            .map(|(i, &a)| t.pose(i, a))
            .collect::<Result<Vec<_>, _>>()?;
        let before = alphas.clone();
        for i in (0..n).filter(|&i| dirty[i]) {
            let g = pose_gouge(t.design, t.table, &poses, i, &strict);
            t.evaluations += 1;
            t.whole_tool_evaluations += 1;
            depth[i] = g.depth;
            if g.gouges(t.opts.gouge.tolerance) {
                let a = t.search(i, alphas[i], alphas[i], Neighbours::Fixed(&poses))?;
                alphas[i] = (a + RAISE_MARGIN).min(t.opts.max_alpha);
                raised += 1;
            }
        }
        smooth(&mut alphas, &s, t.opts.max_rate);
        dirty.iter_mut().for_each(|d| *d = false);
        let mut changed = false;
        for i in (0..n).filter(|&i| alphas[i] != before[i]) {
            changed = true;
            dirty[i.saturating_sub(1)..=(i + 1).min(n - 1)].fill(true);
        }
        if !changed {
            let worst = depth.iter().copied().fold(f64::NEG_INFINITY, f64::max);
            return Ok(PassResult {
                poses,
                searched,
                alphas,
                raised,
                worst,
            });
        }
    }
    Err(FiveAxisError::Positioning {
        pass: t.pass,
        index: 0,
        message: format!(
            "the gouge-free tilt did not settle after {} rounds of smoothing and raising",
            t.opts.max_rounds
        ),
    })
}

/// What [`tilt_pass`] gives for one pass.
struct PassResult {
    poses: Vec<Pose>,
    searched: Vec<f64>,
    alphas: Vec<f64>,
    raised: usize,
    worst: f64,
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
    use crate::drive::{DrivePlanes, drive_plane_passes};
    use crate::gencurve::CurveOptions;
    use crate::sections::Sections;
    use swarf_geom::Point3;

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

    fn opts(max_alpha_deg: f64) -> TiltOptions {
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

    /// Three passes through the middle of the die, 60 degrees off X, 2 mm steps.
    fn die_passes(design: &DesignSurface) -> Vec<Vec<Contact>> {
        let part = die();
        let dp = DrivePlanes {
            angle: 60f64.to_radians(),
            cross_feed: 3.5,
            step: 2.0,
            zigzag: true,
        };
        let all = drive_plane_passes(design, &part.control_box(), &dp).unwrap();
        let mid = all.len() / 2;
        all[mid - 1..=mid + 1].to_vec()
    }

    #[test]
    fn too_small_a_max_alpha_is_an_error_naming_the_point() {
        let design = DesignSurface::new(&die());
        let passes = die_passes(&design);
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

    /// Deepest point of the design above the tool at `pose`, over a dense grid of the
    /// tool's lower surface (independent of generating curves and sections).
    fn brute_depth(design: &DesignSurface, profile: &Profile, pose: &Pose) -> f64 {
        let mut worst = f64::NEG_INFINITY;
        for m in 0..720 {
            let phi = std::f64::consts::TAU * m as f64 / 720.0;
            for j in 0..=60 {
                let (p, _) = profile.surface_point(pose, 0.15 * j as f64 / 60.0, phi);
                if let Some((z, _)) = design.height(p.x, p.y) {
                    worst = worst.max(z - p.z);
                }
            }
        }
        worst
    }

    #[test]
    fn searched_alpha_is_within_a_tenth_of_a_degree_of_brute_force() {
        let design = DesignSurface::new(&die());
        let passes = die_passes(&design);
        let cutter: Cutter = "bull:d=38.1,r=6.35".parse().unwrap();
        let profile = cutter.profile();
        let o = opts(25.0);
        let (out, report) = gouge_free_tilt(&cutter, &design, &passes, &o).unwrap();
        assert!(report.worst_depth <= o.gouge.tolerance);
        assert_eq!(out.len(), passes.len());
        let tenth = 0.1f64.to_radians();
        let contacts = &passes[1];
        let points: Vec<Point3> = contacts.iter().map(|c| c.point).collect();
        let feeds = crate::inclined::feed_directions(&points).unwrap();
        let at = |i: usize, a: f64| -> Pose {
            inclined_pose(&profile, &contacts[i], &feeds[i], Inclination::lead(a)).unwrap()
        };
        let n = contacts.len();
        let table = ProfileTable::new(&profile);
        let mut pt = PassTilt {
            profile: &profile,
            table: &table,
            design: &design,
            contacts,
            feeds: feeds.clone(),
            opts: &o,
            pass: 1,
            evaluations: 0,
            whole_tool_evaluations: 0,
            strict: false,
        };
        let mut checked = 0;
        for i in [n / 5, n / 3, n / 2, 2 * n / 3, 4 * n / 5] {
            let a = report.searched[1][i];
            // Monotone at a quarter-degree scale: every smaller alpha gouges.
            let mut b = 0.0;
            while b < a - o.resolution {
                let g = pt.check(i, b, Neighbours::SameAlpha).unwrap();
                assert!(g.gouges(o.gouge.tolerance), "point {i}: {b} free below {a}");
                b += 0.25f64.to_radians();
            }
            // A tenth of a degree above the answer the tool is gouge-free by a dense
            // independent check; a tenth below it, it gouges (or the answer is 0).
            assert!(
                brute_depth(&design, &profile, &at(i, a + tenth)) <= o.gouge.tolerance,
                "point {i}"
            );
            if a > tenth {
                assert!(
                    brute_depth(&design, &profile, &at(i, a - tenth)) > o.gouge.tolerance,
                    "point {i}"
                );
                checked += 1;
            }
        }
        assert!(checked >= 3, "only {checked} poses needed a tilt");
    }
}
