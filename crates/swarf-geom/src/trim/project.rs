//! The closest point of a part, its faces' trims respected.
//!
//! On a face, the closest point of its patch ([`Patch::project`]) is the answer when
//! it is inside the loops. Otherwise the closest point of the face lies on its
//! boundary (a minimum of the distance over a closed region is interior, where the
//! patch's unconstrained minimum would have been found, or on the boundary): the
//! loops' points mapped to 3D give the nearest vertex, and the two loop edges beside
//! it are searched by golden section on their `(u, v)` segment for the nearest surface
//! point. The part's answer is the nearest over its faces.

use crate::math::Point3;
use crate::part::Part;
use crate::patch::Patch;
use crate::solve::golden_max;
use crate::trim::{Trim, Uv};

/// A closest point on a face.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FacePoint {
    /// The face's index.
    pub face: usize,
    /// Parameters of the point on the face's patch.
    pub uv: Uv,
    /// The point, mm.
    pub point: Point3,
    /// Its distance from the query point, mm.
    pub distance: f64,
}

/// Golden-section iterations along a loop edge (the bracket shrinks to 0.618^n).
const EDGE_ITERATIONS: usize = 60;

impl Part {
    /// The closest point of the part to `p` over its faces, inside their trims; `None`
    /// for a part without faces or a non-finite `p`.
    ///
    /// # Units
    /// mm.
    pub fn project(&self, p: &Point3) -> Option<FacePoint> {
        if !p.coords.iter().all(|c| c.is_finite()) {
            return None;
        }
        (0..self.patches.len())
            .map(|k| project_face(&self.patches[k], self.trim(k), k, p))
            .min_by(|a, b| a.distance.total_cmp(&b.distance))
    }
}

/// The closest point of face `k` (module doc).
fn project_face(patch: &Patch, trim: Option<&Trim>, k: usize, p: &Point3) -> FacePoint {
    let pr = patch.project(p);
    let on = |uv: Uv, point: Point3| FacePoint {
        face: k,
        uv,
        point,
        distance: (point - p).norm(),
    };
    let Some(trim) = trim.filter(|t| !t.contains(pr.u, pr.v)) else {
        return on([pr.u, pr.v], pr.point);
    };
    let mut best = on([f64::NAN; 2], Point3::origin());
    best.distance = f64::INFINITY;
    let mut nearest = (0, 0);
    for (li, l) in trim.loops().iter().enumerate() {
        for (i, uv) in l.iter().enumerate() {
            let q = on(*uv, patch.eval(uv[0], uv[1]));
            if q.distance < best.distance {
                (best, nearest) = (q, (li, i));
            }
        }
    }
    let l = &trim.loops()[nearest.0];
    let i = nearest.1;
    for (a, b) in [
        (l[(i + l.len() - 1) % l.len()], l[i]),
        (l[i], l[(i + 1) % l.len()]),
    ] {
        let at = |t: f64| [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])];
        let g = golden_max(
            |t| {
                let uv = at(t);
                -(patch.eval(uv[0], uv[1]) - p).norm()
            },
            0.0,
            1.0,
            EDGE_ITERATIONS,
        );
        let Some((t, _)) = g.best else { continue };
        let uv = at(t);
        let q = on(uv, patch.eval(uv[0], uv[1]));
        if q.distance < best.distance {
            best = q;
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_point_over_a_hole_projects_to_its_rim_and_a_point_above_the_face_straight_down() {
        let q = |x: f64, y: f64| Point3::new(x, y, 0.0);
        let plate = Patch::bezier(
            [1, 1],
            vec![q(0.0, 0.0), q(0.0, 40.0), q(40.0, 0.0), q(40.0, 40.0)],
        )
        .unwrap();
        let hole: Vec<Uv> = (0..2000)
            .map(|k| {
                let t = std::f64::consts::TAU * k as f64 / 2000.0;
                [0.5 + 0.25 * t.cos(), 0.5 + 0.25 * t.sin()]
            })
            .collect();
        let outer = vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
        let mut part = Part::new("plate", vec![plate]);
        part.faces = vec![crate::part::Face {
            trim: Some(Trim::new(vec![outer, hole]).unwrap()),
            ..Default::default()
        }];
        // Above the hole, 3 mm off its centre, 4 mm up: the rim (radius 10) is
        // 7 mm away in xy, so sqrt(49 + 16) away.
        let r = part.project(&Point3::new(23.0, 20.0, 4.0)).unwrap();
        assert!((r.distance - 65f64.sqrt()).abs() < 1e-3, "{r:?}");
        assert!(
            (r.point - Point3::new(30.0, 20.0, 0.0)).norm() < 0.05,
            "{r:?}"
        );
        let r = part.project(&Point3::new(5.0, 5.0, 2.0)).unwrap();
        assert!(
            (r.distance - 2.0).abs() < 1e-12 && r.uv == [0.125, 0.125],
            "{r:?}"
        );
        assert!(part.project(&Point3::new(f64::NAN, 0.0, 0.0)).is_none());
    }
}
