//! Three-axis gouge check of CL points against the whole part.
//!
//! Ball end mills are checked exactly against the patches ([`crate::gouge_ball`]);
//! other cutters through the mesh drop-cutter as below. Either way a CL point that
//! would enter the part by more than the tolerance is lifted along the axis to its
//! first contact and counted.
//!
//! # Other cutters: mesh drop-cutter
//!
//! A CL point is planned from one CC point and touches the surface there; elsewhere
//! (a concave region tighter than the cutter, a neighbouring patch of the envelope)
//! the cutter may still cut into the part. Every CL point is therefore tested against
//! the whole part, not its CC neighbourhood: the part is tessellated once within
//! `e = tolerance * MESH_FRACTION` and the exact mesh drop-cutter
//! ([`swarf_tool::drop::MeshDropper`]) gives the height `z_m` where the vertical
//! cutter first touches the mesh at the CL point's `(x, y)`.
//!
//! The sign of the tessellation error. The mesh lies within `e` of the surface, on
//! either side (chords under a convex region, over a concave one). The signed
//! distance to the tool is 1-Lipschitz, so the depth by which the cutter at height `z`
//! enters the true surface is at most its depth into the mesh plus `e`, and lowering
//! the cutter by `d` from `z_m` makes it enter the mesh by at most `d`. Hence:
//!
//! - a point with `z >= z_m - (tolerance - e)` enters the part by at most
//!   `tolerance - e + e = tolerance`: it is left alone;
//! - a point below that may enter the part by more than the tolerance: it is lifted
//!   along the axis to the first contact with the mesh, `z_m`, where it enters the true
//!   part by at most `e`, and counted ([`PathPoint::lifted`]).
//!
//! A correct CL point (touching the true surface only at its CC point) sits at most
//! `e / n_z` below `z_m` (the mesh above a concave region, seen along a normal with
//! vertical component `n_z`), so it is never lifted where `n_z > e / (tolerance - e)`,
//! i.e. on slopes below about 70 degrees with the fraction 1/4 used here. Using the
//! threshold `e` instead of `tolerance - e` would lift correct points on every
//! concave region (by up to `e / n_z`), and using no margin would miss gouges up to
//! `e` deep: neither is what the tolerance asks for.

use crate::error::PathError;
use crate::gouge_ball::BallGouge;
use rayon::prelude::*;
use swarf_geom::Part;
use swarf_tool::Cutter;
use swarf_tool::drop::{DropScratch, MeshDropper};
use swarf_toolpath::{Pass, PathPoint};

/// Tessellation tolerance of the gouge mesh as a fraction of the machining tolerance.
pub const MESH_FRACTION: f64 = 0.25;

/// The part prepared for gouge checks of one cutter.
#[derive(Debug, Clone)]
pub enum GougeCheck {
    /// Exact, for a ball end mill.
    Ball {
        /// The prepared part.
        ball: Box<BallGouge>,
        /// Machining tolerance, mm.
        tolerance: f64,
    },
    /// Through the mesh drop-cutter, for any cutter.
    Mesh {
        /// The tessellated part.
        dropper: Box<MeshDropper>,
        /// Its tessellation tolerance, mm.
        mesh_tolerance: f64,
        /// Machining tolerance, mm.
        tolerance: f64,
    },
}

/// What a gouge check did.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct GougeStats {
    /// CL points lifted.
    pub lifted: usize,
    /// Largest lift, mm.
    pub max_lift: f64,
}

impl GougeCheck {
    /// Prepares `part` for gouge checks of `cutter` at `tolerance`: exact for a ball,
    /// else a tessellation within `tolerance * MESH_FRACTION` for the drop-cutter.
    ///
    /// # Units
    /// mm.
    ///
    /// # Errors
    /// [`PathError::InvalidParameter`] on `tolerance` when it is not finite
    /// and > 0; [`PathError::Geom`] when the part cannot be tessellated.
    pub fn new(part: &Part, cutter: &Cutter, tolerance: f64) -> Result<GougeCheck, PathError> {
        if !(tolerance.is_finite() && tolerance > 0.0) {
            return Err(PathError::InvalidParameter {
                field: "tolerance".into(),
                message: format!("expected a finite number > 0, found {tolerance}"),
            });
        }
        if let Cutter::Ball { radius, .. } = cutter {
            return Ok(GougeCheck::Ball {
                ball: Box::new(BallGouge::new(part, *radius)),
                tolerance,
            });
        }
        let mesh_tolerance = tolerance * MESH_FRACTION;
        let mesh = part.tessellate(mesh_tolerance)?;
        Ok(GougeCheck::Mesh {
            dropper: Box::new(MeshDropper::new(&mesh, cutter)),
            mesh_tolerance,
            tolerance,
        })
    }

    /// The height where the vertical cutter first touches the part at `(x, y)`
    /// coming down from above, mm; `None` off the part.
    pub fn drop_z(&self, x: f64, y: f64, scratch: &mut DropScratch) -> Option<f64> {
        match self {
            GougeCheck::Ball { ball, .. } => ball.drop_z(x, y),
            GougeCheck::Mesh { dropper, .. } => {
                MeshDropper::drop(dropper, x, y, scratch).map(|d| d.z)
            }
        }
    }

    /// Checks one point (module doc); lifts it and returns the lift when it would
    /// enter the part by more than the tolerance.
    pub fn check(&self, p: &mut PathPoint, scratch: &mut DropScratch) -> Option<f64> {
        let cl = p.pose.cl;
        let z = match self {
            GougeCheck::Ball { ball, tolerance } => {
                if ball.penetration(&cl) <= *tolerance {
                    return None;
                }
                ball.first_contact(cl.x, cl.y, cl.z)
            }
            GougeCheck::Mesh {
                dropper,
                mesh_tolerance,
                tolerance,
            } => {
                let zm = MeshDropper::drop(dropper, cl.x, cl.y, scratch)?.z;
                if cl.z >= zm - (tolerance - mesh_tolerance) {
                    return None;
                }
                zm
            }
        };
        let lift = z - cl.z;
        p.pose.cl.z = z;
        p.lifted += lift;
        Some(lift)
    }

    /// Checks every point of `rows` (each a list of passes) in parallel
    /// (deterministic: each point is a pure function of the part and its position).
    pub fn apply(&self, rows: &mut [Vec<Pass>]) -> GougeStats {
        let per_pass: Vec<GougeStats> = rows
            .par_iter_mut()
            .flat_map(|row| row.par_iter_mut())
            .map_init(DropScratch::default, |scratch, pass| {
                let mut s = GougeStats::default();
                for p in &mut pass.points {
                    if let Some(lift) = self.check(p, scratch) {
                        s.lifted += 1;
                        s.max_lift = s.max_lift.max(lift);
                    }
                }
                s
            })
            .collect();
        per_pass
            .iter()
            .fold(GougeStats::default(), |a, s| GougeStats {
                lifted: a.lifted + s.lifted,
                max_lift: a.max_lift.max(s.max_lift),
            })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use swarf_geom::{Patch, Point3};
    use swarf_tool::Pose;

    /// A V-shaped valley `z = |x| * 0.5` over `[-10, 10] x [0, 10]`, as two planar
    /// patches, and a ball of radius 4 (tighter than the valley can take).
    fn valley() -> Part {
        let plane = |x0: f64, x1: f64| {
            let p = |x: f64, y: f64| Point3::new(x, y, 0.5 * x.abs());
            Patch::bezier(
                [1, 1],
                vec![p(x0, 0.0), p(x0, 10.0), p(x1, 0.0), p(x1, 10.0)],
            )
            .unwrap()
        };
        Part::new("valley", vec![plane(-10.0, 0.0), plane(0.0, 10.0)])
    }

    #[test]
    fn lifts_only_gouging_points_to_first_contact() {
        let part = valley();
        let check = GougeCheck::new(&part, &"ball:d=8".parse().unwrap(), 0.01).unwrap();
        assert!(matches!(check, GougeCheck::Ball { .. }));
        let check =
            GougeCheck::new(&part, &"taperball:d=8,angle=0,tip=4".parse().unwrap(), 0.01).unwrap();
        assert!(matches!(check, GougeCheck::Mesh { .. }));
        for cutter in ["ball:d=8", "taperball:d=8,angle=0,tip=4"] {
            let cutter: Cutter = cutter.parse().unwrap();
            valley_lifts(&part, &cutter);
        }
    }

    fn valley_lifts(part: &Part, cutter: &Cutter) {
        let check = GougeCheck::new(part, cutter, 0.01).unwrap();
        let mut scratch = DropScratch::default();
        // Touching the right flank at a CC point near the crease: the ball enters
        // the left flank. First contact on the axis x = 0: tip at r / cos(a) - r.
        let n = swarf_geom::Vec3::new(-0.5, 0.0, 1.0).normalize();
        let cc = Point3::new(1.0, 5.0, 0.5);
        let cl = cc + 4.0 * n - 4.0 * swarf_geom::Vec3::z();
        let mut p = PathPoint::new(Pose::vertical(cl));
        let lift = check
            .check(&mut p, &mut scratch)
            .expect("gouges the left flank");
        // Exact first contact with both flanks at this x: sphere centre at distance 4
        // from the plane z = -x/2 on the left: (z_c + x_c / 2) / |(0.5, 1)| = 4.
        let xc = cl.x;
        let want = 4.0 * (1.25f64).sqrt() - 0.5 * xc - 4.0;
        assert!(
            (p.pose.cl.z - want).abs() < 1e-9,
            "{} vs {want}",
            p.pose.cl.z
        );
        assert!((lift - (want - cl.z)).abs() < 1e-9);
        assert_eq!(p.lifted, lift);
        // Far from the crease the same construction touches one flank only.
        let cc = Point3::new(8.0, 5.0, 4.0);
        let mut q = PathPoint::new(Pose::vertical(cc + 4.0 * n - 4.0 * swarf_geom::Vec3::z()));
        assert!(check.check(&mut q, &mut scratch).is_none());
        assert_eq!(q.lifted, 0.0);
        // Slightly low (by less than the tolerance): left alone; by more: lifted.
        let mut low = q;
        low.pose.cl.z -= 0.005;
        assert!(check.check(&mut low, &mut scratch).is_none());
        low.pose.cl.z -= 0.01;
        assert!(check.check(&mut low, &mut scratch).is_some());
    }

    #[test]
    fn bad_tolerance_names_the_field() {
        let ball = Cutter::ball(8.0, None).unwrap();
        let e = GougeCheck::new(&valley(), &ball, 0.0)
            .unwrap_err()
            .to_string();
        let e2 = GougeCheck::new(&valley(), &ball, f64::NAN)
            .unwrap_err()
            .to_string();
        assert!(e2.starts_with("tolerance"), "{e2}");
        assert!(e.starts_with("tolerance"), "{e}");
    }
}
