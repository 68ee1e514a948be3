//! One level's regions cut in order (`regions.rs`): each leaf entered by a ramp,
//! each ring reached from the ring inside it by a step spread along that ring
//! (`moves.rs`), and stretches of rings that meet material only in places cut on
//! their own (`material.rs`).
//!
//! A loop the tool cannot step out to at the level (an island's ring, reached from
//! another loop of its region only across the island) starts a pass of its own: the
//! tool comes down onto the nearest loop already cut inside it, cleared all the way
//! up, and steps out from there; with none (a leaf's island) it ramps in along the
//! loop.

use super::material::{self, Reach};
use super::moves::{OnLoop, blend, ramp_entry};
use super::regions::{self, Region, Ring, cutting_order};
use super::{RoughingReport, RoughingStock, pass_of};
use swarf_toolpath::Pass;

/// The passes being made at one level.
struct Cutter<'a> {
    z: f64,
    above: f64,
    radius: f64,
    ramp_angle: f64,
    passes: &'a mut Vec<Pass>,
    report: &'a mut RoughingReport,
    /// The pass being made.
    current: Option<Vec<[f64; 3]>>,
}

impl Cutter<'_> {
    /// Ends the pass being made.
    fn flush(&mut self) {
        if let Some(pts) = self.current.take() {
            self.passes.push(pass_of(&pts));
        }
    }

    /// A new pass ramping into the level along `lp`.
    fn ramp<'r>(&mut self, lp: &'r Ring) -> OnLoop<'r> {
        self.flush();
        let mut pts = Vec::new();
        let at = ramp_entry(lp, self.above, self.z, self.ramp_angle, &mut pts);
        self.report.entries.push((self.passes.len(), pts.len()));
        self.current = Some(pts);
        at
    }

    /// A leaf's ring: ramped into, which cuts it all round.
    fn ring_entry<'r>(&mut self, lp: &'r Ring) -> OnLoop<'r> {
        self.report.rings += 1;
        self.ramp(lp)
    }

    /// Cuts `lp` all round from `at`'s ring by a spread step, or `None` when it is
    /// out of reach (nothing pushed).
    fn ring_from<'r>(&mut self, at: &OnLoop<'_>, lp: &'r Ring) -> Option<OnLoop<'r>> {
        let z = self.z;
        let pts = self.current.get_or_insert_with(Vec::new);
        let (seg, start) = blend(at, lp, z, self.radius, pts)?;
        pts.push([start[0], start[1], z]);
        let m = lp.len();
        for k in 1..=m {
            let p = lp[(seg + k) % m];
            pts.push([p[0], p[1], z]);
        }
        pts.push([start[0], start[1], z]);
        self.report.rings += 1;
        Some(OnLoop { lp, seg, p: start })
    }
}

/// Cuts one level's regions in order (module doc), appending passes.
pub(super) fn cut_level(
    regions: &[Region],
    z: f64,
    above: f64,
    stock: &RoughingStock<'_>,
    (radius, ramp_angle): (f64, f64),
    passes: &mut Vec<Pass>,
    report: &mut RoughingReport,
) {
    let mut cutter = Cutter {
        z,
        above,
        radius,
        ramp_angle,
        passes,
        report,
        current: None,
    };
    // The loops cut all round, by region.
    let mut cut: Vec<Vec<&Ring>> = vec![Vec::new(); regions.len()];
    // Where the tool stands on the loop it cut last.
    let mut at: Option<OnLoop<'_>> = None;
    for (i, fresh) in cutting_order(regions) {
        let mut live: Vec<&Ring> = Vec::new();
        let mut stretches: Vec<Ring> = Vec::new();
        for lp in &regions[i].loops {
            match material::reach(lp, z, radius, stock) {
                None => {}
                // A leaf is entered along its loop: cut whole.
                Some(Reach::Whole) => live.push(lp),
                Some(Reach::Stretches(_)) if fresh => live.push(lp),
                Some(Reach::Stretches(s)) => stretches.extend(s),
            }
        }
        if !stretches.is_empty() {
            // Each stretch is a pass of its own, coming down where it is clear.
            cutter.flush();
            at = None;
            cutter.report.rings += 1;
            for s in &stretches {
                let pts: Vec<[f64; 3]> = s.iter().map(|p| [p[0], p[1], z]).collect();
                cutter.passes.push(pass_of(&pts));
            }
        }
        for (n, lp) in live.into_iter().enumerate() {
            if fresh && n == 0 {
                at = Some(cutter.ring_entry(lp));
            } else if let Some(next) = at.and_then(|from| cutter.ring_from(&from, lp)) {
                at = Some(next);
            } else {
                at = Some(come_down(&mut cutter, regions, &cut, i, lp));
            }
            cut[i].push(lp);
        }
    }
    cutter.flush();
}

/// Cuts `lp` of region `i` in a pass of its own (module doc): from the nearest
/// loop cut in a child region, else by a ramp along it.
fn come_down<'r>(
    cutter: &mut Cutter<'_>,
    regions: &[Region],
    cut: &[Vec<&'r Ring>],
    i: usize,
    lp: &'r Ring,
) -> OnLoop<'r> {
    let nearest = (0..regions.len())
        .filter(|&c| regions[c].parent == Some(i))
        .flat_map(|c| cut[c].iter().copied())
        .filter_map(|inner| {
            let (seg, gap, p) = regions::distance_to_loop(inner, lp[0]);
            (gap <= cutter.radius).then_some((gap, OnLoop { lp: inner, seg, p }))
        })
        .min_by(|a, b| a.0.total_cmp(&b.0));
    if let Some((_, from)) = nearest {
        cutter.flush();
        cutter.current = Some(vec![[from.p[0], from.p[1], cutter.z]]);
        if let Some(next) = cutter.ring_from(&from, lp) {
            return next;
        }
    }
    cutter.ring_entry(lp)
}
