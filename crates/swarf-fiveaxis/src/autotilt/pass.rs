//! One pass of the automatic tilt: the gouge predicate of a pose with its neighbours,
//! the bracketing and bisection search, and the check-and-raise rounds after smoothing
//! (the module doc of [`super`] gives the method).

use super::{TiltOptions, smooth};
use crate::design::DesignSurface;
use crate::error::FiveAxisError;
use crate::gouge::{PoseGouge, pose_gouge};
use crate::inclined::{Inclination, inclined_pose};
use swarf_geom::Vec3;
use swarf_tool::ProfileTable;
use swarf_tool::{Pose, Profile};
use swarf_toolpath::Contact;

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

/// Where the neighbours of a checked pose come from.
#[derive(Clone, Copy)]
enum Neighbours<'p> {
    /// Placed at the same alpha as the pose (the search before smoothing).
    SameAlpha,
    /// The poses of the pass as they are (the check after smoothing).
    Fixed(&'p [Pose]),
}

/// One pass being tilted.
pub(super) struct PassTilt<'a> {
    pub(super) profile: &'a Profile,
    pub(super) table: &'a ProfileTable<'a>,
    pub(super) design: &'a DesignSurface,
    pub(super) contacts: &'a [Contact],
    pub(super) feeds: Vec<Vec3>,
    pub(super) opts: &'a TiltOptions,
    pub(super) pass: usize,
    pub(super) evaluations: usize,
    pub(super) whole_tool_evaluations: usize,
    /// Check the whole tool at every pose (the final check and its raises).
    pub(super) strict: bool,
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

/// Tilts one pass (module doc: search, smoothing, check).
pub(super) fn tilt_pass(t: &mut PassTilt<'_>) -> Result<PassResult, FiveAxisError> {
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
pub(super) struct PassResult {
    pub(super) poses: Vec<Pose>,
    pub(super) searched: Vec<f64>,
    pub(super) alphas: Vec<f64>,
    pub(super) raised: usize,
    pub(super) worst: f64,
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::autotilt::gouge_free_tilt;
    use crate::autotilt::tests::{die_passes, opts};
    use crate::design::tests::die;
    use swarf_geom::Point3;
    use swarf_tool::Cutter;

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
        let design = DesignSurface::new(&die()).unwrap();
        let passes = die_passes();
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
            // Every alpha more than a tenth of a degree smaller gouges (sampled at a
            // quarter-degree scale): the answer is within a tenth of the smallest
            // gouge-free alpha (the predicate is not monotone to the resolution: on
            // iso-planar passes a few hundredths of a degree below an answer can be
            // free again).
            let mut b = 0.0;
            while b < a - tenth {
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
