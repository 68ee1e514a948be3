//! Rest samples: a pair of contact points with the material between them.
//!
//! Thesis 002 §5.1: where the tool touches the part at two separated points at once
//! (a double contact), the material between the contacts and the part under the tool
//! is left uncut; at a ramp limit the tool is held above the part between the two
//! ramp points. Both give a pair `(a, b)` of points on the part with the tool pose
//! above them, the sample the regions are built from (§5.2).
//!
//! **Depth.** The rest thickness of a pair is the largest distance from the part
//! surface between the contacts to the tool: over the part points `q` above the XY
//! segment `a b` (the part's height there), `max d(q)`, with `d` the exact distance to
//! the tool solid at its pose ([`swarf_tool::Profile::signed_distance`]). For a ball
//! of radius R in a V of included angle `alpha` the farthest part point is the
//! bottom of the V, at `R / sin(alpha/2) - R` (thesis 002 §1.1); in a fillet of
//! radius `rho < R` between a floor and a wall it is the fillet's point on the
//! bisector, at `(R - rho)(sqrt 2 - 1)`. The maximum is found by [`DEPTH_SAMPLES`]
//! even samples and a golden-section refinement around the best one (the distance
//! along the segment is unimodal for a valley: it rises from 0 at each contact).

use serde::Serialize;
use swarf_geom::solve::golden_max;
use swarf_geom::{Point3, Vec3};
use swarf_path::DoubleContact;
use swarf_tool::drop::MeshDropper;
use swarf_tool::{Pose, Profile};

/// Even samples of the part between the contacts in the depth search.
pub const DEPTH_SAMPLES: usize = 32;
/// A part point counts as under the tool up to this above its lower surface, mm.
pub const UNDER_TOL: f64 = 1e-6;
/// Golden-section steps of the depth refinement (the bracket shrinks by 0.618 each).
pub const DEPTH_STEPS: usize = 40;

/// What left the material.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum RestKind {
    /// The tool touches two sides of a valley at once (double contacts).
    Valley,
    /// The tool's ramp angle limit held it above the part (ramp points).
    Ramp,
    /// Found on the in-process stock: material above the design after the parent
    /// program(s).
    Stock,
}

/// A pair of contact points with the tool pose above them and the material between.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct RestPair {
    /// What left it.
    pub kind: RestKind,
    /// The tool tip (CL point), mm.
    pub cl: Point3,
    /// First contact, mm.
    pub a: Point3,
    /// Second contact, mm.
    pub b: Point3,
    /// Part normal at `a`.
    pub na: Vec3,
    /// Part normal at `b`.
    pub nb: Vec3,
    /// Rest thickness (module doc), mm.
    pub depth: f64,
    /// The part point where the thickness is largest, mm.
    pub deepest: Point3,
    /// The pass (or scan line) it was found on.
    pub pass: usize,
}

impl RestPair {
    /// XY midpoint of the two contacts, the point the spatial directory files it by.
    pub fn centre(&self) -> [f64; 2] {
        [0.5 * (self.a.x + self.b.x), 0.5 * (self.a.y + self.b.y)]
    }
}

/// Measures the rest under a tool pose (module doc).
pub struct DepthProbe<'a> {
    dropper: &'a MeshDropper,
    profile: Profile,
}

impl<'a> DepthProbe<'a> {
    /// A probe on the part and tool of `dropper`.
    pub fn new(dropper: &'a MeshDropper) -> DepthProbe<'a> {
        DepthProbe {
            dropper,
            profile: dropper.tool().cutter().profile(),
        }
    }

    /// The largest distance from the part between `a` and `b` (in XY) to the tool
    /// with its tip at `cl`, and the part point where it is reached; `(0, a)` when the
    /// part is not found between them.
    ///
    /// # Units
    /// mm.
    pub fn depth(&self, cl: &Point3, a: &Point3, b: &Point3) -> (f64, Point3) {
        let pose = Pose::vertical(*cl);
        let point = |t: f64| {
            let (x, y) = (a.x + t * (b.x - a.x), a.y + t * (b.y - a.y));
            self.dropper.surface_z(x, y).map(|z| Point3::new(x, y, z))
        };
        let env = self.dropper.tool().envelope();
        let dist = |t: f64| {
            point(t).map_or(f64::NEG_INFINITY, |q| {
                let rho = (q.x - cl.x).hypot(q.y - cl.y);
                let under = rho <= env.radius() && q.z <= cl.z + env.height(rho) + UNDER_TOL;
                if under {
                    self.profile.signed_distance(&pose, &q)
                } else {
                    f64::NEG_INFINITY
                }
            })
        };
        let n = DEPTH_SAMPLES;
        let (k, best) = (0..=n).map(|k| (k, dist(k as f64 / n as f64))).fold(
            (0, f64::NEG_INFINITY),
            |m, (k, v)| if v > m.1 { (k, v) } else { m },
        );
        let lo = k.saturating_sub(1) as f64 / n as f64;
        let hi = (k + 1).min(n) as f64 / n as f64;
        let mut t_best = k as f64 / n as f64;
        let mut v_best = best;
        if let Some((t, v)) = golden_max(dist, lo, hi, DEPTH_STEPS).best
            && v > v_best
        {
            (t_best, v_best) = (t, v);
        }
        match point(t_best) {
            Some(q) if v_best.is_finite() => (v_best.max(0.0), q),
            _ => (0.0, *a),
        }
    }

    /// The rest pair of a double contact (or of a pair of ramp points): its two
    /// farthest-apart contacts, with the depth between them; `None` with fewer than
    /// two contacts.
    pub fn valley(&self, dc: &DoubleContact) -> Option<RestPair> {
        let n = dc.contacts.len();
        let (i, j) = (0..n)
            .flat_map(|i| (i + 1..n).map(move |j| (i, j)))
            .max_by(|&(i, j), &(k, l)| {
                let d = |i: usize, j: usize| (dc.contacts[i] - dc.contacts[j]).norm();
                d(i, j).total_cmp(&d(k, l)).then((k, l).cmp(&(i, j)))
            })?;
        let (a, b) = (dc.contacts[i], dc.contacts[j]);
        let normal = |k: usize| dc.normals.get(k).copied().unwrap_or_else(Vec3::z);
        let (depth, deepest) = self.depth(&dc.cl, &a, &b);
        Some(RestPair {
            kind: if dc.ramp {
                RestKind::Ramp
            } else {
                RestKind::Valley
            },
            cl: dc.cl,
            a,
            b,
            na: normal(i),
            nb: normal(j),
            depth,
            deepest,
            pass: dc.pass,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use swarf_geom::TriMesh;
    use swarf_tool::drop::DropScratch;

    /// A V-groove along y with included angle `alpha`, bottom at z = 0 on x = 0.
    fn groove(alpha: f64) -> TriMesh {
        let s = 1.0 / (alpha / 2.0).tan();
        let p = |x: f64, y: f64| Point3::new(x, y, s * x.abs());
        TriMesh::from_triangles(&[
            [p(-20.0, -20.0), p(0.0, -20.0), p(0.0, 20.0)],
            [p(-20.0, -20.0), p(0.0, 20.0), p(-20.0, 20.0)],
            [p(0.0, -20.0), p(20.0, -20.0), p(20.0, 20.0)],
            [p(0.0, -20.0), p(20.0, 20.0), p(0.0, 20.0)],
        ])
    }

    #[test]
    fn depth_in_a_v_is_the_closed_form() {
        for deg in [60.0f64, 90.0, 120.0] {
            let alpha = deg.to_radians();
            let mesh = groove(alpha);
            let dropper = MeshDropper::new(&mesh, &"ball:d=12".parse().unwrap());
            let mut c = Vec::new();
            let hit = dropper
                .drop_with_contacts(0.0, 3.0, 1e-6, &mut DropScratch::default(), &mut c)
                .unwrap();
            assert_eq!(c.len(), 2, "{deg}");
            let probe = DepthProbe::new(&dropper);
            let cl = Point3::new(0.0, 3.0, hit.z);
            let (d, at) = probe.depth(&cl, &c[0].cc, &c[1].cc);
            let r = 6.0;
            let exact = r / (alpha / 2.0).sin() - r;
            assert!((d - exact).abs() < 1e-9, "{deg}: {d} vs {exact}");
            assert!(at.x.abs() < 1e-6 && at.z.abs() < 1e-6, "{at:?}");
        }
    }
}
